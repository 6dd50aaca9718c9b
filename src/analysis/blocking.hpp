#pragma once
// Statistical errors of time averages from one long run, by blocking (Flyvbjerg & Petersen,
// J. Chem. Phys. 91, 461 (1989)) with a jackknife inside each level so that non-linear
// estimators (ratios, standard deviations) get errors too.
//
// The measuring window is cut into B equal fine bins (B a power of two); each bin holds the sums
// of a few components (counts, time, sum of z, ...). Level l merges 2^l neighbouring bins into
// n_l = B / 2^l blocks and estimates the standard error by the jackknife over those blocks.
// Correlated data make the estimate grow with l until blocks are longer than the correlation
// time, then it stays flat (the plateau). The selected level is the lowest one that no higher
// level (with at least min_blocks blocks) exceeds by more than two of its own standard errors,
// sigma_l / sqrt(2 (n_l - 1)), and whose block values have a lag-1 autocorrelation below
// 2/sqrt(n_l) (blocks indistinguishable from independent ones). If no level below the last
// qualifies, the plateau was not seen: the last level's error is reported, flagged as not
// converged (the error bar is then a lower bound).
#include <functional>
#include <span>
#include <utility>
#include <vector>

#include "model/state_archive_fwd.hpp"

namespace granchain {

struct Estimate {
  double value = 0.0;
  double error = 0.0;      // one standard error
  int blocks = 0;          // number of blocks at the selected level
  bool converged = false;  // a plateau of the blocking curve was found
};

// Sums of `components` quantities in each of `bins` fine bins, row-major.
class BinnedSums {
 public:
  BinnedSums(int bins, int components);
  int bins() const { return bins_; }
  int components() const { return components_; }
  double* bin(int b) { return data_.data() + static_cast<std::size_t>(b) * components_; }
  const double* bin(int b) const { return data_.data() + static_cast<std::size_t>(b) * components_; }
  std::vector<double> totals() const;
  // Every bin's sums (model/state_archive.hpp); restore requires the same bins and components.
  void save(StateArchive& out) const;
  void restore(const StateArchive& in);

 private:
  int bins_, components_;
  std::vector<double> data_;
};

// Maps summed components (over any set of bins) to the estimated quantity.
using Estimator = std::function<double(std::span<const double>)>;

struct BlockingLevel {
  int blocks;
  double error;  // jackknife standard error with this many blocks
  double lag1;   // lag-1 autocorrelation of the block values
};

// Blocking curve: the jackknife standard error at every level with >= min_blocks blocks.
std::vector<BlockingLevel> blocking_curve(const BinnedSums& sums, const Estimator& f,
                                          int min_blocks = 16);

// Value on all data and its standard error from the plateau of the blocking curve.
Estimate blocked_estimate(const BinnedSums& sums, const Estimator& f, int min_blocks = 16);

// Is the time average stationary over the window? The estimate on the first and on the second
// half of the bins, each with its blocked error, and their difference measured twice:
//   z         = (second - first) / sqrt(err1^2 + err2^2), both halves' own errors;
//   z_settled = (second - first) / (sqrt(2) err2), against the spread the difference would have if
//               the first half fluctuated as the second does.
// A window that starts before the column has settled holds a relaxation in its first half; the
// blocked error of that half grows with the drift itself (its blocks differ), so z stays small
// while z_settled sees the drift. Stationary means |z| <= z_max and |z_settled| <= z_max (3: a
// settled system fails a few runs in 1000 when the errors are right, the two tests being nearly
// the same there). Where an error is zero (no spread, e.g. no event at all) the halves must be
// equal.
struct StationarityCheck {
  Estimate first, second;
  double z = 0.0;
  double z_settled = 0.0;
  bool stationary = true;
};
StationarityCheck halves_check(const BinnedSums& sums, const Estimator& f, double z_max = 3.0);
// The verdict on two halves already estimated (as a stored run keeps them): z, z_settled and
// stationary as halves_check gives them.
StationarityCheck judge_halves(const Estimate& first, const Estimate& second, double z_max = 3.0);

// Largest power of two <= min(limit, n), at least 1.
int power_of_two_bins(long long n, int limit);

// Mean of independent values and its standard error (sample standard deviation / sqrt(n)),
// two-pass; NaN where undefined (no value, or one value for the error).
std::pair<double, double> mean_and_error(const std::vector<double>& x);

// The normal deviate of a chi^2 with `dof` degrees of freedom (Wilson-Hilferty: (chi2/dof)^(1/3)
// is nearly normal), about N(0, 1) when the chi^2 is what its errors predict; 0 without dof.
double chi2_normal_deviate(double chi2, int dof);

// A check of error bars against independent replicas: each group holds (value, error) of m >= 2
// independent runs of one point; chi^2 = sum_i (x_i - xbar)^2 / err_i^2 with xbar the weighted
// mean has m - 1 degrees of freedom when the errors are right. Summed over the groups, chi2/dof
// is about 1 (chi2_z about N(0, 1)); above 1 the errors are too small by about sqrt(chi2/dof).
// Groups with fewer than two runs or a non-positive error are skipped. `worst` is the index of
// the group with the largest chi2 / (m - 1).
struct ReplicaScatter {
  int groups = 0, runs = 0, dof = 0;
  double chi2 = 0, chi2_z = 0;
  int worst = -1;
  double worst_ratio = 0;
};
ReplicaScatter replica_scatter(const std::vector<std::vector<std::pair<double, double>>>& groups);

// The same check level by level of the blocking curve: where the replicas scatter more than the
// reported errors say, would longer blocks have seen it? Each group holds the runs of one point
// that carry a curve: n_coll, the reported error and the curve. At each block count that every
// run's curve has, chi^2_l = sum over points and runs of (x_i - xbar_l)^2 / SE_l,i^2 about the mean
// weighted by those errors (m - 1 degrees of freedom per point). chi2_l / dof falls toward 1 at the
// level whose blocks outlast the correlations; where it stays above 1 at the longest blocks (16 per
// window), the column has states that outlast T / 16, which blocking within one run cannot see.
struct LevelScatter {
  int blocks = 0;
  double chi2 = 0;
};
struct CurveScatter {
  int groups = 0, runs = 0, dof = 0;
  double chi2_reported = 0;  // with the reported errors, as replica_scatter
  std::vector<LevelScatter> levels;  // longest blocks last
};
struct ReplicaRun {
  double value = 0, error = 0;
  std::vector<BlockingLevel> curve;
};
CurveScatter replica_scatter_by_level(const std::vector<std::vector<ReplicaRun>>& groups);

}  // namespace granchain
