// `granchain reproduce` for the driven column at fixed N: Figs. cflogk and cfe (N = 3..6),
// cfreqlogN25 (N = 25) and partial_cond (N = 25, the profiles at the largest k).
#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "analysis/condensation.hpp"
#include "reproduce/figures.hpp"
#include "theory/collapse_theory.hpp"

namespace granchain {

namespace {

// Fig. cfreqlogN25's e grids: 0.1 to 1.0 by 0.1, 0.80 to 0.90 by 0.01, 0.87 to 0.90 by 0.002.
const char* kFig5E = "0.1:1.0:0.1,0.80:0.90:0.01,0.87:0.90:0.002";

std::string fig5_table(const StoreAnalysis& a) {
  if (a.report.families.empty()) return "";
  const auto& f = a.report.families.front();
  std::string md = "| quantity | measured | paper |\n|---|---|---|\n";
  md += fmt::format("| e_c1 (b → 0, statistical and systematic error) | {} | 0.894 |\n",
                    f.e_c1.found ? plus_minus(f.e_c1.value, f.e_c1.error, 4) : "not found");
  const analysis::E_c1Estimate& x = f.e_c1_estimate;
  md += fmt::format("| classification boundary (last collapsing e – first uncollapsing e) | {} | 0.894 |\n",
                    x.has_boundary ? fmt::format("{:.4f} – {:.4f}", x.last_collapsing_e, x.first_uncollapsing_e) : "not found");
  md += fmt::format("| e_c2 (convex/concave) | {} | 0.878 – 0.884 |\n",
                    f.e_c2.found ? fmt::format("{:.3f} – {:.3f}", f.e_c2.low, f.e_c2.high) : "not found");
  md += fmt::format("| e_c2 (curvature changes sign: the paper's reading) | {} | 0.878 – 0.884 |\n",
                    f.e_c2_sign.found ? plus_minus(f.e_c2_sign.value, f.e_c2_sign.error, 4) : "not found");
  md += fmt::format("| ᾱ (mean α at e = 0.1 … 0.4) | {} | 0.20 |\n", f.has_alpha_bar ? plus_minus(f.alpha_bar.value, f.alpha_bar.error, 3) : "-");
  md += fmt::format("| local α per interval of k, mean over e = 0.1 … 0.4 (ᾱ averages these) | {} | – |\n",
                    local_exponents_text(f.local_alpha_bar));
  std::string partial, whole;
  const auto fc = a.condensation.find({f.engine, f.drive, f.N, f.kT0});
  if (fc != a.condensation.end())
    for (const auto& [e, c] : fc->second) {
      if (!c.check.condensed || e <= 0.7) continue;
      std::string& list = c.check.state == analysis::CondensedState::Partial ? partial : whole;
      list += fmt::format("{}{:g}", list.empty() ? "" : ", ", e);
    }
  md += fmt::format("| partially condensed (K_i dip, interior hot layer above), e > 0.7 | {} | 0.84 ≲ e ≲ 0.90 |\n",
                    partial.empty() ? "none" : partial);
  md += fmt::format("| condensed as a whole (K_i dip, only the surface warmer), e > 0.7 | {} | e ≲ 0.84 |\n\n",
                    whole.empty() ? "none" : whole);
  return md;
}

std::string small_n_table(const StoreAnalysis& a) {
  std::string md = "| N | e_c1 (b = 0) | e_c2 (convex/concave) | free-space e_c(N) | e_c(N+1) |\n|---|---|---|---|---|\n";
  for (const auto& f : a.report.families)
    md += fmt::format("| {} | {} | {} | {:.4f} | {:.4f} |\n", f.N, f.e_c1.found ? plus_minus(f.e_c1.value, f.e_c1.error, 4) : "not found",
                      f.e_c2.found ? fmt::format("{:.3f} – {:.3f}", f.e_c2.low, f.e_c2.high) : "not found",
                      theory::ec_free(f.N), theory::ec_free(f.N + 1));
  return md + "\n";
}

}  // namespace

// Figs. cflogk, cfe: e = 0.05 ... 1.0 by 0.05, refined around each free-space critical value
// e_c(n), n = 3 ... 7 (= N + 1 for the largest N), by +-0.005 and +-0.01, where the paper finds
// peaks, dips and shoulders of n_coll(e).
std::string small_n_e_grid() {
  std::string e = "0.05:1.0:0.05";
  for (int n = 3; n <= 7; ++n)
    for (double d : {-0.01, -0.005, 0.0, 0.005, 0.01}) e += fmt::format(",{:.4f}", theory::ec_free(n) + d);
  return e;
}

std::vector<GridBlock> ncoll_grid(const ReproduceFlags& o) {
  if (o.figure == "fig5") return {{"25", kFig5E, preset_k(o), preset_T(o, 25)}};
  // The smoke preset checks the pipeline only: the coarse grid and one seed. The others run two
  // independent seeds per point, to show that the fine structure is reproducible (Sec. III.B).
  if (o.smoke()) return {{"3,4,5,6", "0.05:1.0:0.05", preset_k(o), preset_T(o, 3)}};
  GridBlock b{"3,4,5,6", small_n_e_grid(), preset_k(o), preset_T(o, 3)};
  b.replicas = 2;
  return {b};
}
std::vector<GridBlock> partial_condensation_grid(const ReproduceFlags& o) {
  return {{"25", "0.82:0.92:0.01,1.0", preset_k_max(o), preset_T(o, 25)}};
}

// Figs. cflogk, cfe (fig3, fig4: one sweep over N = 3..6, e = 0.05..1.0 by 0.05 refined around
// each e_c(n); fig3.png draws it against log k, fig4.png against e, plots/small_n.py) and
// cfreqlogN25 (fig5: N = 25 on the paper's e grids, the panels of plots/ncoll_panels.py), at the
// preset's k and T.
FigureOutcome reproduce_ncoll_figure(const ReproduceFlags& o, ReproductionLog& log) {
  const bool fig5 = o.figure == "fig5";
  const GridBlock grid = ncoll_grid(o).front();
  const std::vector<SweepPoint> points = grid_points({grid});
  const auto failures = run_missing_points(points, o, o.figure, log);
  StoreAnalysis a = analyze_points(o.db, points, preset_k_min(o));
  // Fig. cfreqlogN25 marks the paper's own e_c1 = 0.894 and 0.878 < e_c2 < 0.884 (N = 25, T0 = 1).
  if (fig5)
    for (auto& fam : a.json["families"])
      if (fam["N"] == 25 && fam["T0"] == 1.0) fam["paper"] = {{"e_c1", 0.894}, {"e_c2_low", 0.878}, {"e_c2_high", 0.884}};
  // Fig. cfe marks the free-space estimates e_c(3), ..., e_c(N + 1) (Sec. III.B) as dotted lines.
  if (!fig5)
    for (auto& fam : a.json["families"]) {
      nlohmann::json lines = nlohmann::json::array();
      for (int n = 3; n <= fam["N"].get<int>() + 1; ++n) lines.push_back(theory::ec_free(n));
      fam["ec_lines"] = lines;
    }
  FigureOutcome out;
  if (fig5) {  // the panels of `analyze --plot` for N = 25: fig5_N25_T01_exact.png
    const std::string prefix = output_path(o, o.figure);
    const std::string problem = draw_ncoll_panels(a, prefix, "--out");
    if (!problem.empty()) throw std::runtime_error(problem);
    out.drawn = prefix + "_N25_T01_exact.png (and .pdf)";
  } else {  // fig3 and fig4 analyse one sweep: fig3.png draws it against log k (cflogk), fig4.png against e (cfe)
    nlohmann::json plot = a.json;
    plot["figure"] = o.figure == "fig3" ? "cflogk" : "cfe";
    out.drawn = draw_figure(o, o.figure, plot, "small_n.py");
  }
  out.status = failures.empty() ? FigureStatus::Done : FigureStatus::PointsFailed;
  out.failed_points = failures;
  out.run_seconds = a.run_seconds;
  out.markdown = fmt::format(
      "Command: `{}`. N = {}, k_B T0 = 1, exact engine, e = {}, k = {}, T = {} (transient T/10), {} runs; fits over "
      "k >= {}. {}.\n\n",
      reproduce_command_line(o), grid.N, grid.e, grid.k, grid.T, a.runs, power_of_ten_text(preset_k_min(o)),
      fig5 ? "Figure: `fig5_N25_T01_exact.png` (and .pdf): panels (a)–(d) as the paper's Fig. cfreqlogN25"
      : o.figure == "fig3" ? "Figure: `fig3.png` (and .pdf): the paper's Fig. cflogk, n_coll against log10 k, one panel per N"
                           : "Figure: `fig4.png` (and .pdf): the paper's Fig. cfe, n_coll against e, one panel per N");
  out.markdown += fig5 ? fig5_table(a) : small_n_table(a) + fine_structure_report(o.db, points);
  out.markdown += "Every (N, e): regime, slope b per decade of k, exponent α, curvature against log10 k, K_i inversion:\n\n```\n" +
                  analysis_text(a) + "```\n";
  out.markdown += "\nCriteria and errors: docs/analysis.md. The quick preset's k range and time are far below the paper's; its "
                  "numbers show the same three regimes, not the paper's precision.\n";
  return out;
}

// Fig. partial_cond: sigma_i / sigma_0,i and K_i of every particle for N = 25, e = 0.82..0.92 (and
// the elastic e = 1 as a check of sigma_0,i, which comes from the exact elastic column), at the
// preset's largest k. The runs at e <= 0.90 are fig5's own points at that k.
FigureOutcome reproduce_partial_condensation(const ReproduceFlags& o, ReproductionLog& log) {
  const GridBlock grid = partial_condensation_grid(o).front();
  const std::vector<SweepPoint> points = grid_points({grid});
  const auto failures = run_missing_points(points, o, o.figure, log);
  const StoreAnalysis a = analyze_points(o.db, points, preset_k_min(o));
  nlohmann::json plot = {{"N", 25}, {"k", grid.k}, {"curves", nlohmann::json::array()}};
  const double z = analysis::pair_test_threshold(analysis::inversion_pairs(25));  // the test's threshold at N = 25
  std::string table = fmt::format(
      "| e | K_i dip at particle | largest rise of K_i above it | inversion (> {:g}σ) | hot layer: particle, cooler one above, drop | state | "
      "min σ_i/σ_0,i (particle) |\n|---|---|---|---|---|---|---|\n", z);
  std::string condensed;
  for (const auto& fam : a.json["families"])
    for (const auto& c : fam["curves"]) {
      if (!c.contains("profile")) continue;
      const auto& pc = c["partial_condensation"];
      plot["curves"].push_back(
          {{"e", c["e"]}, {"profile", c["profile"]}, {"condensed", pc["condensed"]}, {"state", pc["state"]}});
      const double e = c["e"].get<double>();
      const bool yes = pc["condensed"].get<bool>();
      if (yes) condensed += fmt::format("{}{:g}", condensed.empty() ? "" : ", ", e);
      table += fmt::format("| {:g} | {} | {} | {} | {}, {}, {} | {} | {} |\n", e, pc["K_dip_particle"].get<int>(),
                           plus_minus(pc["K_rise"].get<double>(), pc["K_rise_err"].get<double>(), 4), yes ? "yes" : "no",
                           pc["K_hot_particle"].get<int>(), pc["K_cooler_above_particle"].get<int>(),
                           plus_minus(pc["K_hot_drop"].get<double>(), pc["K_hot_drop_err"].get<double>(), 4),
                           pc["state"].get<std::string>(),
                           pc["sigma_ratio_min"].is_null() ? "-"
                                                          : fmt::format("{:.3f} ({})", pc["sigma_ratio_min"].get<double>(),
                                                                        pc["sigma_ratio_min_particle"].get<int>()));
    }
  const std::string drawn = draw_figure(o, "fig8", plot, "partial_cond.py");
  FigureOutcome out;
  out.status = failures.empty() ? FigureStatus::Done : FigureStatus::PointsFailed;
  out.failed_points = failures;
  out.run_seconds = a.run_seconds;
  out.drawn = drawn;
  out.markdown = fmt::format(
      "Command: `{}`. N = 25, k_B T0 = 1, k = {}, T = {}, e = {} (exact engine); "
      "σ_0,i is the exact elastic column's (docs/theory.md), the run at e = 1 checks it. Figure: `fig8.png` (and .pdf): "
      "(a) σ_i/σ_0,i, (b) K_i, against the particle index i.\n\n",
      reproduce_command_line(o), grid.k, grid.T, grid.e);
  out.markdown += table;
  out.markdown += fmt::format(
      "\nPartially condensed (K_i rises above its dip by more than {:g} standard errors) at e = {}; the paper (k = 1e10): a "
      "dip and an inversion layer for 0.84 ≲ e ≲ 0.90, monotone profiles for e ≳ 0.91.\n",
      z, condensed.empty() ? "none" : condensed);
  out.markdown += excluded_markdown(a);
  return out;
}

}  // namespace granchain
