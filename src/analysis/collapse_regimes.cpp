#include "analysis/collapse_regimes.hpp"

#include "analysis/least_squares.hpp"
#include <map>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace granchain::analysis {

namespace {

std::vector<DataPoint> transformed(const std::vector<DataPoint>& pts, bool log_y) {
  std::vector<DataPoint> out;
  for (const auto& p : pts) {
    if (!(p.x > 0)) throw std::invalid_argument("fit: k must be positive");
    if (log_y) {
      if (!(p.y > 0)) throw std::invalid_argument("power fit: n_coll must be positive");
      out.push_back({std::log(p.x), std::log(p.y), p.error / p.y});
    } else {
      out.push_back({std::log10(p.x), p.y, p.error});
    }
  }
  return out;
}

}  // namespace

PolynomialFit fit_polynomial(const std::vector<DataPoint>& pts, int degree) {
  const int n = degree + 1;
  if (degree < 1 || degree > 2) throw std::invalid_argument("fit: degree must be 1 or 2");
  if (static_cast<int>(pts.size()) < n) throw std::invalid_argument("fit: too few points for the degree");
  const auto m = static_cast<Eigen::Index>(pts.size());
  Eigen::MatrixXd X(m, n);
  Eigen::VectorXd y(m), err(m);
  for (Eigen::Index r = 0; r < m; ++r) {
    const DataPoint& p = pts[static_cast<std::size_t>(r)];
    if (!(p.error > 0)) throw std::invalid_argument("fit: every point needs a positive error");
    double xi = 1.0;
    for (int i = 0; i < n; ++i, xi *= p.x) X(r, i) = xi;
    y(r) = p.y;
    err(r) = p.error;
  }
  const LeastSquares ls = weighted_least_squares(X, y, err);
  PolynomialFit f;
  f.coef.assign(ls.coef.data(), ls.coef.data() + n);
  f.chi2 = ls.chi2;
  f.dof = static_cast<int>(pts.size()) - n;
  const double scale = f.dof > 0 ? std::max(1.0, f.chi2 / f.dof) : 1.0;
  for (int i = 0; i < n; ++i) f.error.push_back(std::sqrt(ls.covariance(i, i) * scale));
  f.covariance01 = ls.covariance(0, 1) * scale;
  return f;
}

LogFit fit_log_k(const std::vector<DataPoint>& pts) {
  const PolynomialFit f = fit_polynomial(transformed(pts, false), 1);
  return {f.coef[0], f.error[0], f.coef[1], f.error[1], f.chi2, f.dof};
}

PowerFit fit_power_k(const std::vector<DataPoint>& pts) {
  const PolynomialFit f = fit_polynomial(transformed(pts, true), 1);
  const double c = std::exp(f.coef[0]);
  return {c, c * f.error[0], f.coef[1], f.error[1], f.chi2, f.dof};
}

const char* regime_name(Regime r) {
  switch (r) {
    case Regime::Uncollapsing: return "uncollapsing";
    case Regime::Logarithmic: return "logarithmic";
    case Regime::PowerLaw: return "power-law";
  }
  return "";
}

Classification classify(const std::vector<DataPoint>& all, double k_min, double z) {
  std::vector<DataPoint> pts;
  for (const auto& p : all)
    if (p.x >= k_min) pts.push_back(p);
  std::sort(pts.begin(), pts.end(), [](const DataPoint& a, const DataPoint& b) { return a.x < b.x; });
  if (pts.size() < 3) throw std::invalid_argument("classify: needs at least 3 values of k in the asymptotic range");
  Classification c;
  c.log_fit = fit_log_k(pts);
  bool positive = true;
  for (const auto& p : pts) positive = positive && p.y > 0;
  if (positive) c.power_fit = fit_power_k(pts);
  // Three values of k determine the quadratic exactly (the second difference, its error from
  // theirs); the power-law call below still asks for four.
  const PolynomialFit q = fit_polynomial(transformed(pts, false), 2);
  c.curvature = q.coef[2];
  c.curvature_error = q.error[2];
  const DataPoint& p1 = pts[pts.size() - 2];
  const DataPoint& p2 = pts.back();
  const double decades = std::log10(p2.x / p1.x);
  c.last_slope = (p2.y - p1.y) / decades;
  c.last_slope_error = std::hypot(p1.error, p2.error) / decades;
  if (!(c.log_fit.b > z * c.log_fit.b_error) || !(c.last_slope > z * c.last_slope_error)) c.regime = Regime::Uncollapsing;
  else if (pts.size() >= 4 && c.curvature > z * c.curvature_error) c.regime = Regime::PowerLaw;
  else c.regime = Regime::Logarithmic;
  return c;
}

