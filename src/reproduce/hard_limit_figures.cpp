// `granchain reproduce --figure limit-free` and `limit-driven` (group `beyond`): how the collision
// count grows as k -> infinity, past the paper's k range. Free-space collapse (Sec. III.D) at
// N = 10, 25, 50, 100 (and N = 3, the check) and the driven column at N = 25 and 50 (Sec. III.C): local exponents d ln n / d ln k per
// decade with errors, and the candidate asymptotic forms (analysis/asymptotic_forms) compared by
// AICc and BIC with their pulls, beside the trend of the local slope.
#include <fmt/format.h>

#include <Eigen/Dense>
#include <cmath>
#include <optional>
#include <nlohmann/json.hpp>

#include "analysis/asymptotic_forms.hpp"
#include "config/value_list.hpp"
#include "reproduce/figures.hpp"
#include "simulation/collapse_run.hpp"
#include "store/results_store.hpp"
#include "theory/collapse_theory.hpp"

namespace granchain {

using analysis::FormComparison;
using analysis::LocalExponent;

namespace {

// The forms fitted to (k, y, covariance) for k >= k_fit: their JSON and a Markdown table with the
// verdict. Fewer than 4 points: no fit, said so.
struct FormsOutcome {
  nlohmann::json json;
  std::string markdown;
};
// The points with k >= k_fit and their covariance.
struct Window {
  std::vector<double> k, y;
  Eigen::MatrixXd C;
};
Window window(const std::vector<double>& k, const std::vector<double>& y, const Eigen::MatrixXd& C, double k_fit) {
  std::vector<Eigen::Index> use;
  for (std::size_t i = 0; i < k.size(); ++i)
    if (k[i] >= k_fit * (1 - 1e-9)) use.push_back(static_cast<Eigen::Index>(i));
  Window w;
  w.C.resize(static_cast<Eigen::Index>(use.size()), static_cast<Eigen::Index>(use.size()));
  for (std::size_t a = 0; a < use.size(); ++a) {
    w.k.push_back(k[static_cast<std::size_t>(use[a])]);
    w.y.push_back(y[static_cast<std::size_t>(use[a])]);
    for (std::size_t b = 0; b < use.size(); ++b) w.C(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)) = C(use[a], use[b]);
  }
  return w;
}

FormsOutcome compare_forms(const std::vector<double>& k, const std::vector<double>& y, const Eigen::MatrixXd& C, double k_fit) {
  const Window w = window(k, y, C, k_fit);
  FormsOutcome out{nullptr, ""};
  if (w.k.size() < 4) {
    out.markdown = fmt::format("Fewer than 4 values of k ≥ {}: the forms are not compared.\n", power_of_ten_text(k_fit));
    return out;
  }
  const std::vector<double>& kk = w.k;
  const FormComparison c = analysis::compare_asymptotic_forms(kk, w.y, w.C);
  const double best_a = c.fits[static_cast<std::size_t>(c.best_aicc)].aicc, best_b = c.fits[static_cast<std::size_t>(c.best_bic)].bic;
  out.json = {{"k", kk}, {"forms", nlohmann::json::array()}, {"best_aicc", c.best_aicc}, {"best_bic", c.best_bic}};
  out.markdown = fmt::format("Forms fitted over k = {} … {} ({} points, covariance of the points included):\n\n"
                             "| form | parameters | χ² / dof | ΔAICc | ΔBIC | Akaike weight | largest pull |\n|---|---|---|---|---|---|---|\n",
                             power_of_ten_text(kk.front()), power_of_ten_text(kk.back()), kk.size());
  for (const auto& f : c.fits) {
    std::string params;
    using analysis::AsymptoticForm;
    const bool power = f.form == AsymptoticForm::PowerLaw || f.form == AsymptoticForm::PowerLawLog || f.form == AsymptoticForm::PowerOfLog;
    const char* names[3] = {power ? "ln c" : "a", f.form == AsymptoticForm::PowerOfLog ? "β" : power ? "α" : "b",
                            f.form == AsymptoticForm::PowerLawLog ? "β" : "c"};
    for (std::size_t i = 0; i < f.param.size(); ++i) params += fmt::format("{}{} = {}", i ? ", " : "", names[i], plus_minus(f.param[i], f.error[i], 4));
    double worst = 0;
    for (double p : f.pulls) worst = std::max(worst, std::abs(p));
    out.markdown += fmt::format("| {} | {} | {:.1f} / {} | {:.1f} | {:.1f} | {:.3f} | {:.1f} |\n", analysis::form_formula(f.form), params, f.chi2,
                                f.dof, f.aicc - best_a, f.bic - best_b, f.akaike_weight, worst);
    out.json["forms"].push_back({{"name", analysis::form_name(f.form)}, {"formula", analysis::form_formula(f.form)}, {"param", f.param},
                                 {"error", f.error}, {"chi2", f.chi2}, {"dof", f.dof}, {"aicc", f.aicc}, {"bic", f.bic},
                                 {"weight", f.akaike_weight}, {"model", f.model}, {"pulls", f.pulls}});
  }
  const auto& best = c.fits[static_cast<std::size_t>(c.best_aicc)];
  const bool fits = best.chi2_z < 3.0;
  std::string verdict;
  if (!fits)
    verdict = fmt::format("no form fits (the best, {}, has χ² deviate {:.1f}): no conclusion", analysis::form_name(best.form), best.chi2_z);
  else if (best.akaike_weight >= 0.9 && c.best_aicc == c.best_bic)
    verdict = fmt::format("the data support **{}** (Akaike weight {:.2f}, also BIC's choice)", analysis::form_name(best.form), best.akaike_weight);
  else {
    std::string close;
    for (const auto& f : c.fits)
      if (f.aicc - best_a < 4.0 && &f != &best) close += fmt::format("{}{}", close.empty() ? "" : ", ", analysis::form_name(f.form));
    verdict = fmt::format("AICc prefers {} (weight {:.2f}), BIC {}; within ΔAICc < 4: {}: no conclusion between them", analysis::form_name(best.form),
                          best.akaike_weight, analysis::form_name(c.fits[static_cast<std::size_t>(c.best_bic)].form), close.empty() ? "none" : close);
  }
  out.json["verdict"] = verdict;
  out.markdown += "\nVerdict: " + verdict + ".\n";
  return out;
}

// The two forms that bend, c k^alpha (ln k)^beta and c (ln k)^beta, fitted over k >= k_lo for a
// rising k_lo up to the series' end: a form that is the asymptotic law keeps its parameters as the
// window moves up; an alpha that keeps falling says the power of k is the drift of the lower decades.
std::string sliding_window_text(const std::vector<double>& k, const std::vector<double>& y, const Eigen::MatrixXd& C, nlohmann::json& js) {
  std::string md = fmt::format("The bending forms over k ≥ k_lo … {} (at least 5 points):\n\n| k_lo | c k^α (ln k)^β: α | β | χ² / dof | "
                               "c (ln k)^β: β | χ² / dof | ΔAICc of c (ln k)^β |\n|---|---|---|---|---|---|---|\n",
                               power_of_ten_text(k.back()));
  js["sliding"] = nlohmann::json::array();
  for (double k_lo = 1e5; k_lo <= 1e13 * (1 + 1e-9); k_lo *= 100) {
    const Window w = window(k, y, C, k_lo);
    if (w.k.size() < 5) break;
    const FormComparison c = analysis::compare_asymptotic_forms(w.k, w.y, w.C);
    const analysis::FormFit *pl = nullptr, *lp = nullptr;
    for (const auto& f : c.fits) {
      if (f.form == analysis::AsymptoticForm::PowerLawLog) pl = &f;
      if (f.form == analysis::AsymptoticForm::PowerOfLog) lp = &f;
    }
    if (!pl || !lp) break;
    md += fmt::format("| {} | {} | {} | {:.1f} / {} | {} | {:.1f} / {} | {:.1f} |\n", power_of_ten_text(k_lo), plus_minus(pl->param[1], pl->error[1], 4),
                      plus_minus(pl->param[2], pl->error[2], 3), pl->chi2, pl->dof, plus_minus(lp->param[1], lp->error[1], 3), lp->chi2,
                      lp->dof, lp->aicc - pl->aicc);
    js["sliding"].push_back({{"k_lo", k_lo}, {"alpha", pl->param[1]}, {"alpha_error", pl->error[1]}, {"beta", pl->param[2]},
                             {"beta_error", pl->error[2]}, {"chi2", pl->chi2}, {"dof", pl->dof}, {"log_power_beta", lp->param[1]},
                             {"log_power_beta_error", lp->error[1]}, {"log_power_chi2", lp->chi2}, {"log_power_dof", lp->dof}});
  }
  return md;
}

// Polynomials in ln k of degree 1 .. 5 over k >= k_lo: a count that is a sum of collapse
// generations nested up to J deep grows as a polynomial of degree J in ln k (no power of k). Their
// chi^2 and AICc beside the best of the five forms, and the least degree that fits.
std::string log_polynomials_text(const std::vector<double>& k, const std::vector<double>& y, const Eigen::MatrixXd& C, double k_lo,
                                 nlohmann::json& js) {
  const Window w = window(k, y, C, k_lo);
  if (w.k.size() < 7) return "";
  const FormComparison forms = analysis::compare_asymptotic_forms(w.k, w.y, w.C);
  const analysis::FormFit& best = forms.fits[static_cast<std::size_t>(forms.best_aicc)];
  std::string md = fmt::format("Polynomials in ln k, y = Σ_j c_j (ln k)^j up to degree J, over k = {} … {}, against the best of the five "
                               "forms ({}, χ² = {:.1f} / {}):\n\n| J | c_J | χ² / dof | χ² deviate | ΔAICc to the best form |\n|---|---|---|---|---|\n",
                               power_of_ten_text(w.k.front()), power_of_ten_text(w.k.back()), analysis::form_name(best.form), best.chi2, best.dof);
  nlohmann::json rows = nlohmann::json::array();
  int least = 0;
  double least_daicc = 0;
  for (int J = 1; J <= 5 && static_cast<int>(w.k.size()) >= J + 4; ++J) {
    const analysis::LogPolynomialFit f = analysis::fit_log_polynomial(w.k, w.y, w.C, J);
    md += fmt::format("| {} | {:.4g} ± {:.2g} | {:.1f} / {} | {:.1f} | {:.1f} |\n", J, f.leading, f.leading_error, f.chi2, f.dof, f.chi2_z, f.aicc - best.aicc);
    rows.push_back({{"degree", J}, {"leading", f.leading}, {"leading_error", f.leading_error}, {"chi2", f.chi2}, {"dof", f.dof},
                    {"chi2_z", f.chi2_z}, {"delta_aicc", f.aicc - best.aicc}});
    if (least == 0 && f.chi2_z < 2.0) least = J, least_daicc = f.aicc - best.aicc;
  }
  js["log_polynomials"] = {{"k_lo", k_lo}, {"fits", rows}, {"least_degree", least}};
  const char* against = least_daicc < -4 ? "preferred to every one of the five forms"
                        : least_daicc > 4 ? "the best of the five forms is preferred to it"
                                          : "no conclusion between it and the best of the five forms";
  md += least > 0 ? fmt::format("\nThe least degree that fits (χ² deviate below 2): J = {}, ΔAICc {:.1f}: {}.\n", least, least_daicc, against)
                  : "\nNo degree up to 5 fits (χ² deviate below 2).\n";
  return md;
}

std::string trend_text(const std::vector<LocalExponent>& local, nlohmann::json& js) {
  const analysis::SlopeTrend t = analysis::slope_trend(local);
  js["trend"] = {{"mean", t.mean}, {"mean_error", t.mean_error}, {"constant_chi2", t.constant_chi2}, {"constant_dof", t.constant_dof},
                 {"constant_z", t.constant_z}, {"slope", t.slope}, {"slope_error", t.slope_error}};
  if (!std::isfinite(t.slope)) return "Too few local exponents for a trend.\n";
  return fmt::format("Local exponent: {}. Constant (one power law): mean {}, χ² = {:.1f} on {} dof (deviate {:.1f}); linear trend "
                     "{} per decade of k ({:.1f} standard errors from zero).\n",
                     local_exponents_text(local), plus_minus(t.mean, t.mean_error, 3), t.constant_chi2, t.constant_dof, t.constant_z,
                     plus_minus(t.slope, t.slope_error, 4), t.slope / t.slope_error);
}

// N = 3 below e_c(3), the check of the method (its count grows by a fixed number per decade of k,
// Eq. ntot-log), then N = 6 and 8 at e = 0.3 (paper preset), then the many-body series at e = 0.3
// and 0.5. The paper preset goes to k = 1e20,
// which the exact engine resolves (docs/engines.md); the cheap series come first, so a run cut
// short keeps them.
std::vector<CountSeries> free_series(const ReproduceFlags& o) {
  std::vector<CountSeries> s;
  const std::string k_range = o.smoke() ? "1e4:1e7:x10" : o.paper() ? "1e4:1e20:x10" : "1e4:1e10:x10";
  if (!o.smoke())
    for (double e : {0.03, 0.05}) s.push_back({3, e, k_range, o.paper() ? 1000 : 200});
  // The paper preset adds the fewest particles that collapse at e = 0.3 (n* = 6, Sec. III.B's
  // e_c(n)) and two more: how the growth changes as the chain gains particles beyond one collapse.
  if (o.paper())
    for (int N : {6, 8}) s.push_back({N, 0.3, k_range, 2000});
  for (int N : o.smoke() ? std::vector<int>{10, 25} : o.paper() ? std::vector<int>{10, 25, 50, 100} : std::vector<int>{10, 25, 50})
    for (double e : {0.3, 0.5}) {
      const int launches = o.smoke()   ? 10
                           : o.paper() ? (N == 10 ? 2000 : N == 25 ? 1000 : N == 50 ? 200 : 40)
                                       : (N == 10 ? 400 : N == 25 ? 100 : 40);
      s.push_back({N, e, k_range, launches});
    }
  return s;
}

// A power of ln k, y = c (ln k)^beta, has the local exponent beta / ln k: the local exponent times
// ln k at the middle of its interval is beta, constant for such a law; for y = c k^alpha (ln k)^beta
// it is beta + alpha ln k, rising by alpha ln 10 per decade of k. Its weighted mean and trend.
std::string log_power_text(const std::vector<LocalExponent>& local, nlohmann::json& js) {
  std::vector<analysis::DataPoint> pts;
  for (const auto& l : local) {
    const double mid = 0.5 * std::log(l.k1 * l.k2);
    pts.push_back({0.5 * std::log10(l.k1 * l.k2), l.alpha * mid, l.error * mid});
  }
  const analysis::SlopeTrend t = analysis::trend(pts);
  js["log_power_trend"] = {{"mean", t.mean}, {"mean_error", t.mean_error}, {"constant_chi2", t.constant_chi2}, {"constant_dof", t.constant_dof},
                           {"slope", t.slope}, {"slope_error", t.slope_error}};
  if (!std::isfinite(t.slope)) return "";
  return fmt::format("Local exponent × ln k (the β of (ln k)^β; constant for a power of ln k, rising by α ln 10 per decade of k for "
                     "k^α (ln k)^β): constant: mean {}, χ² = {:.1f} on {} dof (deviate {:.1f}); linear trend {} per decade of k, "
                     "an α of {} ({:.1f} standard errors from zero).\n",
                     plus_minus(t.mean, t.mean_error, 2), t.constant_chi2, t.constant_dof, t.constant_z, plus_minus(t.slope, t.slope_error, 3),
                     plus_minus(t.slope / std::log(10.0), t.slope_error / std::log(10.0), 4), t.slope / t.slope_error);
}

// Three bodies below e_c(3): the increments of n_tot per decade of k (errors from the paired
// launches) against the analytic slope ln 10 / -ln q(e) of the collapse sequence (Eq. deltat12;
// docs/collapse.md explains why it is the collisions' slope, not Eq. ntot-log's).
std::string three_body_increments(const std::vector<double>& k, const std::vector<double>& y, const Eigen::MatrixXd& C, double e,
                                  nlohmann::json& js) {
  const double expected = std::log(10.0) * theory::collisions_slope_per_ln_k(e);
  std::string md = fmt::format("Increments per decade of k against the three-body collapse's ln 10 / −ln q(e) = {:.4f}, which they "
                               "approach as τ_c falls below the launch's first collision intervals (the pulls at small k measure "
                               "that approach):\n\n"
                               "| k1 → k2 | Δn_tot per decade | pull from {:.4f} |\n|---|---|---|\n",
                               expected, expected);
  js["increment_expected"] = expected;
  js["increments"] = nlohmann::json::array();
  for (std::size_t i = 0; i + 1 < k.size(); ++i) {
    const auto a = static_cast<Eigen::Index>(i), b = a + 1;
    const double decades = std::log10(k[i + 1] / k[i]);
    const double d = (y[i + 1] - y[i]) / decades;
    const double err = std::sqrt(std::max(0.0, C(a, a) + C(b, b) - 2 * C(a, b))) / decades;
    md += fmt::format("| {} → {} | {} | {:.1f} |\n", power_of_ten_text(k[i]), power_of_ten_text(k[i + 1]), plus_minus(d, err, 4),
                      err > 0 ? (d - expected) / err : 0.0);
    js["increments"].push_back({{"k1", k[i]}, {"k2", k[i + 1]}, {"per_decade", d}, {"error", err}});
  }
  return md;
}

}  // namespace

