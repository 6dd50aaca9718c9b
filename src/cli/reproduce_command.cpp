#include <fmt/format.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <thread>

#include "cli/input_error.hpp"
#include "cli/output_file.hpp"
#include "cli/plot_script.hpp"
#include "cli/store_analysis.hpp"
#include "cli/subcommand.hpp"
#include "cli/sweep_progress.hpp"
#include "cli/value_list.hpp"
#include "engines/engine.hpp"
#include "simulation/collapse_run.hpp"
#include "store/results_store.hpp"
#include "theory/collapse_theory.hpp"
#include "sweep/sweep_grid.hpp"
#include "sweep/sweep_runner.hpp"

namespace granchain {

namespace {

struct ReproduceFlags {
  std::string figure = "fig5", preset = "quick", db = "reproduce.db", out = "reproduce";
  int threads = 0;
  bool quiet = false;
};

int execute_reproduce(const std::shared_ptr<ReproduceFlags>& impl_);

// The paper's Fig. cfreqlogN25: n_coll(k, e) for N = 25 on its e grids (0.1 to 1.0 by 0.1, 0.80 to
// 0.90 by 0.01, 0.87 to 0.90 by 0.002); paper preset k = 1e5..1e10 and T = 1e4, quick preset
// k = 1e4..1e8 and T = 1000 (the asymptotic range starting one decade above the smallest k).
struct FigureGrid {
  std::string N, e, k, T;
  double k_min;
};
FigureGrid fig5_grid(const std::string& preset) {
  const std::string e = "0.1:1.0:0.1,0.80:0.90:0.01,0.87:0.90:0.002";
  if (preset == "paper") return {"25", e, "1e5:1e10:x10", "1e4", 1e6};
  return {"25", e, "1e4:1e8:x10", "1000", 1e5};
}
// Figs. cflogk and cfe: N = 3, 4, 5, 6, e = 0.05 .. 1.0 by 0.05, the same k and T as Fig. 5.
FigureGrid small_n_grid(const std::string& preset) {
  FigureGrid g = fig5_grid(preset);
  g.N = "3,4,5,6";
  g.e = "0.05:1.0:0.05";
  return g;
}

}  // namespace

Subcommand add_reproduce_command(CLI::App& app) {
  auto impl_ = std::make_shared<ReproduceFlags>();
  CLI::App* sub_ = app.add_subcommand("reproduce", "Run, analyse and draw a figure of the paper, with a report beside the paper's numbers.");
  sub_->footer(
      "fig5 (Fig. cfreqlogN25, N = 25): runs the sweep it needs into --db (points already stored are reused;\n"
      "a killed reproduction resumes), analyses it (granchain analyze), draws the panels (PNG and PDF) and\n"
      "writes a Markdown report that sets every measured number beside the paper's, into --out.\n"
      "Presets: quick (k = 1e4..1e8, T = 1000; minutes on two cores), paper (k = 1e5..1e10, T = 1e4).\n"
      "fig3, fig4 (Figs. cflogk, cfe): the same for N = 3, 4, 5, 6 and e = 0.05..1.0 by 0.05; panel (a) of each\n"
      "figure is n_coll against log k (Fig. cflogk), panel (c) n_coll against e with e_c(3)..e_c(N+1) dotted (Fig. cfe).\n"
      "fig10 (Fig. ntot): free-space collision counts n_tot(k) for N = 3 (e = 0.01, 0.03, 0.05, k = 1e4..1e14, with the\n"
      "predicted slopes) and N = 25 (e = 0.3, 0.5; quick k <= 1e7, paper k <= 1e10), report-fig10.md beside the theory.\n"
      "The other figures and Table 1 are not reproduced by this version yet.");
  sub_->add_option("--figure", impl_->figure, "fig3, fig4, fig5 or fig10 (the other figures: not yet)");
  sub_->add_option("--preset", impl_->preset, "quick (default) or paper");
  sub_->add_option("--db", impl_->db, "results store holding the runs; default reproduce.db")->type_name("FILE");
  sub_->add_option("--out", impl_->out, "folder for the figures and the report; default reproduce")->type_name("DIR");
  sub_->add_option("--threads", impl_->threads, "threads; default all cores");
  sub_->add_flag("--quiet,-q", impl_->quiet, "no progress");
  return {sub_, [impl_] { return execute_reproduce(impl_); }};
}

namespace {

// report.md for Fig. 5 (the main job's), report-<figure>.md for the others.
std::string report_name(const std::string& figure) { return figure == "fig5" ? "report.md" : "report-" + figure + ".md"; }

// Writes a whole output file, or reports why it could not (false).
bool write_output(const std::string& path, const std::string& text) {
  try {
    write_file_atomically(path, text, "--out");
    return true;
  } catch (const std::exception& e) {
    fmt::print(stderr, "granchain: error: {}\n", e.what());
    return false;
  }
}

int reproduce_fig10(const ReproduceFlags& o, int threads);

// Figures drawn from a driven-column sweep: fig3, fig4 (N = 3..6) and fig5 (N = 25).
int reproduce_driven(const ReproduceFlags& o) {
  std::vector<SweepPoint> points;
  FigureGrid grid;
  try {
    grid = o.figure == "fig5" ? fig5_grid(o.preset) : small_n_grid(o.preset);
    SweepDefinition def;
    def.raw["N"] = {grid.N, ""};
    def.raw["e"] = {grid.e, ""};
    def.raw["k"] = {grid.k, ""};
    def.raw["T"] = {grid.T, ""};
    points = build_sweep_points(def);
    ResultsStore::preflight(o.db);
    std::filesystem::create_directories(o.out);
    check_output_file((std::filesystem::path(o.out) / report_name(o.figure)).string(), "--out");
  } catch (const std::exception& e) {
    fmt::print(stderr, "granchain: error: {}\n", e.what());
    return kExitBadInput;
  }
  const int threads = o.threads > 0 ? o.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));

