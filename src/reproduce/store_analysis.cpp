#include "reproduce/store_analysis.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <array>
#include <map>
#include <cmath>
#include <set>
#include <tuple>

#include "reproduce/plot_script.hpp"
#include "config/run_key.hpp"
#include "store/results_store.hpp"
#include "store/store_export.hpp"
#include "store/stored_rows.hpp"
#include "sweep/cost_model.hpp"
#include "theory/equilibrium_column.hpp"

namespace granchain {

namespace {

// The partially condensed state of every (engine, N, T0, e) from the profiles of its runs at the
// largest k stored (replicas combined per particle by weighted mean), against the elastic
// column's sigma_0,i (theory/equilibrium_column) at the same N, k, T0.
std::map<FamilyKey, std::map<double, Condensation>> condensation_by_family(const std::string& db, ExportSelection sel,
                                                                          const std::set<std::int64_t>& left_out,
                                                                          const EnginePool& pool) {
  // (engine, N, T0, e) -> k -> particle -> sums for K and sigma: w, w K, w sigma (weights 1/err^2)
  std::map<FamilyKey, std::map<double, std::map<double, std::map<int, std::array<double, 4>>>>> acc;
  std::map<std::tuple<int, double, double>, ChainParameters> params;
  for (const StoredProfile& row : read_profiles(db, sel)) {
    // Hard spheres (no finite k) have no place on the k axis; profiles without errors carry no weight.
    if (row.setup != "driven_column" || !std::isfinite(row.spec.params.k) || std::isnan(row.K_err) || std::isnan(row.z_std_err) ||
        left_out.count(row.run_id))
      continue;
    const double kerr = row.K_err, serr = row.z_std_err;
    if (!(kerr > 0) || !(serr > 0)) continue;
    const FamilyKey key = family_key(row.spec, pool);
    const double e = row.spec.params.e, k = row.spec.params.k;
    auto& a = acc[key][e][k][row.i];
    a[0] += 1.0 / (kerr * kerr);
    a[1] += row.K_mean / (kerr * kerr);
    a[2] += 1.0 / (serr * serr);
    a[3] += row.z_std / (serr * serr);
    ChainParameters p = row.spec.params;
    p.e = 1.0;
    params[{p.N, p.kT0, k}] = p;
  }
  std::map<FamilyKey, std::map<double, Condensation>> out;
  for (const auto& [key, by_e] : acc)
    for (const auto& [e, by_k] : by_e) {
      const auto& [k, particles] = *by_k.rbegin();  // the largest k
      if (static_cast<int>(particles.size()) != std::get<2>(key) || particles.size() < 3) continue;
      std::vector<analysis::ParticleValue> K, sigma;
      for (const auto& [i, a] : particles) {
        K.push_back({a[1] / a[0], 1.0 / std::sqrt(a[0])});
        sigma.push_back({a[3] / a[2], 1.0 / std::sqrt(a[2])});
      }
      std::vector<double> sigma0;  // the elastic column on the thermal floor: none for a plate
      try {
        if (!std::get<1>(key).plate()) sigma0 = elastic_column_equilibrium(params.at({std::get<2>(key), std::get<3>(key), k})).z_std;
      } catch (const std::exception&) {
        sigma0.clear();  // no closed form for this column: the sigma ratio is left out
      }
      out[key][e] = {k, analysis::detect_partial_condensation(K, sigma, sigma0), K, sigma, sigma0};
    }
  return out;
}

}  // namespace

// The check of the blocking errors by independent replicas (null where no point has two runs).
nlohmann::json replica_check_json(const analysis::FamilyAnalysis& f) {
  const ReplicaScatter& r = f.replicas;
  if (r.groups == 0) return nullptr;
  return {{"points", r.groups}, {"runs", r.runs}, {"chi2", r.chi2}, {"dof", r.dof}, {"chi2_z", r.chi2_z},
          {"worst_chi2_per_dof", r.worst_ratio}, {"worst_e", f.replicas_worst_e}, {"worst_k", f.replicas_worst_k}};
}

nlohmann::json critical_json(const analysis::CriticalValue& c) {
  if (!c.found) return nullptr;
  return {{"value", c.value}, {"error", c.error}, {"low", c.low}, {"high", c.high}, {"method", c.method}};
}

nlohmann::json e_c1_json(const analysis::E_c1Estimate& x) {
  nlohmann::json j = critical_json(x.e_c1);
  if (j.is_null()) j = nlohmann::json::object();
  j["statistical"] = x.e_c1.found ? nlohmann::json(x.statistical) : nlohmann::json(nullptr);
  j["systematic"] = x.e_c1.found ? nlohmann::json(x.systematic) : nlohmann::json(nullptr);
  j["variants"] = x.variants;
  j["variants_found"] = x.variants_found;
  j["residual_b"] = x.residual_b;
  j["residual_b_err"] = x.residual_b_error;
  j["boundary"] = x.has_boundary ? nlohmann::json{{"last_collapsing_e", x.last_collapsing_e},
                                                  {"first_uncollapsing_e", x.first_uncollapsing_e},
                                                  {"isolated_collapsing_e", x.isolated_collapsing_e}}
                                 : nlohmann::json(nullptr);
  return j;
}

std::string power_of_ten_text(double k) {
  if (!(k > 0) || !std::isfinite(k)) return fmt::format("{:g}", k);
  const double p = std::round(std::log10(k));
  return std::abs(k - std::pow(10.0, p)) <= 1e-9 * k ? fmt::format("1e{:g}", p) : fmt::format("{:g}", k);
}

std::string local_exponents_text(const std::vector<analysis::LocalExponent>& l) {
  std::string out;
  for (const auto& x : l)
    out += fmt::format("{}{}–{}: {}", out.empty() ? "" : ", ", power_of_ten_text(x.k1), power_of_ten_text(x.k2),
                       plus_minus(x.alpha, x.error));
  return out.empty() ? "-" : out;
}

nlohmann::json local_exponents_json(const std::vector<analysis::LocalExponent>& l) {
  nlohmann::json j = nlohmann::json::array();
  for (const auto& x : l) j.push_back({{"k1", x.k1}, {"k2", x.k2}, {"alpha", x.alpha}, {"error", x.error}});
  return j;
}

std::string cost_markdown(const std::vector<RunCost>& costs) {
  struct Sums {
    int runs = 0, within_2 = 0;
    double seconds = 0, predicted = 0, log_ratio = 0;
  };
  std::map<int, Sums> by_n;
  for (const RunCost& c : costs) {
    if (!(c.seconds > 0) || !(c.predicted > 0)) continue;  // a run stored without a time says nothing
    Sums& s = by_n[c.N];
    const double r = c.seconds / c.predicted;
    ++s.runs;
    s.seconds += c.seconds;
    s.predicted += c.predicted;
    s.log_ratio += std::log(r);
    if (r >= 0.5 && r <= 2.0) ++s.within_2;
  }
  if (by_n.empty()) return "";
  std::string md =
      "| N | runs | measured CPU-hours | predicted CPU-hours | measured / predicted (sums) | geometric mean of the runs' ratios | "
      "within a factor of 2 |\n|---|---|---|---|---|---|---|\n";
  for (const auto& [N, s] : by_n)
    md += fmt::format("| {} | {} | {:.3g} | {:.3g} | {:.2f} | {:.2f} | {} of {} |\n", N, s.runs, s.seconds / 3600, s.predicted / 3600,
                      s.seconds / s.predicted, std::exp(s.log_ratio / s.runs), s.within_2, s.runs);
  return md;
}

std::string plus_minus(double v, double e, int digits) {
  if (!std::isfinite(v)) return "-";
  return fmt::format("{:.{}f} ± {:.{}f}", v, digits, e, digits);
}

namespace {

// drive, plate_A, plate_omega of a family, as a run's JSON has them (null under the thermal floor).
void put_drive(nlohmann::json& j, const DriveSpec& d) {
  j["drive"] = d.plate() ? nlohmann::json(drive_name(d.kind)) : nlohmann::json(nullptr);
  j["plate_A"] = d.plate() ? nlohmann::json(d.A) : nlohmann::json(nullptr);
  j["plate_omega"] = d.plate() ? nlohmann::json(d.omega) : nlohmann::json(nullptr);
}

}  // namespace

StoreAnalysis analyze_store(const std::string& db, const ExportSelection& selection, double k_min, const EnginePool& pool) {
  ExportSelection sel = selection;
  sel.table = ExportTable::Runs;
  StoreAnalysis a;
  a.k_min = k_min;
  a.pool = pool;
  std::vector<analysis::NcollRun> runs;
  const std::vector<StoredRun> rows = read_runs(db, sel);
  for (const StoredRun& row : rows) {
    if (row.setup != "driven_column") continue;
    // The run's thread CPU time where stored (not stretched by a loaded machine), else its wall time.
    const double seconds = std::isnan(row.cpu_seconds) ? row.wall_seconds : row.cpu_seconds;
    a.run_seconds += seconds;
    a.costs.push_back({row.spec.params.N, seconds, estimate_cost_seconds(row.spec)});
    analysis::NcollRun run;
    run.engine = pool.family_engine(row.spec.engine.kind);
    run.drive = row.spec.drive;
    run.N = row.spec.params.N;
    run.kT0 = row.spec.params.kT0;
    run.e = row.spec.params.e;
    run.k = std::isfinite(row.spec.params.k) ? row.spec.params.k : std::nan("");  // hard spheres: no point on the k axis
    run.n_coll = row.n_coll;
    run.n_coll_err = row.n_coll_err;
    run.stationary = row.stationary.value_or(true);  // runs stored before the check count as stationary
    run.run_id = row.id;
    run.trajectory = trajectory_key(row.spec);  // config/run_key.hpp
    run.T = row.spec.T;
    run.transient = row.spec.transient;
    runs.push_back(run);
  }
  a.runs = runs.size();
  a.report = analysis::analyze_runs(runs, k_min);
  std::set<std::int64_t> left_out;
  for (const auto& x : a.report.excluded) left_out.insert(x.run_id);
  a.blocking_checks = blocking_against_replicas(db, rows, left_out, pool);
  a.condensation = condensation_by_family(db, sel, left_out, pool);
  nlohmann::json& j = a.json;
  j = {{"k_min", k_min}, {"runs", a.runs}, {"families", nlohmann::json::array()}, {"across_N", nlohmann::json::array()}};
  for (const auto& f : a.report.families) {
    nlohmann::json curves = nlohmann::json::array();
    for (const auto& c : f.curves) {
      nlohmann::json pts = nlohmann::json::array();
      for (const auto& p : c.n_coll_of_k) pts.push_back({{"k", p.x}, {"n_coll", p.y}, {"error", p.error}});
      nlohmann::json cj = {{"e", c.e}, {"n_coll_of_k", pts}, {"classified", c.classified},
                           {"non_stationary_k", c.non_stationary_k}};
      if (c.classified) {
        cj["regime"] = analysis::regime_name(c.c.regime);
        cj["log_fit"] = {{"a", c.c.log_fit.a}, {"a_err", c.c.log_fit.a_error}, {"b", c.c.log_fit.b}, {"b_err", c.c.log_fit.b_error},
                         {"chi2", c.c.log_fit.chi2}, {"dof", c.c.log_fit.dof}};
        cj["power_fit"] = {{"c", c.c.power_fit.c}, {"c_err", c.c.power_fit.c_error}, {"alpha", c.c.power_fit.alpha},
                           {"alpha_err", c.c.power_fit.alpha_error}, {"chi2", c.c.power_fit.chi2}, {"dof", c.c.power_fit.dof}};
        cj["curvature"] = {{"value", c.c.curvature}, {"error", c.c.curvature_error}};
        // The local exponent per interval of k beside the global alpha: how the slope drifts.
        cj["local_exponents"] = local_exponents_json(analysis::local_exponents(c.n_coll_of_k));
      }
      const auto fc = a.condensation.find({f.engine, f.drive, f.N, f.kT0});
      if (fc != a.condensation.end() && fc->second.count(c.e)) {
        const Condensation& pc = fc->second.at(c.e);
        cj["partial_condensation"] = {{"k", pc.k}, {"condensed", pc.check.condensed},
                                      {"state", analysis::condensed_state_name(pc.check.state)},
                                      {"K_hot_particle", pc.check.hot}, {"K_cooler_above_particle", pc.check.cooler_above},
                                      {"K_hot_drop", pc.check.hot_drop}, {"K_hot_drop_err", pc.check.hot_drop_error},
                                      {"K_dip_particle", pc.check.dip},
                                      {"K_rise", pc.check.rise}, {"K_rise_err", pc.check.rise_error},
                                      {"z_threshold", pc.check.z},
                                      {"sigma_ratio_min", pc.check.sigma_dip ? nlohmann::json(pc.check.sigma_ratio_min) : nlohmann::json(nullptr)},
                                      {"sigma_ratio_min_particle", pc.check.sigma_dip}};
        nlohmann::json prof = {{"K", nlohmann::json::array()}, {"K_err", nlohmann::json::array()},
                               {"sigma", nlohmann::json::array()}, {"sigma_err", nlohmann::json::array()},
                               {"sigma0", pc.sigma0}};
        for (std::size_t i = 0; i < pc.K.size(); ++i) {
          prof["K"].push_back(pc.K[i].value);
          prof["K_err"].push_back(pc.K[i].error);
          prof["sigma"].push_back(pc.sigma[i].value);
          prof["sigma_err"].push_back(pc.sigma[i].error);
        }
        cj["profile"] = prof;
      }
      curves.push_back(cj);
    }
    j["families"].push_back({{"engine", pool.label(f.engine)}, {"N", f.N}, {"T0", f.kT0}, {"curves", curves}, {"e_c1", critical_json(f.e_c1)},
                             {"e_c1_estimate", e_c1_json(f.e_c1_estimate)},
                             {"local_alpha_bar", local_exponents_json(f.local_alpha_bar)},
                             {"e_c2", critical_json(f.e_c2)},
                             {"e_c2_curvature_sign", critical_json(f.e_c2_sign)},
                             {"replica_check", replica_check_json(f)},
                             {"blocking_check", a.blocking_checks.count({f.engine, f.drive, f.N, f.kT0})
                                                    ? curve_scatter_json(a.blocking_checks.at({f.engine, f.drive, f.N, f.kT0}))
                                                    : nlohmann::json(nullptr)},
                             {"alpha_bar", f.has_alpha_bar ? nlohmann::json{{"value", f.alpha_bar.value}, {"error", f.alpha_bar.error}}
                                                           : nlohmann::json(nullptr)}});
    put_drive(j["families"].back(), f.drive);
  }
  j["excluded"] = nlohmann::json::array();
  for (const auto& x : a.report.excluded) {
    j["excluded"].push_back({{"run_id", x.run_id}, {"engine", pool.label(x.engine)}, {"N", x.N}, {"T0", x.kT0}, {"e", x.e},
                             {"k", std::isfinite(x.k) ? nlohmann::json(x.k) : nlohmann::json(nullptr)}, {"reason", x.reason}});
    put_drive(j["excluded"].back(), x.drive);
  }
  for (const auto& a : a.report.across) {
    auto inv = [](bool has, const analysis::InverseNFit& f) {
      return has ? nlohmann::json{{"A", f.A}, {"A_err", f.A_error}, {"chi2", f.chi2}, {"dof", f.dof}} : nlohmann::json(nullptr);
    };
    j["across_N"].push_back({{"engine", pool.label(a.engine)}, {"T0", a.kT0}, {"A_ec1", inv(a.has_A1, a.A1)}, {"A_ec2", inv(a.has_A2, a.A2)},
                             {"A_boundary", inv(a.has_A1_boundary, a.A1_boundary)}, {"A_ec2_curvature_sign", inv(a.has_A2_sign, a.A2_sign)},
                             {"alpha_vs_log10_N", a.has_alpha_fit ? nlohmann::json{{"slope", a.alpha_fit.slope},
                                                                                   {"slope_err", a.alpha_fit.slope_error},
                                                                                   {"intercept", a.alpha_fit.intercept},
                                                                                   {"intercept_err", a.alpha_fit.intercept_error}}
                                                                  : nlohmann::json(nullptr)}});
    nlohmann::json lines = nlohmann::json::array();
    for (const analysis::LocalAlphaLine& l : a.local_alpha_lines) {
      lines.push_back({{"k1", l.k1}, {"k2", l.k2}, {"N", l.Ns}, {"slope", l.fit.slope}, {"slope_err", l.fit.slope_error},
                       {"intercept", l.fit.intercept}, {"intercept_err", l.fit.intercept_error}, {"chi2", l.fit.chi2}, {"dof", l.fit.dof}});
      nlohmann::json slopes = nlohmann::json::array();
      for (const analysis::NeighbourSlope& n : l.neighbour_slopes)
        slopes.push_back({{"N1", n.N1}, {"N2", n.N2}, {"slope", n.slope}, {"slope_err", n.error}, {"e_count", n.e_count}});
      lines.back()["same_e_neighbour_slopes"] = std::move(slopes);
      if (l.has_excess) {
        nlohmann::json per_e = nlohmann::json::array();
        for (const analysis::DataPoint& p : l.excess.per_e) per_e.push_back({{"e", p.x}, {"excess", p.y}, {"error", p.error}});
        lines.back()["same_e_largest_N_excess"] = {{"N", l.excess.N},          {"others", l.excess.others}, {"excess", l.excess.excess},
                                                   {"error", l.excess.error},  {"per_e", per_e}};
      } else {
        lines.back()["same_e_largest_N_excess"] = nullptr;
      }
    }
    j["across_N"].back()["local_alpha_vs_log10_N"] = std::move(lines);
    put_drive(j["across_N"].back(), a.drive);
  }
  return a;
}

namespace {

// The slopes between neighbouring columns and the largest column's excess over the line through
// the others, each at the same e on both sides (analysis/alpha_across_n.hpp).
std::string same_e_text(const analysis::LocalAlphaLine& l) {
  std::string out;
  if (!l.neighbour_slopes.empty()) {
    out += "    same e: d alpha / d log10 N between neighbours";
    for (const analysis::NeighbourSlope& n : l.neighbour_slopes)
      out += fmt::format(" {}→{} {}{}", n.N1, n.N2, plus_minus(n.slope, n.error), &n == &l.neighbour_slopes.back() ? "" : ",");
    out += "\n";
  }
  if (l.has_excess) {
    std::string per_e;
    for (const analysis::DataPoint& p : l.excess.per_e)
      per_e += fmt::format("{}e = {:g}: {:+.3f} ± {:.3f}", per_e.empty() ? "" : ", ", p.x, p.y, p.error);
    out += fmt::format("    same e: N = {} minus the line through N = {}: {:+.3f} ± {:.3f} ({})\n", l.excess.N,
                       fmt::join(l.excess.others, ", "), l.excess.excess, l.excess.error, per_e);
  }
  return out;
}

}  // namespace

std::string excluded_text(const std::vector<analysis::ExcludedRun>& excluded, const EnginePool& pool) {
  if (excluded.empty()) return "";
  // Runs left out for one reason at one (engine, drive, N, T0, e, k), named together.
  std::map<std::tuple<std::string, EngineKind, int, double, double, double, DriveSpec>, std::vector<std::int64_t>> groups;
  for (const auto& x : excluded) groups[{x.reason, x.engine, x.N, x.kT0, x.e, x.k, x.drive}].push_back(x.run_id);
  std::string out = fmt::format("left out of the analysis: {} run{}\n", excluded.size(), excluded.size() == 1 ? "" : "s");
  for (const auto& [g, ids] : groups) {
    std::string list;
    for (std::int64_t id : ids) list += fmt::format("{}{}", list.empty() ? "" : ", ", id);
    out += fmt::format("  engine {}{}, N = {}, T0 = {:g}, e = {:g}, k = {:g}: run{} {}: {}\n", pool.label(std::get<1>(g)),
                       drive_label(std::get<6>(g)), std::get<2>(g), std::get<3>(g), std::get<4>(g), std::get<5>(g),
                       ids.size() == 1 ? "" : "s", list, std::get<0>(g));
  }
  return out;
}

std::string excluded_markdown(const StoreAnalysis& a) {
  const std::string text = excluded_text(a.report.excluded, a.pool);
  return text.empty() ? "" : "\nRuns the analysis could not use (granchain analyze lists them the same way):\n\n```\n" + text + "```\n";
}

std::string analysis_text(const StoreAnalysis& a) {
  std::string out;
  out += fmt::format("{} runs; asymptotic range k >= {}\n", a.runs, power_of_ten_text(a.k_min));
  out += excluded_text(a.report.excluded, a.pool);
  for (const auto& f : a.report.families) {
    out += fmt::format("\nengine {}{}, N = {}, T0 = {:g}\n", a.pool.label(f.engine), drive_label(f.drive), f.N, f.kT0);
    out += fmt::format("{:>8} {:>4} {:>14} {:>20} {:>16} {:>22}  {}\n", "e", "k's", "regime", "b (per decade)", "alpha", "curvature",
               "K_i inversion (at largest k)");
    const auto fc = a.condensation.find({f.engine, f.drive, f.N, f.kT0});
    auto inversion = [&](double e) -> std::string {
      if (fc == a.condensation.end() || !fc->second.count(e)) return "-";
      const auto& ch = fc->second.at(e).check;
      if (!ch.condensed) return "no";
      if (ch.state == analysis::CondensedState::Partial)
        return fmt::format("partial: dip at {}, rise {}; hot layer at {}, cooler at {} by {}", ch.dip,
                           plus_minus(ch.rise, ch.rise_error), ch.hot, ch.cooler_above, plus_minus(ch.hot_drop, ch.hot_drop_error));
      return fmt::format("whole: dip at {}, rise {}", ch.dip, plus_minus(ch.rise, ch.rise_error));
    };
    std::string unsettled;  // (e, k) of runs whose window failed the stationarity check
    for (const auto& c : f.curves)
      for (double k : c.non_stationary_k) unsettled += fmt::format("{}(e = {:g}, k = {:g})", unsettled.empty() ? "" : ", ", c.e, k);
    for (const auto& c : f.curves) {
      if (!c.classified) {
        out += fmt::format("{:>8.4g} {:>4} {:>14}\n", c.e, c.n_coll_of_k.size(), "(too few k)");
        continue;
      }
      out += fmt::format("{:>8.4g} {:>4} {:>14} {:>20} {:>16} {:>22}  {}\n", c.e, c.n_coll_of_k.size(), analysis::regime_name(c.c.regime),
                 plus_minus(c.c.log_fit.b, c.c.log_fit.b_error), plus_minus(c.c.power_fit.alpha, c.c.power_fit.alpha_error),
                 plus_minus(c.c.curvature, c.c.curvature_error, 4), inversion(c.e) + (c.non_stationary_k.empty() ? "" : "  [!]"));
    }
    if (!unsettled.empty())
      out += fmt::format("  [!] window not stationary (n_coll or the mean height differ between its halves by > 3 errors; "
                         "run longer or with a longer transient): {}\n", unsettled);
    if (fc != a.condensation.end()) {
      std::string partial, whole;
      const analysis::CondensationCheck& any = fc->second.begin()->second.check;  // one N: one z for the family
      for (const auto& [e, pc] : fc->second) {
        std::string& list = pc.check.state == analysis::CondensedState::Partial ? partial : whole;
        if (pc.check.condensed) list += fmt::format("{}{:g}", list.empty() ? "" : ", ", e);
      }
      out += fmt::format("  K_i inversion (rise > z = {:.2f} standard errors, z set by the {} pairs compared): partially condensed "
                         "(interior hot layer, Fig. partial_cond) at e = {}; condensed as a whole (only the surface warmer) at e = {}\n",
                         any.z, any.pairs, partial.empty() ? "none" : partial, whole.empty() ? "none" : whole);
    }
    out += fmt::format("  e_c1 = {}   e_c2 = {}   alpha bar (e = 0.1..0.4) = {}\n",
               f.e_c1.found ? plus_minus(f.e_c1.value, f.e_c1.error, 4) : "not found",
               f.e_c2.found ? fmt::format("{:.4g} .. {:.4g}", f.e_c2.low, f.e_c2.high) : "not found",
               f.has_alpha_bar ? plus_minus(f.alpha_bar.value, f.alpha_bar.error) : "-");
    if (!f.local_alpha_bar.empty())
      out += fmt::format("    local alpha per interval of k (mean over e = 0.1..0.4): {}\n", local_exponents_text(f.local_alpha_bar));
    const analysis::E_c1Estimate& x = f.e_c1_estimate;
    if (f.e_c1.found)
      out += fmt::format("    e_c1: {:.4f} ± {:.4f} (statistical) ± {:.4f} (systematic, {} of {} variants, range {:.4f} .. {:.4f}); "
                         "finite-k slope of the uncollapsing side b_res = {}\n",
                         f.e_c1.value, x.statistical, x.systematic, x.variants_found, x.variants, f.e_c1.low, f.e_c1.high,
                         plus_minus(x.residual_b, x.residual_b_error, 4));
    if (x.has_boundary) {
      std::string isolated;
      for (double e : x.isolated_collapsing_e) isolated += fmt::format("{}{:g}", isolated.empty() ? "" : ", ", e);
      out += fmt::format("    classification boundary: last collapsing e = {:g}, first uncollapsing e = {:g}{}\n",
                         x.last_collapsing_e, x.first_uncollapsing_e,
                         isolated.empty() ? "" : "; isolated collapsing e above it (taken as b = 0): " + isolated);
    }
    if (f.e_c2_sign.found)
      out += fmt::format("    e_c2 where the curvature changes sign (the paper's reading, no significance asked): {} (between {:g} and {:g})\n",
                         plus_minus(f.e_c2_sign.value, f.e_c2_sign.error, 4), f.e_c2_sign.low, f.e_c2_sign.high);
    const ReplicaScatter& r = f.replicas;
    if (r.groups > 0)
      out += fmt::format("    blocking errors against independent replicas: {} points with {} runs, chi2/dof = {:.1f}/{} = {:.2f} "
                         "(z = {:.1f}; about 1 when the errors are right); largest chi2/dof {:.2f} at e = {:g}, k = {:g}\n",
                         r.groups, r.runs, r.chi2, r.dof, r.chi2 / r.dof, r.chi2_z, r.worst_ratio, f.replicas_worst_e,
                         f.replicas_worst_k);
    if (const auto b = a.blocking_checks.find({f.engine, f.drive, f.N, f.kT0}); b != a.blocking_checks.end()) {
      out += "    the replicas that keep blocking curves, level by level (chi2/dof about (n - 1)/(n - 3) with n blocks, 1.15 at 16, where blocks of that length see the scatter):\n";
      for (const auto& [k, s] : b->second) out += "      " + curve_scatter_text(k, s) + "\n";
    }
  }
  const EnginePool& pool = a.pool;
  for (const auto& a : a.report.across) {
    if (!(a.has_A1 || a.has_A2 || a.has_A1_boundary || a.has_A2_sign || a.has_alpha_fit || !a.local_alpha_lines.empty())) continue;
    out += fmt::format("\nacross N (engine {}{}, T0 = {:g}):", pool.label(a.engine), drive_label(a.drive), a.kT0);
    if (a.has_A1) out += fmt::format("  1 - e_c1 = A/N with A = {}", plus_minus(a.A1.A, a.A1.A_error, 2));
    if (a.has_A2) out += fmt::format("  1 - e_c2 = A/N with A = {}", plus_minus(a.A2.A, a.A2.A_error, 2));
    if (a.has_A1_boundary)
      out += fmt::format("  1 - (classification boundary) = A/N with A = {}", plus_minus(a.A1_boundary.A, a.A1_boundary.A_error, 2));
    if (a.has_A2_sign)
      out += fmt::format("  1 - e_c2 (curvature changes sign) = A/N with A = {}", plus_minus(a.A2_sign.A, a.A2_sign.A_error, 2));
    if (a.has_alpha_fit)
      out += fmt::format("  alpha bar = ({}) log10 N + ({})", plus_minus(a.alpha_fit.slope, a.alpha_fit.slope_error),
                 plus_minus(a.alpha_fit.intercept, a.alpha_fit.intercept_error));
    out += fmt::format("\n");
    for (const analysis::LocalAlphaLine& l : a.local_alpha_lines)
      out += fmt::format("  local alpha {}–{} = ({}) log10 N + ({}), chi2/dof = {:.1f}/{} over N = {}\n", power_of_ten_text(l.k1), power_of_ten_text(l.k2),
                         plus_minus(l.fit.slope, l.fit.slope_error), plus_minus(l.fit.intercept, l.fit.intercept_error), l.fit.chi2,
                         l.fit.dof, fmt::join(l.Ns, ", "))
             + same_e_text(l);
  }
  return out;
}

namespace {

// The file name, without extension, of one (engine, drive, N, T0)'s panels; plots/ncoll_panels.py takes it
// from the JSON ("stem").
std::string panel_stem(const std::string& prefix, const nlohmann::json& family) {
  std::string stem = fmt::format("{}_N{}_T0{:g}_{}", prefix, family.at("N").get<int>(), family.at("T0").get<double>(),
                                 family.at("engine").get<std::string>());
  if (family.contains("drive") && family.at("drive").is_string())
    stem += fmt::format("_{}_A{:g}_w{:g}", family.at("drive").get<std::string>(), family.at("plate_A").get<double>(),
                        family.at("plate_omega").get<double>());
  return stem;
}

}  // namespace

std::vector<std::string> ncoll_panel_files(const StoreAnalysis& a, const std::string& prefix) {
  std::vector<std::string> files = {prefix + ".json"};
  for (const auto& f : a.json.at("families")) {
    files.push_back(panel_stem(prefix, f) + ".png");
    files.push_back(panel_stem(prefix, f) + ".pdf");
  }
  return files;
}

std::string draw_ncoll_panels(const StoreAnalysis& a, const std::string& prefix, const std::string& option) {
  nlohmann::json j = a.json;
  for (auto& f : j.at("families")) f["stem"] = panel_stem(prefix, f);
  try {
    write_file_atomically(prefix + ".json", j.dump(1) + "\n", option);
  } catch (const std::exception& e) {
    return e.what();
  }
  return run_plot_script("ncoll_panels.py", {prefix + ".json", prefix});
}

}  // namespace granchain