std::vector<CollapseSpec> free_space_exponent_specs(const ReproduceFlags& o) { return count_specs(free_series(o), o); }

FigureOutcome reproduce_free_space_exponents(const ReproduceFlags& o, ReproductionLog& log) {
  const double k_fit = o.smoke() ? 1e4 : 1e5;
  nlohmann::json plot = {{"title", "free-space collapse"}, {"y_label", "n_tot"}, {"series", nlohmann::json::array()}};
  std::string md = fmt::format("Command: `{}`. Free-space launches of Sec. III.D (a = v0 = 1, "
                               "dv0 = 0.1, stop rule `ends`), exact engine, the same launches at every k: local exponents "
                               "α = ln(n2/n1)/ln(k2/k1) per decade with errors from the paired launches, and the forms fitted with "
                               "the covariance of the counts across k estimated from the launches. Counts are stored in --db (table "
                               "collapse_runs) and reused. Figure: `limit-free.png` (and .pdf).\n",
                               reproduce_command_line(o));
  // The upper window: the forms fitted again over k >= 1e10 where a series reaches 1e16, to see
  // whether the verdict is the asymptotic one or the drift of the lower decades.
  const double k_upper = 1e10;
  int drawn = 0;
  // --stored-only: one read-only handle for every count.
  std::optional<ResultsStore> reader =
      o.stored_only ? std::optional<ResultsStore>(std::in_place, o.db, ResultsStore::Access::ReadOnly) : std::nullopt;
  for (const CountSeries& s : free_series(o)) {
    std::vector<CollapseResult> results;
    const std::vector<double> ks = parse_value_list(s.k, "--k");
    for (double k : ks) {
      const CollapseSpec spec = free_space_spec(s.N, s.e, k, s.launches, o);
      if (!o.stored_only) {
        results.push_back(stored_or_run_collapse(spec, o, "limit-free"));
      } else if (std::optional<CollapseResult> r = reader->find_collapse(spec)) {
        results.push_back(*r);
      }
    }
    if (results.size() < ks.size())
      log.partial.push_back(fmt::format("limit-free (N = {}, e = {:g}): {} of {} counts", s.N, s.e, results.size(), ks.size()));
    if (results.size() < 2) {
      md += fmt::format("\n### N = {}, e = {:g} ({} launches)\n\nFewer than two of its counts are stored (--stored-only): not drawn.\n", s.N,
                        s.e, s.launches);
      continue;
    }
    ++drawn;
    const std::size_t nk = results.size();
    std::vector<double> k, y, err;
    for (const auto& r : results) k.push_back(r.spec.params.k), y.push_back(r.n_tot_mean), err.push_back(r.n_tot_error);
    // Each launch's counts at every k: their covariance across k, and from it the local exponents'
    // errors (the launches are paired).
    std::vector<std::vector<double>> per_launch(results[0].outcomes.size(), std::vector<double>(nk));
    for (std::size_t i = 0; i < nk; ++i)
      for (std::size_t r = 0; r < per_launch.size(); ++r) per_launch[r][i] = static_cast<double>(results[i].outcomes[r].n_tot());
    const Eigen::MatrixXd C = analysis::covariance_of_means(per_launch);
    const std::vector<LocalExponent> local = analysis::local_exponents(k, y, C);
    nlohmann::json js = {{"label", fmt::format("N = {}, e = {:g}", s.N, s.e)}, {"N", s.N}, {"e", s.e}, {"k", k}, {"y", y}, {"error", err},
                         {"launches", s.launches}, {"local", local_exponents_json(local)}};
    md += fmt::format("\n### N = {}, e = {:g} ({} launches)\n\n| k | n_tot | local α to the next k | × ln √(k1 k2) |\n|---|---|---|---|\n",
                      s.N, s.e, s.launches);
    for (std::size_t i = 0; i < nk; ++i) {
      const double mid = i + 1 < nk ? 0.5 * std::log(k[i] * k[i + 1]) : 0.0;
      md += fmt::format("| {} | {} | {} | {} |\n", power_of_ten_text(k[i]), plus_minus(y[i], err[i], s.N == 3 ? 3 : 1),
                        i + 1 < nk ? plus_minus(local[i].alpha, local[i].error, 3) : "",
                        i + 1 < nk ? plus_minus(local[i].alpha * mid, local[i].error * mid, 2) : "");
    }
    if (s.N == 3) {
      md += "\n" + three_body_increments(k, y, C, s.e, js);
    } else {
      md += "\n" + trend_text(local, js) + "\n" + log_power_text(local, js) + "\n";
      const FormsOutcome forms = compare_forms(k, y, C, k_fit);
      js["fit"] = forms.json;
      md += forms.markdown;
      md += "\n" + log_polynomials_text(k, y, C, k_fit, js);
      if (k.back() >= 1e16 * (1 - 1e-9)) {
        const FormsOutcome upper = compare_forms(k, y, C, k_upper);
        js["fit_upper"] = upper.json;
        nlohmann::json upper_js;
        md += "\nThe upper decades alone. " + upper.markdown + "\n" + log_polynomials_text(k, y, C, k_upper, upper_js) + "\n" +
              sliding_window_text(k, y, C, js);
        js["log_polynomials_upper"] = upper_js["log_polynomials"];
      }
    }
    plot["series"].push_back(js);
  }
  if (o.stored_only && drawn == 0) throw NothingStored(fmt::format("no free-space series of limit-free has two counts in {}", o.db));
  FigureOutcome out{FigureStatus::Done, md, draw_figure(o, "limit-free", plot, "limit_exponents.py"), -1.0, "", {}};
  return out;
}

