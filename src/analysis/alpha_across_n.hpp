#pragma once
// How the local exponent alpha of one interval of k depends on the column size N, read at the same
// restitution coefficients on both sides so that alpha's dependence on e (Table 1) cancels:
//  - the slope d alpha / d log10 N between neighbouring columns (is alpha(N) one line in log N,
//    Eq. alphafit, or convex / concave?);
//  - the largest column's excess over the line alpha = p log10 N + q through the smaller ones,
//    the line's extrapolation error included (does the largest column keep the law?).
// Per e with the runs' own errors, then the plain mean over e with the larger of the propagated
// error and the scatter's standard error (as Table 1's alpha bar).
#include <map>
#include <vector>

#include "analysis/collapse_regimes.hpp"

namespace granchain::analysis {

// One column's local exponents of one interval of k, by e.
struct ColumnExponents {
  int N = 0;
  std::map<double, DataPoint> by_e;  // e -> (x unused, alpha, error)
};

struct NeighbourSlope {
  int N1 = 0, N2 = 0;
  double slope = 0, error = 0;  // per decade of N
  int e_count = 0;              // the e both columns have
};
// Between each pair of successive columns (sorted by N) that share at least one e.
std::vector<NeighbourSlope> neighbour_slopes(std::vector<ColumnExponents> columns);

struct LineExcess {
  int N = 0;             // the largest column
  std::vector<int> others;  // the columns the lines go through
  double excess = 0, error = 0;  // alpha(N) - line(N), mean over e
  std::vector<DataPoint> per_e;  // x = e
};
// The largest column against, for each of its e, the weighted line through the other columns with
// that e (at least two of them); the prediction's variance from the line's covariance, scaled by
// chi^2/dof where that exceeds 1. Returns false (out unusable) when no e has two other columns.
bool excess_over_line(std::vector<ColumnExponents> columns, LineExcess& out);

}  // namespace granchain::analysis
