#include "analysis/critical_restitution.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace granchain::analysis {

namespace {

struct Slopes {
  std::vector<DataPoint> b_of_e;  // every classified e: b (uncollapsing ones with their raw b)
  std::vector<bool> uncollapsing;
  double residual = 0, residual_error = 0;
  bool has_boundary = false;
  double last_collapsing = 0, first_uncollapsing = 0;
  std::vector<double> isolated;  // collapsing e above the boundary, counted as uncollapsing
};

Slopes slopes_over(const std::vector<Curve>& curves, int N, double k_min, double z) {
  Slopes s;
  std::vector<std::pair<double, bool>> regimes;  // e, uncollapsing
  for (const Curve& c : curves) {
    int asymptotic = 0;
    for (const DataPoint& p : c.n_coll_of_k) asymptotic += p.x >= k_min;
    if (asymptotic < 3) continue;
    const Classification cl = classify(c.n_coll_of_k, k_min, z);
    const bool unc = cl.regime == Regime::Uncollapsing;
    s.b_of_e.push_back({c.e, cl.log_fit.b, cl.log_fit.b_error});
    s.uncollapsing.push_back(unc);
    regimes.emplace_back(c.e, unc);
  }
  std::sort(regimes.begin(), regimes.end());
  // The boundary, scanning down from the largest e: the first collapsing e that is not isolated
  // (an isolated one has uncollapsing neighbours on both sides: a slope 2 errors above zero happens
  // by chance in one curve of 40), and the next e of the grid above it. Isolated collapsing e above
  // the boundary are counted apart and enter the fit as b = 0.
  const std::size_t n = regimes.size();
  for (std::size_t i = n; i-- > 0;) {
    if (regimes[i].second) continue;
    const bool isolated = i > 0 && i + 1 < n && regimes[i - 1].second && regimes[i + 1].second;
    if (isolated) continue;
    s.last_collapsing = regimes[i].first;
    s.has_boundary = i + 1 < n;
    if (s.has_boundary) s.first_uncollapsing = regimes[i + 1].first;
    break;
  }
  for (std::size_t j = 0; j < s.b_of_e.size(); ++j) {
    if (s.has_boundary && !s.uncollapsing[j] && s.b_of_e[j].x > s.first_uncollapsing) {
      s.uncollapsing[j] = true;
      s.isolated.push_back(s.b_of_e[j].x);
    }
  }
  // The finite-k residual: weighted mean b of the uncollapsing curves at least 1/N (the width of
  // the critical region, Eq. e-fit) above the last collapsing e; closer ones may still collapse
  // with slopes too small to resolve.
  double sw = 0, swb = 0;
  for (std::size_t i = 0; i < s.b_of_e.size(); ++i) {
    const DataPoint& p = s.b_of_e[i];
    if (!s.uncollapsing[i] || p.x < s.last_collapsing + 1.0 / N || !(p.error > 0)) continue;
    const double w = 1.0 / (p.error * p.error);
    sw += w;
    swb += w * p.y;
  }
  if (sw > 0) {
    s.residual = std::max(0.0, swb / sw);
    s.residual_error = 1.0 / std::sqrt(sw);
  }
  return s;
}

// b_of_e with the residual subtracted (its error added in quadrature); uncollapsing e count as 0.
std::vector<DataPoint> approach_of_b(const Slopes& s, bool subtract) {
  std::vector<DataPoint> out;
  for (std::size_t i = 0; i < s.b_of_e.size(); ++i) {
    const DataPoint& p = s.b_of_e[i];
    if (s.uncollapsing[i]) {
      out.push_back({p.x, 0.0, p.error});
    } else if (subtract) {
      out.push_back({p.x, p.y - s.residual, std::hypot(p.error, s.residual_error)});
    } else {
      out.push_back(p);
    }
  }
  return out;
}

}  // namespace

E_c1Estimate estimate_e_c1(const std::vector<Curve>& curves, int N, double k_min, double z) {
  E_c1Estimate out;
  const double windows[] = {std::min(0.04, 0.5 / N), std::min(0.08, 1.0 / N), std::min(0.16, 2.0 / N)};
  double lo = INFINITY, hi = -INFINITY;
  bool central_found = false;
  CriticalValue fallback;
  for (const double km : {k_min, 10.0 * k_min}) {
    const Slopes s = slopes_over(curves, N, km, z);
    if (km == k_min) {
      out.residual_b = s.residual;
      out.residual_b_error = s.residual_error;
      out.has_boundary = s.has_boundary;
      out.last_collapsing_e = s.last_collapsing;
      out.first_uncollapsing_e = s.first_uncollapsing;
      out.isolated_collapsing_e = s.isolated;
    }
    if (s.b_of_e.empty()) continue;
    for (const bool subtract : {true, false}) {
      const std::vector<DataPoint> b = approach_of_b(s, subtract);
      for (const double w : windows) {
        ++out.variants;
        const CriticalValue cv = e_c1_from_b(b, w, z);
        if (!cv.found) continue;
        ++out.variants_found;
        lo = std::min(lo, cv.value);
        hi = std::max(hi, cv.value);
        if (km == k_min && subtract && w == windows[1]) {
          out.e_c1 = cv;
          central_found = true;
        } else if (!fallback.found) {
          fallback = cv;
        }
      }
    }
  }
  if (!central_found) out.e_c1 = fallback;  // the first variant found, in the order above
  if (!out.e_c1.found) return out;
  out.statistical = out.e_c1.error;
  out.systematic = out.variants_found > 1 ? 0.5 * (hi - lo) : 0.0;
  out.e_c1.error = std::hypot(out.statistical, out.systematic);
  out.e_c1.low = lo;
  out.e_c1.high = hi;
  out.e_c1.method = fmt::format(
      "root of sqrt(b - b_res) against e (Eq. b_e_N), b_res = {:.3g} ± {:.2g} the finite-k slope of the uncollapsing "
      "side; ± {:.4f} statistical, ± {:.4f} systematic: half the range of {} of {} variants (k >= k_min or 10 k_min; "
      "windows 0.5/N, 1/N, 2/N; b_res subtracted or not){}",
      out.residual_b, out.residual_b_error, out.statistical, out.systematic, out.variants_found, out.variants,
      central_found ? "" : "; the central variant was not found, the first one found stands in");
  return out;
}

CriticalValue classification_boundary(const E_c1Estimate& x) {
  CriticalValue c;
  c.method = "classification boundary";
  if (!x.has_boundary) return c;
  c.low = x.last_collapsing_e;
  c.high = x.first_uncollapsing_e;
  c.value = 0.5 * (c.low + c.high);
  c.error = (c.high - c.low) / std::sqrt(12.0);
  c.grid_rounded = true;
  c.found = true;
  return c;
}

}  // namespace granchain::analysis