  // 1. The sweep (resumable: stored points are skipped).
  std::vector<std::string> failures;
  try {
    ResultsStore store(o.db);
    const std::vector<std::size_t> todo = points_to_run(points, store.point_keys());
    if (!o.quiet)
      fmt::print(stderr, "reproduce {} ({}): {} runs, {} already in {}, {} to run on {} threads\n", o.figure, o.preset,
                 points.size(), points.size() - todo.size(), o.db, todo.size(), threads);
    SweepRunner runner(points, todo, [&](const SweepPoint& p, const RunResult* r, const std::string& error) {
      if (r) store.insert_sweep_point(*r, p.key, 1, p.replica);
      else failures.push_back(p.key + ": " + error);
    });
    const bool tty = isatty(STDERR_FILENO) != 0;
    SweepProgressCallback cb;
    if (!o.quiet) cb = SweepProgressPrinter(tty, "reproduce");
    runner.run(threads, cb, tty ? 0.5 : 30.0);
  } catch (const StoreError& e) {
    fmt::print(stderr, "granchain: error: {}; repeat the command to resume\n", e.what());
    return kExitStoreFailed;
  }
  for (const auto& f : failures) fmt::print(stderr, "granchain: error: run turned unphysical, not stored: {}\n", f);

  // 2. Analysis, figure and report.
  ExportSelection sel;
  sel.values["N"] = parse_value_list(grid.N, "--N");
  sel.values["T0"] = {1};
  sel.values["k"] = parse_value_list(grid.k, "--k");
  sel.engines = {"exact"};
  StoreAnalysis a;
  try {
    a = analyze_store(o.db, sel, grid.k_min);
  } catch (const StoreError& e) {
    fmt::print(stderr, "granchain: error: {}\n", e.what());
    return kExitStoreFailed;
  }
  const std::string prefix = (std::filesystem::path(o.out) / o.figure).string();
  // Fig. cfe marks the free-space estimates e_c(3), ..., e_c(N + 1) (Sec. III.B) as dotted lines.
  if (o.figure != "fig5")
    for (auto& fam : a.json["families"]) {
      nlohmann::json lines = nlohmann::json::array();
      for (int n = 3; n <= fam["N"].get<int>() + 1; ++n) lines.push_back(theory::ec_free(n));
      fam["ec_lines"] = lines;
    }
  const std::string problem = draw_ncoll_panels(a, prefix);
  if (!problem.empty()) {
    fmt::print(stderr, "granchain: error: {}\n", problem);
    return kExitStoreFailed;
  }
  std::string md = fmt::format("# {} ({}), preset {}\n\n", o.figure,
                               o.figure == "fig5" ? "cfreqlogN25" : o.figure == "fig3" ? "cflogk" : "cfe", o.preset);
  md += fmt::format("Command: `granchain reproduce --figure {} --preset {}`. N = {}, k_B T0 = 1, exact engine, e = {}, k = {}, "
                    "T = {} (transient T/10), {} runs; fits over k >= {:g}. Figures: `{}_N<N>_T01_exact.png` (and .pdf): "
                    "panel (a) is Fig. cflogk, panel (c) Fig. cfe.\n\n",
                    o.figure, o.preset, grid.N, grid.e, grid.k, grid.T, a.runs, grid.k_min, o.figure);
  if (o.figure != "fig5") {
    md += "| N | e_c1 (b = 0) | e_c2 (convex/concave) | free-space e_c(N) | e_c(N+1) |\n|---|---|---|---|---|\n";
    for (const auto& f : a.report.families)
      md += fmt::format("| {} | {} | {} | {:.4f} | {:.4f} |\n", f.N, f.e_c1.found ? plus_minus(f.e_c1.value, f.e_c1.error, 4) : "not found",
                        f.e_c2.found ? fmt::format("{:.3f} – {:.3f}", f.e_c2.low, f.e_c2.high) : "not found",
                        theory::ec_free(f.N), theory::ec_free(f.N + 1));
    md += "\n";
  } else if (!a.report.families.empty()) {
    const auto& f = a.report.families.front();
    md += "| quantity | measured | paper |\n|---|---|---|\n";
    md += fmt::format("| e_c1 (b = 0) | {} | 0.894 |\n", f.e_c1.found ? plus_minus(f.e_c1.value, f.e_c1.error, 4) : "not found");
    md += fmt::format("| e_c2 (convex/concave) | {} | 0.878 – 0.884 |\n",
                      f.e_c2.found ? fmt::format("{:.3f} – {:.3f}", f.e_c2.low, f.e_c2.high) : "not found");
    md += fmt::format("| ᾱ (mean α at e = 0.1 … 0.4) | {} | 0.20 |\n", f.has_alpha_bar ? plus_minus(f.alpha_bar.value, f.alpha_bar.error, 3) : "-");
    std::string cond;
    const auto fc = a.condensation.find({f.engine, f.N, f.kT0});
    if (fc != a.condensation.end())
      for (const auto& [e, c] : fc->second)
        if (c.check.condensed && e > 0.7) cond += fmt::format("{}{:g}", cond.empty() ? "" : ", ", e);
    md += fmt::format("| K_i inversion (partially condensed), e > 0.7 | {} | 0.84 ≲ e ≲ 0.90 |\n\n", cond.empty() ? "none" : cond);
  }
  md += "Every (N, e): regime, slope b per decade of k, exponent α, curvature against log10 k, K_i inversion:\n\n```\n" +
        analysis_text(a) + "```\n";
  md += "\nCriteria and errors: docs/analysis.md. The quick preset's k range and time are far below the paper's; its numbers "
        "show the same three regimes, not the paper's precision.\n";
  const std::string report = (std::filesystem::path(o.out) / report_name(o.figure)).string();
  if (!write_output(report, md)) return kExitStoreFailed;
  fmt::print("figure: {}_N{}_T01_exact.png (and .pdf)\nreport: {}\nruns:   {}\n", prefix, o.figure == "fig5" ? "25" : "<N>",
             report, o.db);
  return failures.empty() ? kExitOk : kExitUnphysical;
}