CriticalValue e_c1_from_b(const std::vector<DataPoint>& b_of_e, double window, double z) {
  CriticalValue cv;
  cv.method = "root of a weighted line through sqrt(b) against e (b ~ (e_c1 - e)^2, Eq. b_e_N)";
  double e_max = -1.0;
  for (const auto& p : b_of_e)
    if (p.y > z * p.error) e_max = std::max(e_max, p.x);
  if (e_max < 0) return cv;
  std::vector<DataPoint> roots;
  for (const auto& p : b_of_e)
    if (p.y > z * p.error && p.x >= e_max - window) roots.push_back({p.x, std::sqrt(p.y), p.error / (2.0 * std::sqrt(p.y))});
  if (roots.size() < 2) return cv;
  const PolynomialFit f = fit_polynomial(roots, 1);
  if (!(f.coef[1] < 0)) return cv;  // sqrt(b) must fall as e rises toward e_c1
  cv.value = -f.coef[0] / f.coef[1];
  const double var = (f.error[0] * f.error[0] + 2.0 * cv.value * f.covariance01 + cv.value * cv.value * f.error[1] * f.error[1]) /
                     (f.coef[1] * f.coef[1]);
  cv.error = std::sqrt(std::max(var, 0.0));
  cv.low = cv.high = cv.value;
  // The root must lie beyond the last positive slope, within the window above it, and inside the
  // grid (some e of the grid at or above it, where b was measured not to be positive): a line
  // through two or three points far from the root, or past the end of the grid, extrapolates to
  // nothing reliable.
  double e_top = -INFINITY;
  for (const auto& p : b_of_e) e_top = std::max(e_top, p.x);
  cv.found = cv.value >= e_max && cv.value <= e_max + window && cv.value <= e_top && cv.value <= 1.0;
  return cv;
}

CriticalValue e_c2_from_regimes(const std::vector<double>& e, const std::vector<Regime>& regimes) {
  CriticalValue cv;
  cv.method = "between the largest e classified power-law and the next e of the grid";
  std::vector<std::pair<double, Regime>> sorted;
  for (std::size_t i = 0; i < e.size(); ++i) sorted.emplace_back(e[i], regimes.at(i));
  std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  int last_power = -1;
  for (std::size_t i = 0; i < sorted.size(); ++i)
    if (sorted[i].second == Regime::PowerLaw) last_power = static_cast<int>(i);
  if (last_power < 0 || last_power + 1 >= static_cast<int>(sorted.size())) return cv;
  cv.low = sorted[last_power].first;
  cv.high = sorted[last_power + 1].first;
  cv.value = 0.5 * (cv.low + cv.high);
  cv.error = 0.5 * (cv.high - cv.low);
  cv.grid_rounded = true;
  cv.found = true;
  return cv;
}

