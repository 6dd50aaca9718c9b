#include "analysis/alpha_across_n.hpp"

#include <algorithm>
#include <cmath>

#include "analysis/least_squares.hpp"

namespace granchain::analysis {

namespace {
void sort_by_n(std::vector<ColumnExponents>& columns) {
  std::sort(columns.begin(), columns.end(), [](const ColumnExponents& a, const ColumnExponents& b) { return a.N < b.N; });
}
}  // namespace

std::vector<NeighbourSlope> neighbour_slopes(std::vector<ColumnExponents> columns) {
  sort_by_n(columns);
  std::vector<NeighbourSlope> out;
  for (std::size_t i = 0; i + 1 < columns.size(); ++i) {
    const ColumnExponents &a = columns[i], &b = columns[i + 1];
    const double span = std::log10(static_cast<double>(b.N) / a.N);
    if (!(span > 0)) continue;
    std::vector<DataPoint> slopes;
    for (const auto& [e, pa] : a.by_e) {
      const auto pb = b.by_e.find(e);
      if (pb == b.by_e.end()) continue;
      slopes.push_back({e, (pb->second.y - pa.y) / span, std::hypot(pa.error, pb->second.error) / span});
    }
    if (slopes.empty()) continue;
    const Mean m = mean_exponent(slopes);
    out.push_back({a.N, b.N, m.value, m.error, static_cast<int>(slopes.size())});
  }
  return out;
}

bool excess_over_line(std::vector<ColumnExponents> columns, LineExcess& out) {
  sort_by_n(columns);
  if (columns.size() < 3) return false;
  const ColumnExponents& last = columns.back();
  out = LineExcess{};
  out.N = last.N;
  for (std::size_t i = 0; i + 1 < columns.size(); ++i) out.others.push_back(columns[i].N);
  const double x0 = std::log10(static_cast<double>(last.N));
  for (const auto& [e, p] : last.by_e) {
    std::vector<double> xs, ys, errs;
    for (std::size_t i = 0; i + 1 < columns.size(); ++i)
      if (const auto q = columns[i].by_e.find(e); q != columns[i].by_e.end() && q->second.error > 0) {
        xs.push_back(std::log10(static_cast<double>(columns[i].N)));
        ys.push_back(q->second.y);
        errs.push_back(q->second.error);
      }
    if (xs.size() < 2) continue;
    const auto n = static_cast<Eigen::Index>(xs.size());
    Eigen::MatrixXd X(n, 2);
    Eigen::VectorXd y(n), err(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      X(i, 0) = 1.0;
      X(i, 1) = xs[i];
      y(i) = ys[i];
      err(i) = errs[i];
    }
    const LeastSquares fit = weighted_least_squares(X, y, err);
    const Eigen::Vector2d at(1.0, x0);
    double var = at.dot(fit.covariance * at);
    if (n > 2) var *= std::max(1.0, fit.chi2 / static_cast<double>(n - 2));
    out.per_e.push_back({e, p.y - at.dot(fit.coef), std::sqrt(var + p.error * p.error)});
  }
  if (out.per_e.empty()) return false;
  const Mean m = mean_exponent(out.per_e);
  out.excess = m.value;
  out.error = m.error;
  return true;
}

}  // namespace granchain::analysis