int execute_reproduce(const std::shared_ptr<ReproduceFlags>& impl_) {
  const ReproduceFlags& o = *impl_;
  if (o.figure != "fig3" && o.figure != "fig4" && o.figure != "fig5" && o.figure != "fig10") {
    fmt::print(stderr, "granchain: error: --figure = '{}' is not available; valid: fig3, fig4, fig5, fig10 (the paper's other figures "
                       "are not reproduced by this version yet)\n", o.figure);
    return kExitBadInput;
  }
  if (o.preset != "quick" && o.preset != "paper") {
    fmt::print(stderr, "granchain: error: --preset = '{}' is not a preset; valid: quick, paper\n", o.preset);
    return kExitBadInput;
  }
  if (o.threads < 0 || o.threads > 1024) {
    fmt::print(stderr, "granchain: error: --threads = {} is out of range; valid range: 1 <= threads <= 1024\n", o.threads);
    return kExitBadInput;
  }
  const int threads = o.threads > 0 ? o.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return o.figure == "fig10" ? reproduce_fig10(o, threads) : reproduce_driven(o);
}

// The paper's Fig. ntot (Sec. III.D): collisions n_tot of a free-space collapse against k, for
// N = 3 below e_c(3) (with the predicted log-k slope) and N = 25 (a power of k).
int reproduce_fig10(const ReproduceFlags& o, int threads) {
  struct Series {
    int N;
    double e;
    std::string k;
    int realizations;
  };
  const bool paper = o.preset == "paper";
  std::vector<Series> series = {{3, 0.01, "1e4:1e14:x100", 1000}, {3, 0.03, "1e4:1e14:x100", 1000},
                                {3, 0.05, "1e4:1e14:x100", 1000}, {25, 0.3, paper ? "1e4:1e10:x10" : "1e4:1e7:x10", 200},
                                {25, 0.5, paper ? "1e4:1e10:x10" : "1e4:1e7:x10", 200}};
  try {
    ResultsStore::preflight(o.db);
    std::filesystem::create_directories(o.out);
    check_output_file((std::filesystem::path(o.out) / "report-fig10.md").string(), "--out");
  } catch (const std::exception& e) {
    fmt::print(stderr, "granchain: error: {}\n", e.what());
    return kExitBadInput;
  }
  nlohmann::json plot = {{"series", nlohmann::json::array()}};
  std::string md = fmt::format("# Fig. 10 (ntot), preset {}\n\nCommand: `granchain reproduce --figure fig10 --preset {}`. "
                               "Free-space launches of Sec. III.D (a = v0 = 1, dv0 = 0.1, stop rule `ends`), exact engine; "
                               "the same launches at every k, so slopes are paired per launch. Figure: `fig10.png` (and .pdf).\n\n",
                               o.preset, o.preset);
  std::string n3 = "| e | slope of n_tot per decade (last two k) | all collisions, -ln10/ln q | Eq. ntot-log |\n|---|---|---|---|\n";
  std::string n25 = "| e | k1 → k2 | n_tot(k2) | local α |\n|---|---|---|---|\n";
  try {
    ResultsStore store(o.db);
    for (const Series& s : series) {
      std::vector<CollapseResult> results;
      for (double k : parse_value_list(s.k, "--k")) {
        CollapseSpec spec;
        spec.params.N = s.N;
        spec.params.e = s.e;
        spec.params.k = k;
        spec.params.g = 0.0;
        spec.realizations = s.realizations;
        spec.threads = threads;
        if (!o.quiet) fmt::print(stderr, "reproduce fig10: N = {}, e = {:g}, k = {:g}, {} launches\n", s.N, s.e, k, s.realizations);
        results.push_back(run_collapse(spec));
        store.insert_collapse(results.back());
      }
      nlohmann::json js = {{"N", s.N}, {"e", s.e}, {"k", nlohmann::json::array()}, {"n_tot", nlohmann::json::array()},
                           {"error", nlohmann::json::array()}};
      for (const auto& r : results) {
        js["k"].push_back(r.spec.params.k);
        js["n_tot"].push_back(r.n_tot_mean);
        js["error"].push_back(r.n_tot_error);
      }
      if (s.N == 3) {
        const KSlope last = k_slope(results[results.size() - 2], results.back());
        const double per_decade = last.per_log10_k;  // k_slope: per decade of k already
        js["slope_per_decade"] = std::log(10.0) * theory::collisions_slope_per_ln_k(s.e);
        n3 += fmt::format("| {:g} | {:.3f} ± {:.3f} ({:g} → {:g}) | {:.4f} | {:.4f} |\n", s.e, per_decade,
                          last.error, last.k1, last.k2,
                          std::log(10.0) * theory::collisions_slope_per_ln_k(s.e), std::log(10.0) * theory::ntot_slope_per_ln_k(s.e));
      } else {
        for (std::size_t i = 0; i + 1 < results.size(); ++i) {
          const KSlope sl = k_slope(results[i], results[i + 1]);
          n25 += fmt::format("| {:g} | {:g} → {:g} | {:.1f} ± {:.1f} | {:.3f} ± {:.3f} |\n", s.e, sl.k1, sl.k2,
                             results[i + 1].n_tot_mean, results[i + 1].n_tot_error, sl.alpha, sl.alpha_error);
        }
      }
      plot["series"].push_back(js);
    }
  } catch (const StoreError& e) {
    fmt::print(stderr, "granchain: error: {}\n", e.what());
    return kExitStoreFailed;
  } catch (const UnphysicalStateError& e) {
    fmt::print(stderr, "granchain: error: a launch turned unphysical: {}\n", e.what());
    return kExitUnphysical;
  }
  const std::string prefix = (std::filesystem::path(o.out) / "fig10").string();
  if (!write_output(prefix + ".json", plot.dump(1) + "\n")) return kExitStoreFailed;
  const std::string problem = run_plot_script("ntot.py", {prefix + ".json", prefix});
  if (!problem.empty()) {
    fmt::print(stderr, "granchain: error: {}\n", problem);
    return kExitStoreFailed;
  }
  md += "## N = 3\n\nThe paper's Eq. ntot-log counts intervals between collisions of one pair; all collisions grow twice as "
        "fast (docs/collapse.md).\n\n" + n3 + "\n## N = 25\n\nThe paper: n_tot ∝ k^α with α ≈ 0.2 for e ≲ 0.6.\n\n" + n25;
  const std::string report = (std::filesystem::path(o.out) / "report-fig10.md").string();
  if (!write_output(report, md)) return kExitStoreFailed;
  fmt::print("figure: {}.png (and .pdf)\nreport: {}\nruns:   {}\n", prefix, report, o.db);
  return kExitOk;
}

}  // namespace

}  // namespace granchain