CriticalValue e_c2_from_curvature_sign(const std::vector<DataPoint>& curvature_of_e, double half_width, double max_gap) {
  CriticalValue cv;
  cv.method = "zero of the curvature against log10 k: a weighted line through the curvatures around its sign change";
  std::vector<DataPoint> c;
  for (const auto& p : curvature_of_e)
    if (p.error > 0 && std::isfinite(p.y)) c.push_back(p);
  std::sort(c.begin(), c.end(), [](const DataPoint& a, const DataPoint& b) { return a.x < b.x; });
  for (std::size_t i = c.size(); i-- > 1;) {
    if (!(c[i].y <= 0 && c[i - 1].y > 0)) continue;
    const DataPoint& lo = c[i - 1];
    const DataPoint& hi = c[i];
    // Across a gap of the grid wider than max_gap the sign change is not located.
    if (hi.x - lo.x > max_gap) return cv;
    cv.low = lo.x;
    cv.high = hi.x;
    const double mid = 0.5 * (lo.x + hi.x);
    std::vector<DataPoint> near;  // the points within half_width of the bracket
    for (const auto& p : c)
      if (std::abs(p.x - mid) <= half_width + 0.5 * (hi.x - lo.x)) near.push_back({p.x - mid, p.y, p.error});
    if (near.size() >= 3) {
      const PolynomialFit f = fit_polynomial(near, 1);  // curvature = a + b (e - mid)
      const double a = f.coef[0], b = f.coef[1];
      const auto [first, last] = std::minmax_element(near.begin(), near.end(), [](const DataPoint& p, const DataPoint& q) { return p.x < q.x; });
      const double r = b < 0 ? a / b : NAN;
      // A zero outside the points the line was fitted to would be an extrapolation.
      if (std::isfinite(r) && -r >= first->x && -r <= last->x) {
        cv.value = mid - r;
        // delta method for -a/b: var = (var a - 2 r cov(a, b) + r^2 var b) / b^2
        const double var = (f.error[0] * f.error[0] - 2 * r * f.covariance01 + r * r * f.error[1] * f.error[1]) / (b * b);
        cv.error = std::sqrt(std::max(var, 0.0));
        cv.found = true;
        return cv;
      }
    }
    // Too few points for a line (fig6's coarse e = 1 - c/N), a line that does not fall with e, or
    // one whose zero lies outside them: the zero of the straight line through the two bracketing
    // curvatures, with their errors propagated and the rounding of an unknown shape between two
    // grid points, (high - low) / sqrt 12, added in quadrature.
    const double dy = lo.y - hi.y, dx = hi.x - lo.x;
    cv.value = lo.x + dx * lo.y / dy;
    const double d_lo = -dx * hi.y / (dy * dy), d_hi = dx * lo.y / (dy * dy);
    const double statistical = std::hypot(d_lo * lo.error, d_hi * hi.error);
    cv.error = std::hypot(statistical, dx / std::sqrt(12.0));
    cv.method = "zero of the curvature against log10 k: linear interpolation between the two curvatures around its sign change";
    cv.grid_rounded = true;
    cv.found = true;
    return cv;
  }
  return cv;
}

InverseNFit fit_inverse_n(const std::vector<double>& N, const std::vector<CriticalValue>& e_c) {
  std::vector<DataPoint> pts;
  for (std::size_t i = 0; i < N.size(); ++i) {
    if (!e_c.at(i).found) continue;
    const double sigma = std::max(e_c[i].error, 1e-12);
    pts.push_back({1.0 / N[i], 1.0 - e_c[i].value, sigma});
  }
  if (pts.empty()) throw std::invalid_argument("fit_inverse_n: no critical value was found");
  // 1 - e_c = A / N: a line through the origin in x = 1/N.
  const auto m = static_cast<Eigen::Index>(pts.size());
  Eigen::MatrixXd X(m, 1);
  Eigen::VectorXd y(m), err(m);
  for (Eigen::Index r = 0; r < m; ++r) {
    X(r, 0) = pts[static_cast<std::size_t>(r)].x;
    y(r) = pts[static_cast<std::size_t>(r)].y;
    err(r) = pts[static_cast<std::size_t>(r)].error;
  }
  const LeastSquares ls = weighted_least_squares(X, y, err);
  InverseNFit f;
  f.A = ls.coef(0);
  f.chi2 = ls.chi2;
  f.dof = static_cast<int>(pts.size()) - 1;
  const double scale = f.dof > 0 ? std::max(1.0, f.chi2 / f.dof) : 1.0;
  f.A_error = std::sqrt(ls.covariance(0, 0) * scale);
  return f;
}

