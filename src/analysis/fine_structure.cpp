#include "analysis/fine_structure.hpp"

#include <algorithm>
#include <cmath>

#include "analysis/blocking.hpp"
#include "theory/collapse_theory.hpp"

namespace granchain::analysis {

const char* extremum_kind_name(ExtremumKind k) { return k == ExtremumKind::Peak ? "peak" : "dip"; }

std::vector<Extremum> significant_extrema(const std::vector<DataPoint>& c, double z) {
  std::vector<Extremum> out;
  for (std::size_t i = 1; i + 1 < c.size(); ++i) {
    const DataPoint &l = c[i - 1], &p = c[i], &r = c[i + 1];
    if (!(l.error > 0) || !(p.error > 0) || !(r.error > 0)) continue;
    const double sl = std::hypot(p.error, l.error), sr = std::hypot(p.error, r.error);
    for (const ExtremumKind kind : {ExtremumKind::Peak, ExtremumKind::Dip}) {
      const double sign = kind == ExtremumKind::Peak ? 1.0 : -1.0;
      const double dl = sign * (p.y - l.y), dr = sign * (p.y - r.y);
      const double zi = std::min(dl / sl, dr / sr);
      if (zi > z) out.push_back({kind, p.x, p.y, p.error, zi, std::min(dl, dr)});
    }
  }
  return out;
}

namespace {

// The curve linearly interpolated at x, with the error of the interpolation (the two samples'
// errors weighted as in the interpolation); the nearest end sample outside the sampled range.
DataPoint interpolate(const std::vector<DataPoint>& c, double x) {
  if (x <= c.front().x) return c.front();
  if (x >= c.back().x) return c.back();
  const auto hi = std::lower_bound(c.begin(), c.end(), x, [](const DataPoint& p, double v) { return p.x < v; });
  const auto lo = hi - 1;
  const double w = (x - lo->x) / (hi->x - lo->x);
  return {x, (1 - w) * lo->y + w * hi->y, std::hypot((1 - w) * lo->error, w * hi->error)};
}

}  // namespace

BroadPeak broad_peak(const std::vector<DataPoint>& c, double centre, double half_width, double z) {
  BroadPeak out;
  const DataPoint* top = nullptr;
  for (const auto& p : c)
    if (std::abs(p.x - centre) <= half_width && (!top || p.y > top->y)) top = &p;
  if (!top || c.size() < 3) return out;
  const DataPoint left = interpolate(c, centre - half_width), right = interpolate(c, centre + half_width);
  const double zl = (top->y - left.y) / std::hypot(top->error, left.error);
  const double zr = (top->y - right.y) / std::hypot(top->error, right.error);
  out.x = top->x;
  out.y = top->y;
  out.z = std::min(zl, zr);
  out.found = std::isfinite(out.z) && out.z > z;
  return out;
}

FineStructure find_fine_structure(int N, const std::vector<DataPoint>& curve, double window, double broad_half_width,
                                  double z) {
  FineStructure fs;
  fs.N = N;
  for (int n = 3; n <= N + 1; ++n) fs.at_critical.push_back({n, theory::ec_free(n), {}});
  for (const Extremum& x : significant_extrema(curve, z)) {
    bool placed = false;
    for (auto& c : fs.at_critical)
      if (std::abs(x.x - c.e_c) <= window) {
        c.extrema.push_back(x);
        placed = true;
      }
    if (!placed) fs.elsewhere.push_back(x);
  }
  fs.near_next = broad_peak(curve, theory::ec_free(N + 1), broad_half_width, z);
  return fs;
}

ReplicaAgreement compare_replicas(const std::vector<DataPoint>& a, const std::vector<DataPoint>& b, double z, double z_recur) {
  ReplicaAgreement out;
  std::vector<DataPoint> a_common, b_common;  // both curves at their common x, in order
  for (const auto& p : a) {
    const auto q = std::find_if(b.begin(), b.end(), [&](const DataPoint& s) { return std::abs(s.x - p.x) <= 1e-12; });
    if (q == b.end() || !(p.error > 0) || !(q->error > 0)) continue;
    a_common.push_back(p);
    b_common.push_back(*q);
    out.chi2 += std::pow(p.y - q->y, 2) / (p.error * p.error + q->error * q->error);
  }
  out.dof = static_cast<int>(a_common.size());
  out.chi2_z = chi2_normal_deviate(out.chi2, out.dof);
  const auto in_b = significant_extrema(b_common, z_recur);
  for (const Extremum& x : significant_extrema(a_common, z)) {
    ++out.extrema_a;
    const auto at = std::find_if(a_common.begin(), a_common.end(), [&](const DataPoint& p) { return p.x == x.x; }) - a_common.begin();
    const bool recurs = std::any_of(in_b.begin(), in_b.end(), [&](const Extremum& y) {
      if (y.kind != x.kind) return false;
      const auto j = std::find_if(b_common.begin(), b_common.end(), [&](const DataPoint& p) { return p.x == y.x; }) - b_common.begin();
      return std::abs(j - at) <= 1;
    });
    out.recurring_in_b += recurs;
  }
  return out;
}

GrowthPerDecade growth_per_decade(const std::vector<DataPoint>& y) {
  GrowthPerDecade g;
  for (std::size_t i = 1; i < y.size(); ++i) {
    const double decades = std::log10(y[i].x / y[i - 1].x);
    if (!(decades > 0)) continue;
    g.increments.push_back({y[i - 1].x, y[i].x, (y[i].y - y[i - 1].y) / decades, std::hypot(y[i].error, y[i - 1].error) / decades});
  }
  if (g.increments.size() >= 2) {
    const Increment &f = g.increments.front(), &l = g.increments.back();
    // The first and last increments share a sample only when there are two of them: then
    // (y2 - y1)/d2 - (y1 - y0)/d1 carries y1 with weight 1/d1 + 1/d2.
    double err = std::hypot(f.error, l.error);
    if (g.increments.size() == 2) {
      const double d1 = std::log10(f.k2 / f.k1), d2 = std::log10(l.k2 / l.k1);
      err = std::sqrt(std::pow(y[0].error / d1, 2) + std::pow(y[1].error * (1 / d1 + 1 / d2), 2) + std::pow(y[2].error / d2, 2));
    }
    g.rising_z = err > 0 ? (l.dy - f.dy) / err : 0.0;
  }
  return g;
}

}  // namespace granchain::analysis
