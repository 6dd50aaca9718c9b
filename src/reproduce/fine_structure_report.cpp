// The fine structure of n_coll(e) in the small columns of Figs. cflogk and cfe (N = 3 ... 6): each
// statement the paper makes about it (Sec. III.B and the Summary) tested on the stored curves at
// the largest k, on both seeds together and on each seed alone (analysis/fine_structure).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "analysis/fine_structure.hpp"
#include "reproduce/figures.hpp"
#include "store/stored_rows.hpp"
#include "theory/collapse_theory.hpp"

namespace granchain {

namespace {

using analysis::DataPoint;
using Curve = std::vector<DataPoint>;  // n_coll against e, e ascending
constexpr int kCombined = -1;          // the replicas' weighted mean

// N -> k -> replica (or kCombined) -> n_coll(e).
using SmallNCurves = std::map<int, std::map<double, std::map<int, Curve>>>;

SmallNCurves read_curves(const std::string& db, const std::vector<SweepPoint>& points) {
  ExportSelection sel;
  for (const SweepPoint& p : points) sel.point_keys.push_back(p.key);
  std::map<int, std::map<double, std::map<int, std::map<double, DataPoint>>>> acc;  // N, k, replica, e
  for (const StoredRun& row : read_runs(db, sel)) {
    if (std::isnan(row.n_coll_err) || !std::isfinite(row.spec.params.k)) continue;
    const double e = row.spec.params.e, err = row.n_coll_err;
    if (!(err > 0)) continue;
    acc[row.spec.params.N][row.spec.params.k][row.replica][e] = {e, row.n_coll, err};
  }
  SmallNCurves out;
  for (const auto& [N, by_k] : acc)
    for (const auto& [k, by_r] : by_k) {
      std::map<double, std::pair<double, double>> mean;  // e -> (sum w, sum w n)
      for (const auto& [r, by_e] : by_r) {
        Curve& c = out[N][k][r];
        for (const auto& [e, p] : by_e) {
          c.push_back(p);
          mean[e].first += 1 / (p.error * p.error);
          mean[e].second += p.y / (p.error * p.error);
        }
      }
      Curve& c = out[N][k][kCombined];
      for (const auto& [e, s] : mean) c.push_back({e, s.second / s.first, 1 / std::sqrt(s.first)});
    }
  return out;
}

// The most significant extremum of a kind in the window of e_c(n), or null.
const analysis::Extremum* feature_at(const analysis::FineStructure& fs, int n, analysis::ExtremumKind kind) {
  const analysis::Extremum* best = nullptr;
  for (const auto& c : fs.at_critical)
    if (c.n == n)
      for (const auto& x : c.extrema)
        if (x.kind == kind && (!best || x.z > best->z)) best = &x;
  return best;
}

struct Finding {
  bool holds = false;
  std::string evidence;
};
std::string cell(const Finding& f) { return fmt::format("{}{}{}", f.holds ? "**yes**" : "no", f.evidence.empty() ? "" : ": ", f.evidence); }

Finding extremum_finding(const analysis::FineStructure& fs, int n, analysis::ExtremumKind kind) {
  const analysis::Extremum* x = feature_at(fs, n, kind);
  if (!x) return {false, ""};
  return {true, fmt::format("e = {:.4f}, {:.2f} {} its neighbours, z = {:.1f}", x->x, x->prominence,
                            kind == analysis::ExtremumKind::Peak ? "above" : "below", x->z)};
}

// The paper's dip "at e slightly larger than e_c(N)": the most significant dip within e_c(N)'s
// window or above it up to e_c(N) + 0.025 (half the coarse grid step; the refined grid stops at
// e_c(N) + 0.01).
Finding dip_at_or_above(const analysis::FineStructure& fs, int N) {
  const double e_c = theory::ec_free(N);
  const analysis::Extremum* best = feature_at(fs, N, analysis::ExtremumKind::Dip);
  for (const auto& x : fs.elsewhere)
    if (x.kind == analysis::ExtremumKind::Dip && x.x > e_c && x.x <= e_c + 0.025 && (!best || x.z > best->z)) best = &x;
  if (!best) return {false, ""};
  return {true, fmt::format("e = {:.4f}, {:.2f} below its neighbours, z = {:.1f}", best->x, best->prominence, best->z)};
}

// The e_c(3) peak is the most prominent peak of the curve.
Finding e_c3_highest(const analysis::FineStructure& fs) {
  const analysis::Extremum* p3 = feature_at(fs, 3, analysis::ExtremumKind::Peak);
  if (!p3) return {false, "no peak at e_c(3)"};
  const analysis::Extremum* other = nullptr;
  auto consider = [&](const analysis::Extremum& x) {
    if (x.kind == analysis::ExtremumKind::Peak && x.x != p3->x && (!other || x.prominence > other->prominence)) other = &x;
  };
  for (const auto& c : fs.at_critical)
    for (const auto& x : c.extrema) consider(x);
  for (const auto& x : fs.elsewhere) consider(x);
  if (!other) return {true, fmt::format("the only peak ({:.2f})", p3->prominence)};
  return {p3->prominence > other->prominence,
          fmt::format("{:.2f} against {:.2f} at e = {:.4f}", p3->prominence, other->prominence, other->x)};
}

Finding broad_finding(const analysis::FineStructure& fs, int N) {
  const auto& b = fs.near_next;
  if (b.z == 0 && b.x == 0) return {false, ""};
  return {b.found, fmt::format("highest e in e_c({}) ± 0.05: {:.4f}, z = {:.1f} above the window's edges", N + 1, b.x, b.z)};
}

// n_coll(e) at one e against k for one replica, k ascending.
Curve n_of_k(const std::map<double, std::map<int, Curve>>& by_k, int replica, double e) {
  Curve out;
  for (const auto& [k, by_r] : by_k) {
    const auto r = by_r.find(replica);
    if (r == by_r.end()) continue;
    for (const auto& p : r->second)
      if (std::abs(p.x - e) < 5e-5) out.push_back({k, p.y, p.error});
  }
  return out;
}

// The height of the e_c(3) sample above the mean of its two neighbours, against k.
Curve peak_height_of_k(const std::map<double, std::map<int, Curve>>& by_k, int replica) {
  Curve out;
  for (const auto& [k, by_r] : by_k) {
    const auto r = by_r.find(replica);
    if (r == by_r.end()) continue;
    const Curve& c = r->second;
    for (std::size_t i = 1; i + 1 < c.size(); ++i)
      if (std::abs(c[i].x - theory::ec_free(3)) < 5e-5)
        out.push_back({k, c[i].y - 0.5 * (c[i - 1].y + c[i + 1].y),
                       std::sqrt(c[i].error * c[i].error + 0.25 * (c[i - 1].error * c[i - 1].error + c[i + 1].error * c[i + 1].error))});
  }
  return out;
}

std::string increments_text(const analysis::GrowthPerDecade& g) {
  std::string s;
  for (const auto& i : g.increments) s += fmt::format("{}{:.3f}", s.empty() ? "" : ", ", i.dy);
  return s;
}

// Growth faster than log k: the increment per decade rises (last against first by > 3 sigma).
Finding faster_than_log(const Curve& y) {
  const analysis::GrowthPerDecade g = analysis::growth_per_decade(y);
  if (g.increments.size() < 2) return {false, "too few k"};
  return {g.rising_z > 3, fmt::format("per decade {}; rise z = {:.1f}", increments_text(g), g.rising_z)};
}
// Logarithmic growth: increments per decade positive and without a significant trend.
Finding like_log(const Curve& y) {
  const analysis::GrowthPerDecade g = analysis::growth_per_decade(y);
  if (g.increments.size() < 2) return {false, "too few k"};
  const bool positive = std::all_of(g.increments.begin(), g.increments.end(), [](const analysis::Increment& i) { return i.dy > 0; });
  return {positive && std::abs(g.rising_z) <= 3, fmt::format("per decade {}; trend z = {:.1f}", increments_text(g), g.rising_z)};
}

}  // namespace

std::string fine_structure_report(const std::string& db, const std::vector<SweepPoint>& points) {
  const SmallNCurves curves = read_curves(db, points);
  if (curves.empty()) return "";
  std::string md;
  bool header = false;
  for (const auto& [N, by_k] : curves) {
    const double k = by_k.rbegin()->first;
    const auto& at_k = by_k.rbegin()->second;
    std::vector<int> replicas;
    for (const auto& [r, c] : at_k)
      if (r != kCombined) replicas.push_back(r);
    if (!header) {
      md += fmt::format(
          "### The fine structure of n_coll(e) at k = {} (Sec. III.B)\n\n"
          "Each statement of the paper tested on the curve at the largest k: both seeds together, then each seed alone. A peak "
          "(dip) is a sample above (below) both of its neighbours by more than 3 standard errors of the difference, counted at "
          "e_c(n) when within ±0.0105 of it; a broad peak near e_c(N+1) is a maximum within e_c(N+1) ± 0.05 that exceeds the "
          "curve at both edges of that window by 3 standard errors; growth per decade of k compares the last increment with the "
          "first (docs/analysis.md).\n\n"
          "| N | the paper | both seeds | {} |\n|---|---|---|{}\n",
          power_of_ten_text(k), replicas.size() > 1 ? "seed 1 | seed 2" : "seed 1", replicas.size() > 1 ? "---|---|" : "---|");
      header = true;
    }
    auto row = [&](const std::string& statement, auto&& finding) {
      md += fmt::format("| {} | {} | {} |", N, statement, cell(finding(kCombined)));
      for (int r : replicas) md += fmt::format(" {} |", cell(finding(r)));
      md += "\n";
    };
    std::map<int, analysis::FineStructure> fs;
    for (const auto& [r, c] : at_k) fs[r] = analysis::find_fine_structure(N, c);
    for (int n = 3; n <= std::max(3, N - 1); ++n)
      row(fmt::format("sharp peak at e_c({}) = {:.4f}", n, theory::ec_free(n)),
          [&](int r) { return extremum_finding(fs[r], n, analysis::ExtremumKind::Peak); });
    if (N > 3) row("the peak at e_c(3) is the highest", [&](int r) { return e_c3_highest(fs[r]); });
    if (N == 3) row(fmt::format("dip at e_c(4) = {:.4f}", theory::ec_free(4)), [&](int r) {
      return extremum_finding(fs[r], 4, analysis::ExtremumKind::Dip);
    });
    if (N > 3)
      row(fmt::format("dip at or slightly above e_c({}) = {:.4f} (up to +0.025)", N, theory::ec_free(N)),
          [&](int r) { return dip_at_or_above(fs[r], N); });
    if (N > 3)
      row(fmt::format("broad peak near e_c({}) = {:.4f}", N + 1, theory::ec_free(N + 1)), [&](int r) { return broad_finding(fs[r], N); });
    if (N == 3) {
      row("n_coll at e = 0.0718 grows faster than log k", [&](int r) { return faster_than_log(n_of_k(by_k, r, 0.0718)); });
      row("the e_c(3) peak's height above its neighbours grows faster than log k",
          [&](int r) { return faster_than_log(peak_height_of_k(by_k, r)); });
      row("below e_c(3) (e = 0.05) n_coll grows by a nearly constant amount per decade",
          [&](int r) { return like_log(n_of_k(by_k, r, 0.05)); });
    }
    // Reproducibility: the two seeds' curves at every k, and the structure outside the windows.
    if (replicas.size() > 1) {
      const analysis::ReplicaAgreement a = analysis::compare_replicas(at_k.at(replicas[0]), at_k.at(replicas[1]));
      std::string per_k;
      for (const auto& [kk, by_r] : by_k)
        if (by_r.count(replicas[0]) && by_r.count(replicas[1])) {
          const auto x = analysis::compare_replicas(by_r.at(replicas[0]), by_r.at(replicas[1]));
          per_k += fmt::format("{}{}: {:.2f}", per_k.empty() ? "" : ", ", power_of_ten_text(kk), x.chi2 / std::max(1, x.dof));
        }
      md += fmt::format("| {} | reproducible under a change of random numbers | χ²/dof of seed 1 − seed 2 at k = {}: {:.2f} "
                        "({} e, z = {:.1f}); per k: {} | extrema of seed 1 recurring in seed 2: {} of {} | |\n",
                        N, power_of_ten_text(k), a.chi2 / std::max(1, a.dof), a.dof, a.chi2_z, per_k, a.recurring_in_b, a.extrema_a);
    }
    std::string windows;
    for (const auto& c : fs[kCombined].at_critical)
      for (const auto& x : c.extrema)
        windows += fmt::format("{}e_c({}): {} at {:.4f} ({:.2f}, z = {:.1f})", windows.empty() ? "" : "; ", c.n,
                               analysis::extremum_kind_name(x.kind), x.x, x.prominence, x.z);
    md += fmt::format("| {} | every extremum within ±0.0105 of an e_c(n), n = 3 … {} | {} |", N, N + 1, windows.empty() ? "none" : windows);
    for (std::size_t i = 0; i < replicas.size(); ++i) md += " |";
    md += "\n";
    std::string elsewhere;
    for (const auto& x : fs[kCombined].elsewhere)
      elsewhere += fmt::format("{}{} at {:.4f} (z = {:.1f})", elsewhere.empty() ? "" : ", ", analysis::extremum_kind_name(x.kind), x.x, x.z);
    md += fmt::format("| {} | other structure (outside every e_c(n) window) | {} |", N, elsewhere.empty() ? "none" : elsewhere);
    for (std::size_t i = 0; i < replicas.size(); ++i) md += " |";
    md += "\n";
  }
  return md + "\n";
}

}  // namespace granchain
