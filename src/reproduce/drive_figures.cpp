// `granchain reproduce`, group `drives` (docs/drives.md): the paper's analysis of the collapse
// regimes repeated with the vibrating plates of the classical columns beside its thermal floor.
//   drives-onset     e_c1 and e_c2 against N for every drive, the fits 1 - e_c = A/N per drive, and
//                    whether one A fits all drives (the paper's summary: "the point where the system
//                    starts to condense is not sensitive to the driving mode")
//   drives-ncoll     n_coll(k) at N = 25 on every drive: the three regimes (panels of Fig. cfreqlogN25)
//   drives-profiles  the classical observables of a vibrated column: number density and granular
//                    temperature against height, the centre of mass and its velocity against the
//                    plate's phase
#include <fmt/format.h>

#include <cmath>
#include <map>
#include <numbers>

#include "analysis/column_profiles.hpp"
#include "model/plate_motion.hpp"
#include "reproduce/figures.hpp"
#include "simulation/trajectory.hpp"
#include "store/stored_rows.hpp"

namespace granchain {

namespace {

// The plates, all at omega = 10 and the same peak speed V = A omega (sine), A omega / pi (sawtooth),
// 4 A omega / pi (quadratic) = 1 = sqrt(k_B T0 / m) of the thermal floor at k_B T0 = 1, g = 1:
// amplitudes A << V^2 / g (Gamma = 10 for the sine, 8/pi^2 x 10 x pi/4 = 6.4 for the quadratic),
// the regime of the two papers where a plate acts on the column mainly through its speed.
struct DriveChoice {
  const char* drive;
  double A, omega;
  const char* published;  // the onset of condensation the classical papers give for that drive
};
constexpr double kPlateOmega = 10.0;
const std::vector<DriveChoice>& drive_choices() {
  static const std::vector<DriveChoice> d = {
      {"thermal", 0.0, 0.0, "2.6 (the paper, e_c1; 3.0 for e_c2)"},
      {"sine", 1.0 / kPlateOmega, kPlateOmega, "2.5 (Luding et al.)"},
      {"sawtooth", std::numbers::pi / kPlateOmega, kPlateOmega, "2.6 (Bernu et al.)"},
      {"quadratic", std::numbers::pi / (4 * kPlateOmega), kPlateOmega, "2.6 (Bernu et al.)"},
  };
  return d;
}

std::vector<int> drive_ns(const ReproduceFlags& o) {
  if (o.smoke()) return {10, 25};
  return {10, 20, 25, 30, 40, 50, 100};
}

GridBlock drive_block(const ReproduceFlags& o, const DriveChoice& d, int N) {
  GridBlock b{std::to_string(N), e_list_at_n_one_minus_e(N, critical_region_c()), preset_k(o), preset_T(o, N)};
  b.drive = d.drive;
  if (b.drive != "thermal") {
    b.A = fmt::format("{:.12g}", d.A);
    b.omega = fmt::format("{:.12g}", d.omega);
  }
  return b;
}

std::string grid_text(const ReproduceFlags& o, std::size_t runs) {
  std::string Ns;
  for (int N : drive_ns(o)) Ns += fmt::format("{}{}", Ns.empty() ? "" : ", ", N);
  return fmt::format("N = {}; e = 1 − c/N for {}; k = {} (fits over k ≥ {}), T = {} for N < 50 and {} for N ≥ 50 (transient T/10), "
                     "exact engine, k_B T0 = 1; plates at ω = {:g} with peak speed 1 (sine A = {:.4g}, Γ = {:.3g}; sawtooth A = {:.4g}; "
                     "quadratic A = {:.4g}, Γ = {:.3g}); {} runs",
                     Ns, critical_region_text(), preset_k(o), power_of_ten_text(preset_k_min(o)), preset_T(o, 20), preset_T(o, 50),
                     kPlateOmega, drive_choices()[1].A, drive_choices()[1].A * kPlateOmega * kPlateOmega, drive_choices()[2].A,
                     drive_choices()[3].A, gamma_factor(DriveKind::Quadratic) * drive_choices()[3].A * kPlateOmega * kPlateOmega, runs);
}

std::string drive_text(const DriveSpec& d) { return d.plate() ? drive_name(d.kind) : "thermal"; }

std::string e_text(const analysis::CriticalValue& c) { return c.found ? plus_minus(c.value, c.error, 4) : "not found"; }

// "2.52 ± 0.04" as c = N (1 - e) of a critical value.
std::string c_text(int N, const analysis::CriticalValue& c) {
  return c.found ? plus_minus(N * (1 - c.value), N * c.error, 2) : "not found";
}
std::string c_bracket_text(int N, const analysis::CriticalValue& c) {
  return c.found ? fmt::format("{:.2f} – {:.2f}", N * (1 - c.high), N * (1 - c.low)) : "not found";
}

struct AVariant {
  const char* key;
  const char* what;
  bool analysis::AcrossN::*has;
  analysis::InverseNFit analysis::AcrossN::*fit;
};
const std::vector<AVariant>& a_variants() {
  static const std::vector<AVariant> v = {
      {"A1", "e_c1 (b → 0)", &analysis::AcrossN::has_A1, &analysis::AcrossN::A1},
      {"A1_boundary", "classification boundary", &analysis::AcrossN::has_A1_boundary, &analysis::AcrossN::A1_boundary},
      {"A2", "e_c2 (convex by 2 errors / not)", &analysis::AcrossN::has_A2, &analysis::AcrossN::A2},
      {"A2_sign", "e_c2 (curvature changes sign)", &analysis::AcrossN::has_A2_sign, &analysis::AcrossN::A2_sign},
  };
  return v;
}

// Whether one A fits every drive: the weighted mean of the drives' A, its chi^2 on (drives - 1)
// dof, and each drive's pull from the mean. A drive's error is scaled by sqrt(chi^2 / dof) of its
// own fit where that exceeds 1 (the PDG's rule: points scattering beyond their errors about A/N).
std::string one_a_row(const std::vector<const analysis::AcrossN*>& across, const AVariant& v) {
  double sw = 0, swa = 0;
  std::vector<std::pair<std::string, analysis::InverseNFit>> fits;
  for (const analysis::AcrossN* x : across)
    if (x->*(v.has) && (x->*(v.fit)).A_error > 0) {
      analysis::InverseNFit f = x->*(v.fit);
      if (f.dof > 0 && f.chi2 > f.dof) f.A_error *= std::sqrt(f.chi2 / f.dof);
      fits.push_back({drive_text(x->drive), f});
      sw += 1 / (f.A_error * f.A_error);
      swa += f.A / (f.A_error * f.A_error);
    }
  if (fits.size() < 2) return fmt::format("| {} | fewer than two drives with a fit | | |\n", v.what);
  const double mean = swa / sw, err = 1 / std::sqrt(sw);
  double chi2 = 0;
  std::string pulls;
  for (const auto& [name, f] : fits) {
    const double pull = (f.A - mean) / f.A_error;
    chi2 += pull * pull;
    pulls += fmt::format("{}{} {:+.1f}", pulls.empty() ? "" : ", ", name, pull);
  }
  return fmt::format("| {} | {} | {:.1f} on {} dof | {} |\n", v.what, plus_minus(mean, err, 2), chi2, fits.size() - 1, pulls);
}

// The trajectories of drives-profiles: N = 25 at c = N(1 - e) = 1.2 (the fluid side of the critical
// region) and 4 (the power-law side, condensed), at one k, sampled every dt over [from, from + length].
struct ProfileWindow {
  double k, from, length, dt;
};
ProfileWindow profile_window(const ReproduceFlags& o) {
  if (o.smoke()) return {1e5, 10, 20, 0.01};
  if (o.paper()) return {1e8, 100, 4000, 0.02};
  return {1e7, 100, 1000, 0.01};
}
constexpr int kProfileN = 25;
const std::vector<double> kProfileC = {1.2, 4.0};
constexpr int kProfileBlocks = 20;  // batch means
constexpr int kPhaseBins = 24;
constexpr double kHeightBin = 1.0;  // in d: one particle per bin in a packed column (centres at i - 1/2)

nlohmann::json binned_json(const std::vector<analysis::BinnedValue>& v) {
  nlohmann::json value = nlohmann::json::array(), error = nlohmann::json::array();
  for (const auto& b : v) {
    value.push_back(b.measured ? nlohmann::json(b.value) : nlohmann::json(nullptr));
    error.push_back(b.measured ? nlohmann::json(b.error) : nlohmann::json(nullptr));
  }
  return {{"value", value}, {"error", error}};
}

DriveSpec drive_spec(const DriveChoice& d) {
  DriveSpec spec;
  find_drive(d.drive, spec.kind);
  spec.A = d.A;
  spec.omega = d.omega;
  return spec;
}

// Where the growth of n_coll with k happens: per (drive, e) at N = 25, the growth per decade of k
// between the fits' smallest k and the largest of the floor's (the plate's) hits per unit time and
// of the collisions per unit time of one pair contact on average (pp_rate / (N - 1)), and their
// ratio. A plate of restitution e can take part in a collapse like a pair contact (the bottom
// particle chattering on it: ratio near 1); the thermal floor, which launches particle 1 afresh at
// every hit, cannot (ratio near 0).
std::string growth_split_table(const std::string& db, const std::vector<SweepPoint>& points, double k_min) {
  ExportSelection sel;
  for (const SweepPoint& p : points) sel.point_keys.push_back(p.key);
  std::map<std::pair<std::string, double>, std::map<double, StoredRun>> by;  // (drive, e) -> k -> run
  for (StoredRun& r : read_runs(db, sel))
    if (r.spec.params.k >= k_min * (1 - 1e-9)) by[{drive_text(r.spec.drive), r.spec.params.e}][r.spec.params.k] = std::move(r);
  std::string t = "| drive | e | N(1 − e) | n_coll, growth per decade | floor or plate hits per unit time, growth per decade | "
                  "collisions of one pair contact per unit time, growth per decade | ratio floor / pair |\n|---|---|---|---|---|---|---|\n";
  for (const auto& [de, runs] : by) {
    if (runs.size() < 2) continue;
    const StoredRun& lo = runs.begin()->second;
    const StoredRun& hi = runs.rbegin()->second;
    const double decades = std::log10(hi.spec.params.k / lo.spec.params.k), N = lo.spec.params.N;
    const double floor_growth = (hi.floor_rate - lo.floor_rate) / decades,
                 floor_growth_err = std::hypot(hi.floor_rate_err, lo.floor_rate_err) / decades;
    const double pair_growth = (hi.pp_rate - lo.pp_rate) / ((N - 1) * decades),
                 pair_growth_err = std::hypot(hi.pp_rate_err, lo.pp_rate_err) / ((N - 1) * decades);
    // The ratio only where the pairs' growth is significant (3 errors).
    std::string ratio = "-";
    if (std::abs(pair_growth) > 3 * pair_growth_err && pair_growth_err > 0) {
      const double r = floor_growth / pair_growth;
      ratio = plus_minus(r, std::hypot(floor_growth_err, r * pair_growth_err) / std::abs(pair_growth), 2);
    }
    t += fmt::format("| {} | {:.4g} | {:.2g} | {} | {} | {} | {} |\n", de.first, de.second, N * (1 - de.second),
                     plus_minus((hi.n_coll - lo.n_coll) / decades, std::hypot(hi.n_coll_err, lo.n_coll_err) / decades, 3),
                     plus_minus(floor_growth, floor_growth_err, 3), plus_minus(pair_growth, pair_growth_err, 3), ratio);
  }
  return t;
}

std::string degrees(double rad, double err) { return plus_minus(rad * 180 / std::numbers::pi, err * 180 / std::numbers::pi, 0) + "°"; }

}  // namespace

std::vector<GridBlock> drives_grid(const ReproduceFlags& o) {
  std::vector<GridBlock> blocks;
  for (const DriveChoice& d : drive_choices())
    for (int N : drive_ns(o))
      if (o.figure != "drives-ncoll" || N == 25) blocks.push_back(drive_block(o, d, N));
  return blocks;
}

// e_c1 and e_c2 against N for every drive, the fits (1 - e_c) = A/N per drive, and one A for all.
FigureOutcome reproduce_drive_onset(const ReproduceFlags& o, ReproductionLog& log) {
  const std::vector<SweepPoint> points = grid_points(drives_grid(o));
  const std::vector<std::string> failed = run_missing_points(points, o, o.figure, log);
  const StoreAnalysis a = analyze_points(o.db, points, preset_k_min(o));
  nlohmann::json plot = {{"drives", nlohmann::json::array()}};
  std::string table = "| drive | N | N(1 − e_c1) (b → 0) | classification boundary in N(1 − e) | N(1 − e_c2) (convex by 2 errors / not) "
                      "| N(1 − e_c2) (curvature changes sign) | partially condensed at N(1 − e) |\n|---|---|---|---|---|---|---|\n";
  std::vector<const analysis::AcrossN*> across;
  std::string fits = "| drive | fit | A | χ² / dof | published onset |\n|---|---|---|---|---|\n";
  for (const DriveChoice& d : drive_choices()) {
    nlohmann::json dj = {{"drive", d.drive}, {"families", nlohmann::json::array()}};
    for (const auto& f : a.report.families) {
      if (drive_text(f.drive) != d.drive || f.kT0 != 1.0) continue;
      const std::vector<double> cond = condensed_es(a, f);
      const analysis::CriticalValue boundary = analysis::classification_boundary(f.e_c1_estimate);
      dj["families"].push_back({{"N", f.N}, {"e_c1", critical_json(f.e_c1)}, {"e_c2", critical_json(f.e_c2)},
                                {"e_c2_sign", critical_json(f.e_c2_sign)}, {"boundary", critical_json(boundary)}, {"condensed_e", cond}});
      std::string cond_text = "none";
      if (!cond.empty()) cond_text = fmt::format("{:.2f} – {:.2f}", f.N * (1 - cond.back()), f.N * (1 - cond.front()));
      table += fmt::format("| {} | {} | {} | {} | {} | {} | {} |\n", d.drive, f.N, c_text(f.N, f.e_c1), c_bracket_text(f.N, boundary),
                           c_bracket_text(f.N, f.e_c2), c_text(f.N, f.e_c2_sign), cond_text);
    }
    for (const auto& x : a.report.across)
      if (drive_text(x.drive) == d.drive && x.kT0 == 1.0 && x.engine == EngineKind::Exact) {
        across.push_back(&x);
        for (const AVariant& v : a_variants()) {
          if (!(x.*(v.has))) continue;
          const analysis::InverseNFit& fit = x.*(v.fit);
          dj[v.key] = {{"A", fit.A}, {"error", fit.A_error}};
          fits += fmt::format("| {} | 1 − {} = A/N | {} | {:.1f} / {} | {} |\n", d.drive, v.what, plus_minus(fit.A, fit.A_error, 2),
                              fit.chi2, fit.dof, d.published);
        }
      }
    plot["drives"].push_back(dj);
  }
  std::string one = "| A of | weighted mean over the drives | χ² of one A | pulls (A − mean) / error |\n|---|---|---|---|\n";
  for (const AVariant& v : a_variants()) one += one_a_row(across, v);
  const std::string drawn = draw_figure(o, "drives-onset", plot, "drive_onset.py");
  FigureOutcome out{failed.empty() ? FigureStatus::Done : FigureStatus::PointsFailed, "", drawn, a.run_seconds, "", failed};
  out.markdown = fmt::format("Command: `{}`. {}. Figure: `drives-onset.png` (and .pdf): N(1 − e_c) against N per drive, "
                             "the fits 1 − e_c = A/N as horizontal lines.\n\n",
                             reproduce_command_line(o), grid_text(o, a.runs));
  out.markdown += "Critical values per drive and N, as c = N(1 − e) (the paper's A for a single N):\n\n" + table;
  out.markdown += "\nThe fits per drive (the k window of every fit: the preset's, above; the published onsets are for hard "
                  "spheres and their own observables):\n\n" + fits;
  out.markdown += "\nOne A for every drive? The drives' A against their weighted mean, each A's error scaled by √(χ²/dof) of its "
                  "own fit where that exceeds 1 (a χ² much larger than its dof says no):\n\n" + one;
  out.markdown += excluded_markdown(a);
  return out;
}

// n_coll(k) at N = 25 on every drive, the panels of Fig. cfreqlogN25 per drive.
FigureOutcome reproduce_drive_ncoll(const ReproduceFlags& o, ReproductionLog& log) {
  const std::vector<SweepPoint> points = grid_points(drives_grid(o));
  const std::vector<std::string> failed = run_missing_points(points, o, o.figure, log);
  const StoreAnalysis a = analyze_points(o.db, points, preset_k_min(o));
  const std::string prefix = output_path(o, "drives-ncoll");
  const std::string problem = draw_ncoll_panels(a, prefix, "--out");
  if (!problem.empty()) throw OutputError(problem);
  FigureOutcome out{failed.empty() ? FigureStatus::Done : FigureStatus::PointsFailed, "", prefix + "_N25_*.png (and .pdf), one per drive",
                    a.run_seconds, "", failed};
  out.markdown = fmt::format("Command: `{}`. The N = 25 points of drives-onset's grid ({}). Figures: `drives-ncoll_N25_T01_exact.png` (the thermal "
                             "floor) and `drives-ncoll_N25_T01_exact_<drive>_A<A>_w<ω>.png` (and .pdf), the panels of Fig. "
                             "cfreqlogN25 for each drive.\n\n",
                             reproduce_command_line(o), grid_text(o, a.runs));
  std::string table = "| drive | e_c1 | e_c2 (curvature changes sign) | regimes on the grid (uncollapsing / logarithmic / power law) |\n"
                      "|---|---|---|---|\n";
  for (const auto& f : a.report.families) {
    std::map<analysis::Regime, int> counts;
    for (const auto& c : f.curves)
      if (c.classified) ++counts[c.c.regime];
    table += fmt::format("| {} | {} | {} | {} / {} / {} |\n", drive_text(f.drive), e_text(f.e_c1), e_text(f.e_c2_sign), counts[analysis::Regime::Uncollapsing],
                         counts[analysis::Regime::Logarithmic], counts[analysis::Regime::PowerLaw]);
  }
  out.markdown += table;
  out.markdown += fmt::format("\nWhere the growth happens, between k = {} and the largest k, per decade: of n_coll, of the "
                              "floor's or plate's hits per unit time, and of the collisions per unit time of one pair contact "
                              "(all pairs' over N − 1); errors from the two runs' blocking errors. A plate of restitution e can "
                              "take part in a collapse as a pair contact does (the bottom particle chattering on it: a ratio near "
                              "1); the thermal floor, which launches particle 1 afresh at every hit, cannot (near 0).\n\n",
                              power_of_ten_text(preset_k_min(o)));
  out.markdown += growth_split_table(o.db, points, preset_k_min(o));
  out.markdown += "\nEvery (drive, e): regime, slope b per decade of k, exponent α, curvature, K_i inversion:\n\n```\n" +
                  analysis_text(a) + "```\n" + excluded_markdown(a);
  return out;
}

// The classical observables of the vibrated column beside the thermal floor's: n(z), T(z), and
// the centre of mass and its velocity through the plate's cycle.
FigureOutcome reproduce_drive_profiles(const ReproduceFlags& o, ReproductionLog&) {
  const ProfileWindow w = profile_window(o);
  nlohmann::json plot = {{"N", kProfileN}, {"k", w.k}, {"columns", nlohmann::json::array()}};
  std::string table = "| drive | N(1 − e) | e | ⟨z_cm⟩ | m⟨v²⟩ (all particles) | z_cm: first harmonic, at θ | v_cm: first harmonic, at θ |\n"
                      "|---|---|---|---|---|---|---|\n";
  for (const double c : kProfileC)
    for (const DriveChoice& d : drive_choices()) {
      TraceSpec spec;
      spec.run.params.N = kProfileN;
      spec.run.params.e = 1 - c / kProfileN;
      spec.run.params.k = w.k;
      spec.run.drive = drive_spec(d);
      spec.run.seed = 1;
      spec.t_from = w.from;
      spec.t_to = w.from + w.length;
      spec.dt = w.dt;
      const Trajectory tr = record_trajectory(spec);
      double top = 0;
      std::vector<double> zcm, v2;
      for (std::size_t s = 0; s < tr.z.size(); ++s) {
        double z = 0, vv = 0;
        for (std::size_t i = 0; i < tr.z[s].size(); ++i) {
          top = std::max(top, tr.z[s][i]);
          z += tr.z[s][i] / kProfileN;
          vv += spec.run.params.m * tr.v[s][i] * tr.v[s][i] / kProfileN;
        }
        zcm.push_back(z);
        v2.push_back(vv);
      }
      const int bins = static_cast<int>(std::ceil(top / kHeightBin)) + 1;
      const analysis::HeightProfiles h = analysis::height_profiles(tr.z, tr.v, spec.run.params.m, 0.0, kHeightBin, bins, kProfileBlocks);
      const analysis::BinnedValue z_mean = analysis::batch_mean(zcm, kProfileBlocks), t_mean = analysis::batch_mean(v2, kProfileBlocks);
      nlohmann::json col = {{"drive", d.drive}, {"c", c}, {"e", spec.run.params.e}, {"z", h.z}, {"density", binned_json(h.density)},
                            {"temperature", binned_json(h.temperature)}, {"z_cm", z_mean.value}};
      std::string harmonics = "- | -";
      if (d.A > 0) {
        const analysis::PhaseProfiles p =
            analysis::phase_profiles(tr.z, tr.v, tr.plate_phase, tr.plate, tr.plate_v, kPhaseBins, kProfileBlocks);
        col["phase"] = {{"theta", p.theta}, {"z_cm", binned_json(p.z_cm)}, {"v_cm", binned_json(p.v_cm)},
                        {"z_plate", binned_json(p.z_plate)}, {"v_plate", binned_json(p.v_plate)}};
        // The first harmonics of z_cm and v_cm: amplitude and the phase theta of their maximum
        // (the plate's own: z_p highest at 90 degrees for the sine and the quadratic arcs, at 360 for
        // the sawtooth; v_p largest at 0 for the sine and the quadratic, constant on the sawtooth).
        const analysis::Harmonic hz = analysis::first_harmonic(p.theta, p.z_cm), hv = analysis::first_harmonic(p.theta, p.v_cm);
        if (hz.measured && hv.measured) {
          const auto turn = [](double x) { return x - 2 * std::numbers::pi * std::floor(x / (2 * std::numbers::pi)); };  // [0, 2 pi)
          harmonics = fmt::format("{} at {} | {} at {}", plus_minus(hz.amplitude, hz.amplitude_error, 4), degrees(turn(hz.phase), hz.phase_error),
                                  plus_minus(hv.amplitude, hv.amplitude_error, 4), degrees(turn(hv.phase), hv.phase_error));
          col["harmonic"] = {{"z_amplitude", hz.amplitude}, {"z_phase", turn(hz.phase)}, {"v_amplitude", hv.amplitude},
                             {"v_phase", turn(hv.phase)}};
        }
      }
      plot["columns"].push_back(col);
      table += fmt::format("| {} | {:g} | {:.3f} | {} | {} | {} |\n", d.drive, c, spec.run.params.e, plus_minus(z_mean.value, z_mean.error, 3),
                           plus_minus(t_mean.value, t_mean.error, 4), harmonics);
    }
  const std::string drawn = draw_figure(o, "drives-profiles", plot, "drive_profiles.py");
  FigureOutcome out{FigureStatus::Done, "", drawn, -1.0, "", {}};
  out.markdown = fmt::format(
      "Command: `{}`. N = {}, k = {}, exact engine, seed 1, each drive of drives-onset (plates at ω = {:g}, peak speed 1), at "
      "N(1 − e) = 1.2 (the fluid side of the critical region) and 4 (the power-law side), sampled every {:g} over {:g} ≤ t ≤ {:g}; errors "
      "are batch means over {} blocks. Figure: `drives-profiles.png` (and .pdf): number density n(z) and granular temperature "
      "T(z) = m⟨(v − u(z))²⟩ in bins of {:g} d, and through the plate's cycle (θ in {} bins) the centre of mass z_cm − ⟨z_cm⟩ and "
      "its velocity beside the plate's.\n\n",
      reproduce_command_line(o), kProfileN, power_of_ten_text(w.k), kPlateOmega, w.dt, w.from, w.from + w.length, kProfileBlocks,
      kHeightBin, kPhaseBins);
  out.markdown += table;
  out.markdown += "\nThe harmonics are the first Fourier components in θ of the phase-binned means (attenuated by the bins' "
                  "width, sin(π/24)/(π/24) = 0.997), with the θ of their maximum. The plate's own: z_p is highest at θ = 90° (sine, "
                  "quadratic arcs) or just before 360° (sawtooth, which then drops), v_p largest at θ = 0 (sine, quadratic) or constant "
                  "(sawtooth).\n";
  return out;
}

}  // namespace granchain