LineFit fit_alpha_vs_log10_n(const std::vector<DataPoint>& alpha_of_n) {
  std::vector<DataPoint> pts;
  for (const auto& p : alpha_of_n) pts.push_back({std::log10(p.x), p.y, p.error});
  const PolynomialFit f = fit_polynomial(pts, 1);
  return {f.coef[1], f.error[1], f.coef[0], f.error[0], f.chi2, f.dof};
}

ScalingCollapseFit fit_scaling_collapse(const std::vector<ScalingPoint>& points, double A, double z) {
  std::vector<DataPoint> pts;  // x = ln X, y = ln(b / N^{5/2}), error = b_error / b
  for (const auto& p : points) {
    const double X = (1.0 - p.e) - A / p.N;
    if (!(X > 0) || !(p.b_error > 0) || !(p.b > z * p.b_error)) continue;
    pts.push_back({std::log(X), std::log(p.b / std::pow(p.N, 2.5)), p.b_error / p.b});
  }
  if (pts.size() < 3) throw std::invalid_argument("fit_scaling_collapse: fewer than 3 points with X > 0 and b > 0");
  ScalingCollapseFit f;
  f.A = A;
  f.points = static_cast<int>(pts.size());
  const PolynomialFit line = fit_polynomial(pts, 1);
  f.slope = line.coef[1];
  f.slope_error = line.error[1];
  f.prefactor = std::exp(line.coef[0]);
  f.prefactor_error = f.prefactor * line.error[0];
  f.chi2 = line.chi2;
  f.dof = line.dof;
  double sw = 0, swy = 0;  // slope held at 2: ln C2 is the weighted mean of y - 2x
  for (const auto& p : pts) {
    const double w = 1.0 / (p.error * p.error);
    sw += w;
    swy += w * (p.y - 2.0 * p.x);
  }
  const double lnC = swy / sw;
  for (const auto& p : pts) f.chi2_C2 += std::pow((p.y - 2.0 * p.x - lnC) / p.error, 2);
  const int dof2 = f.points - 1;
  f.C2 = std::exp(lnC);
  f.C2_error = f.C2 * std::sqrt(std::max(1.0, f.chi2_C2 / dof2) / sw);
  return f;
}

Mean mean_exponent(const std::vector<DataPoint>& alphas) {
  if (alphas.empty()) throw std::invalid_argument("mean_exponent: no values");
  const double n = static_cast<double>(alphas.size());
  Mean m;
  double var = 0;
  for (const auto& a : alphas) {
    m.value += a.y / n;
    var += a.error * a.error;
  }
  const double propagated = std::sqrt(var) / n;
  double ss = 0;
  for (const auto& a : alphas) ss += (a.y - m.value) * (a.y - m.value);
  const double scatter = alphas.size() > 1 ? std::sqrt(ss / (n - 1) / n) : 0.0;
  m.error = std::max(propagated, scatter);
  return m;
}

std::vector<LocalExponent> local_exponents(const std::vector<DataPoint>& n) {
  std::vector<LocalExponent> out;
  for (std::size_t i = 0; i + 1 < n.size(); ++i) {
    const DataPoint &a = n[i], &b = n[i + 1];
    if (!(a.y > 0 && b.y > 0 && b.x > a.x)) continue;
    const double span = std::log(b.x / a.x);
    out.push_back({a.x, b.x, std::log(b.y / a.y) / span, std::hypot(a.error / a.y, b.error / b.y) / span});
  }
  return out;
}

std::vector<LocalExponent> mean_local_exponents(const std::vector<std::vector<LocalExponent>>& curves) {
  std::map<std::pair<double, double>, std::vector<DataPoint>> by_interval;
  for (const auto& c : curves)
    for (const LocalExponent& l : c)
      if (l.error > 0) by_interval[{l.k1, l.k2}].push_back({0.0, l.alpha, l.error});
  std::vector<LocalExponent> out;
  for (const auto& [k, xs] : by_interval) {
    const Mean m = mean_exponent(xs);
    out.push_back({k.first, k.second, m.value, m.error});
  }
  return out;
}

}  // namespace granchain::analysis