// The paper preset: N = 25 to k = 1e16 and N = 50 (e = 0.1, 0.3) to 1e14, at the paper's T (1e4 for
// N < 50, 1e3 from N = 50 on, so that N = 50 continues fig6's runs).
std::vector<GridBlock> driven_limit_grid(const ReproduceFlags& o) {
  if (o.paper()) return {{"25", "0.1:0.5:0.1", "1e5:1e16:x10", "1e4"}, {"50", "0.1,0.3", "1e5:1e14:x10", "1e3"}};
  if (o.smoke()) return {{"25", "0.1:0.5:0.2", "1e4:1e6:x10", "20"}};
  return {{"25", "0.1:0.5:0.1", "1e4:1e9:x10", "1000"}};
}

FigureOutcome reproduce_driven_exponents(const ReproduceFlags& o, ReproductionLog& log) {
  const std::vector<SweepPoint> points = grid_points(driven_limit_grid(o));
  const std::vector<std::string> failed = run_missing_points(points, o, "limit-driven", log);
  const double k_fit = preset_k_min(o);
  const StoreAnalysis a = analyze_points(o.db, points, k_fit);
  std::string T;
  for (const GridBlock& b : driven_limit_grid(o)) T += fmt::format("{}{} (N = {})", T.empty() ? "" : ", ", b.T, b.N);
  nlohmann::json plot = {{"title", "driven column"}, {"y_label", "n_coll"}, {"series", nlohmann::json::array()}};
  std::string md = fmt::format("Command: `{}`. Driven column, k_B T0 = 1, "
                               "measuring time T = {} (transient T/10), exact engine, one run per point (runs stored in --db and "
                               "reused, so the paper preset shares fig5's points up to k = 1e10). Local exponents between successive k "
                               "with errors from the two runs' blocking errors; forms fitted over k ≥ {} with independent errors. "
                               "Figure: `limit-driven.png` (and .pdf).\n",
                               reproduce_command_line(o), T, power_of_ten_text(k_fit));
  for (const auto& fam : a.report.families)
    for (const auto& c : fam.curves) {
      std::vector<double> k, y, err;
      for (const auto& p : c.n_coll_of_k) k.push_back(p.x), y.push_back(p.y), err.push_back(p.error);
      const std::vector<LocalExponent> local = analysis::local_exponents(c.n_coll_of_k);
      nlohmann::json js = {{"label", fmt::format("N = {}, e = {:g}", fam.N, c.e)}, {"N", fam.N}, {"e", c.e}, {"k", k}, {"y", y}, {"error", err},
                           {"local", local_exponents_json(local)}, {"non_stationary_k", c.non_stationary_k}};
      md += fmt::format("\n### N = {}, e = {:g}\n\n| k | n_coll | local α to the next k |\n|---|---|---|\n", fam.N, c.e);
      for (std::size_t i = 0; i < k.size(); ++i) {
        bool unsettled = false;
        for (double u : c.non_stationary_k) unsettled = unsettled || u == k[i];
        md += fmt::format("| {} | {}{} | {} |\n", power_of_ten_text(k[i]), plus_minus(y[i], err[i], 3), unsettled ? " [not stationary]" : "",
                          i + 1 < k.size() && i < local.size() ? plus_minus(local[i].alpha, local[i].error, 3) : "");
      }
      md += "\n" + trend_text(local, js) + "\n";
      Eigen::MatrixXd C = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(k.size()), static_cast<Eigen::Index>(k.size()));
      for (std::size_t i = 0; i < k.size(); ++i) C(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i)) = err[i] * err[i];
      const FormsOutcome forms = compare_forms(k, y, C, k_fit);
      js["fit"] = forms.json;
      md += forms.markdown;
      md += "\n" + log_polynomials_text(k, y, C, k_fit, js);
      plot["series"].push_back(js);
    }
  FigureOutcome out{failed.empty() ? FigureStatus::Done : FigureStatus::PointsFailed, md, draw_figure(o, "limit-driven", plot, "limit_exponents.py"),
                    a.run_seconds, "", failed};
  for (const std::string& f : failed) out.markdown += "\nFailed point (left out): " + f + "\n";
  out.markdown += excluded_markdown(a);
  return out;
}

}  // namespace granchain
