#include "analysis/regime_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <tuple>

namespace granchain::analysis {

namespace {

// The e values of Table 1's mean exponent.
bool table1_e(double e) {
  for (double x : {0.1, 0.2, 0.3, 0.4})
    if (std::abs(e - x) < 1e-9) return true;
  return false;
}

}  // namespace

std::pair<double, double> combine_replicas(const std::vector<PointRun>& runs) {
  const bool windows_known = std::all_of(runs.begin(), runs.end(), [](const PointRun& r) { return r.T > 0; });
  const auto weight = [&](const PointRun& r) { return windows_known ? r.T : 1.0; };
  double w = 0, wn = 0, blocking2 = 0;
  for (const PointRun& r : runs) {
    w += weight(r);
    wn += weight(r) * r.n_coll;
    blocking2 += weight(r) * weight(r) * r.error * r.error;
  }
  const double mean = wn / w;
  double error = std::sqrt(blocking2) / w;
  if (runs.size() >= kReplicasForScatter) {
    double scatter2 = 0;
    for (const PointRun& r : runs) scatter2 += weight(r) * weight(r) * (r.n_coll - mean) * (r.n_coll - mean);
    const double m = static_cast<double>(runs.size());
    error = std::max(error, std::sqrt(m / (m - 1) * scatter2) / w);
  }
  return {mean, error};
}

RegimeReport analyze_runs(const std::vector<NcollRun>& runs, double k_min) {
  // (engine, drive, N, kT0) -> e -> k -> the runs of the point, combined below by combine_replicas
  using Key = std::tuple<EngineKind, DriveSpec, int, double>;
  using Runs = std::vector<PointRun>;
  std::map<Key, std::map<double, std::map<double, Runs>>> groups;
  std::map<Key, std::map<double, std::vector<double>>> unsettled;  // non-stationary runs' k per e
  RegimeReport report;
  // Why a run cannot enter the fits on its own ("" if it can).
  const auto unusable = [](const NcollRun& r) -> std::string {
    if (!std::isfinite(r.k)) return "k is not finite (the hard-sphere engine): n_coll(k) needs a finite k";
    if (!std::isfinite(r.n_coll)) return "n_coll is not a number";
    if (!(r.n_coll_err > 0))
      return fmt::format("n_coll = {:g} has no positive error (too few collisions in the window for blocking; run longer)", r.n_coll);
    return "";
  };
  // One trajectory, one sample: the run kept for each trajectory (of the usable ones, the longest
  // window, then the first).
  std::map<std::string, std::size_t> kept;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const NcollRun& r = runs[i];
    if (r.trajectory.empty() || !unusable(r).empty()) continue;
    const auto [it, fresh] = kept.emplace(r.trajectory, i);
    if (!fresh && r.T > runs[it->second].T) it->second = i;
  }
  // Per point, the longest transient after which a usable run's window was stationary, and per
  // (point, transient) how many usable runs there are and how many failed the check.
  using PointKey = std::tuple<EngineKind, DriveSpec, int, double, double, double>;
  const auto point_of = [](const NcollRun& r) { return PointKey{r.engine, r.drive, r.N, r.kT0, r.e, r.k}; };
  std::map<PointKey, double> settled_after;
  std::map<std::pair<PointKey, double>, std::pair<int, int>> verdicts;  // (runs, non-stationary)
  for (const NcollRun& r : runs) {
    if (!unusable(r).empty()) continue;
    auto& [n, failed] = verdicts[{point_of(r), r.transient}];
    ++n;
    failed += !r.stationary;
    if (!r.stationary) continue;
    const auto [it, fresh] = settled_after.emplace(point_of(r), r.transient);
    if (!fresh) it->second = std::max(it->second, r.transient);
  }
  // Results identical to the last bit at one point: not two independent samples, whatever their
  // seeds say (zero scatter); the first is kept.
  std::map<std::tuple<EngineKind, DriveSpec, int, double, double, double, double, double>, std::size_t> first_result;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const NcollRun& r = runs[i];
    std::string why = unusable(r);
    if (why.empty()) {
      // A transient whose runs fail the check beside stationary runs after a longer one: all the
      // runs after it are left out, those that passed too (they come from the same unsettled start).
      const auto s = settled_after.find(point_of(r));
      const auto [n, failed] = verdicts.at({point_of(r), r.transient});
      if (s != settled_after.end() && s->second > r.transient && failed > 0)
        why = fmt::format("its transient of {:g} had not settled the point ({} of its {} runs after it fail the stationarity "
                          "check; runs after {:g} pass)", r.transient, failed, n, s->second);
    }
    if (why.empty() && !r.trajectory.empty() && kept.at(r.trajectory) != i)
      why = fmt::format("the same trajectory as run {} (the same parameters and seed{}); one trajectory is one sample",
                        runs[kept.at(r.trajectory)].run_id, r.T == runs[kept.at(r.trajectory)].T ? "" : ", a shorter window");
    if (why.empty()) {
      const auto [at, fresh] = first_result.emplace(std::make_tuple(r.engine, r.drive, r.N, r.kT0, r.e, r.k, r.n_coll, r.n_coll_err), i);
      if (!fresh)
        why = fmt::format("n_coll and its error are those of run {} to the last bit (zero scatter): not an independent sample",
                          runs[at->second].run_id);
    }
    if (!why.empty()) {
      report.excluded.push_back({r.run_id, r.engine, r.N, r.kT0, r.e, r.k, why, r.drive});
      continue;
    }
    groups[{r.engine, r.drive, r.N, r.kT0}][r.e][r.k].push_back({r.n_coll, r.n_coll_err, r.T});
    if (!r.stationary) unsettled[{r.engine, r.drive, r.N, r.kT0}][r.e].push_back(r.k);
  }
  report.k_min = k_min;
  for (const auto& [key, by_e] : groups) {
    FamilyAnalysis fam;
    std::tie(fam.engine, fam.drive, fam.N, fam.kT0) = key;
    std::vector<Curve> all_curves;
    std::vector<double> es;
    std::vector<Regime> regimes;
    for (const auto& [e, by_k] : by_e) {
      CurveAnalysis curve;
      curve.e = e;
      for (const auto& [k, point_runs] : by_k) {
        curve.n_coll_of_k.push_back({k, 0, 0});
        std::tie(curve.n_coll_of_k.back().y, curve.n_coll_of_k.back().error) = combine_replicas(point_runs);
      }
      all_curves.push_back({e, curve.n_coll_of_k});
      const auto u = unsettled.find(key);
      if (u != unsettled.end() && u->second.count(e)) curve.non_stationary_k = u->second.at(e);
      int asymptotic = 0;
      for (const auto& p : curve.n_coll_of_k) asymptotic += p.x >= k_min;
      if (asymptotic >= 3) {
        curve.c = classify(curve.n_coll_of_k, k_min);
        curve.classified = true;
        es.push_back(e);
        regimes.push_back(curve.c.regime);
        if (table1_e(e) && curve.c.power_fit.alpha_error > 0) {
          fam.alphas.push_back({e, curve.c.power_fit.alpha, curve.c.power_fit.alpha_error});
          fam.local_alpha_by_e[e] = local_exponents(curve.n_coll_of_k);
        }
      } else if (asymptotic == 2 && table1_e(e)) {
        // Too few k to classify or fit, but a local exponent needs only two: a large column
        // measured at two k on the power-law side still enters the across-N lines of its interval.
        fam.local_alpha_by_e[e] = local_exponents(curve.n_coll_of_k);
      }
      fam.curves.push_back(std::move(curve));
    }
    if (!es.empty()) {
      // e_c1 from the approach of b to zero, with its systematic error (critical_restitution.hpp).
      fam.e_c1_estimate = estimate_e_c1(all_curves, fam.N, k_min);
      fam.e_c1 = fam.e_c1_estimate.e_c1;
      fam.e_c2 = e_c2_from_regimes(es, regimes);
      std::vector<DataPoint> curvatures;  // of the collapsing curves
      for (const auto& c : fam.curves)
        if (c.classified && c.c.regime != Regime::Uncollapsing) curvatures.push_back({c.e, c.c.curvature, c.c.curvature_error});
      // A sign change across more than 2/N of e (the width of the critical region, Eq. e-fit) is a
      // hole in the grid, not a located e_c2.
      fam.e_c2_sign = e_c2_from_curvature_sign(curvatures, 0.0061, 2.0 / fam.N);
    }
    {
      std::vector<std::vector<std::pair<double, double>>> point_groups;  // each (e, k)'s (n_coll, error), for the replica check
      std::vector<std::pair<double, double>> where;
      for (const auto& [e, by_k] : by_e)
        for (const auto& [k, point_runs] : by_k) {
          point_groups.emplace_back();
          for (const PointRun& r : point_runs) point_groups.back().push_back({r.n_coll, r.error});
          where.push_back({e, k});
        }
      fam.replicas = replica_scatter(point_groups);
      if (fam.replicas.worst >= 0) std::tie(fam.replicas_worst_e, fam.replicas_worst_k) = where[fam.replicas.worst];
    }
    if (!fam.alphas.empty()) {
      fam.alpha_bar = mean_exponent(fam.alphas);
      fam.has_alpha_bar = true;
    }
    if (!fam.local_alpha_by_e.empty()) {
      std::vector<std::vector<LocalExponent>> per_e;
      for (const auto& [e, locals] : fam.local_alpha_by_e) per_e.push_back(locals);
      fam.local_alpha_bar = mean_local_exponents(per_e);
    }
    report.families.push_back(std::move(fam));
  }
  // Across N for each (engine, drive, kT0).
  std::map<std::tuple<EngineKind, DriveSpec, double>, std::vector<const FamilyAnalysis*>> by_temperature;
  for (const auto& f : report.families) by_temperature[{f.engine, f.drive, f.kT0}].push_back(&f);
  for (const auto& [key, fams] : by_temperature) {
    AcrossN a;
    std::tie(a.engine, a.drive, a.kT0) = key;
    // (1 - e_c) = A/N over the N where a critical value was found (at least two).
    // A value located only to the grid (CriticalValue::grid_rounded): on fig6's grid
    // e = 1 - c/N every N's bracket is a step in c = N (1 - e), the same step at every N, so the
    // rounding is shared, not independent, and averaging over N cannot shrink it. If each N's
    // position sits at the same fraction of its bracket, A moves by the fit's weighted mean of the
    // brackets' widths in c (weights x^2 / error^2, x = 1/N, as in the fit); A's error is at least
    // that mean over sqrt 12. A value fitted between denser points enters that mean as 0.
    auto fit_over_n = [&fams](auto value_of, bool& has, InverseNFit& fit) {
      std::vector<double> Ns;
      std::vector<CriticalValue> values;
      double w_sum = 0, w_width = 0;
      for (const FamilyAnalysis* f : fams) {
        const CriticalValue c = value_of(*f);
        if (!c.found) continue;
        Ns.push_back(f->N);
        values.push_back(c);
        const double x = 1.0 / f->N, sigma = std::max(c.error, 1e-12);
        w_sum += x * x / (sigma * sigma);
        if (c.grid_rounded) w_width += x * x / (sigma * sigma) * f->N * (c.high - c.low);
      }
      has = Ns.size() >= 2;
      if (!has) return;
      fit = fit_inverse_n(Ns, values);
      fit.A_error = std::max(fit.A_error, w_width / w_sum / std::sqrt(12.0));
    };
    fit_over_n([](const FamilyAnalysis& f) { return f.e_c1; }, a.has_A1, a.A1);
    fit_over_n([](const FamilyAnalysis& f) { return f.e_c2; }, a.has_A2, a.A2);
    fit_over_n([](const FamilyAnalysis& f) { return classification_boundary(f.e_c1_estimate); }, a.has_A1_boundary, a.A1_boundary);
    fit_over_n([](const FamilyAnalysis& f) { return f.e_c2_sign; }, a.has_A2_sign, a.A2_sign);
    std::vector<DataPoint> alpha_of_n;
    for (const FamilyAnalysis* f : fams)
      if (f->has_alpha_bar && f->alpha_bar.error > 0) alpha_of_n.push_back({static_cast<double>(f->N), f->alpha_bar.value, f->alpha_bar.error});
    if (alpha_of_n.size() >= 3) {
      a.alpha_fit = fit_alpha_vs_log10_n(alpha_of_n);
      a.has_alpha_fit = true;
    }
    std::map<std::pair<double, double>, std::vector<DataPoint>> local_of_n;  // by interval of k
    for (const FamilyAnalysis* f : fams)
      for (const LocalExponent& l : f->local_alpha_bar)
        if (std::isfinite(l.alpha) && l.error > 0) local_of_n[{l.k1, l.k2}].push_back({static_cast<double>(f->N), l.alpha, l.error});
    for (auto& [k, pts] : local_of_n) {
      if (pts.size() < 3) continue;
      std::sort(pts.begin(), pts.end(), [](const DataPoint& a, const DataPoint& b) { return a.x < b.x; });
      LocalAlphaLine line;
      line.k1 = k.first;
      line.k2 = k.second;
      line.fit = fit_alpha_vs_log10_n(pts);
      for (const DataPoint& p : pts) line.Ns.push_back(static_cast<int>(p.x));
      std::vector<ColumnExponents> columns;
      for (const FamilyAnalysis* f : fams) {
        ColumnExponents c{f->N, {}};
        for (const auto& [e, locals] : f->local_alpha_by_e)
          for (const LocalExponent& l : locals)
            if (l.k1 == k.first && l.k2 == k.second && std::isfinite(l.alpha) && l.error > 0) c.by_e[e] = {0.0, l.alpha, l.error};
        if (!c.by_e.empty()) columns.push_back(std::move(c));
      }
      line.neighbour_slopes = neighbour_slopes(columns);
      line.has_excess = excess_over_line(columns, line.excess);
      a.local_alpha_lines.push_back(std::move(line));
    }
    report.across.push_back(a);
  }
  return report;
}

}  // namespace granchain::analysis
