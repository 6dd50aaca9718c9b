// The runs of one point combined into one n_coll and its error (analysis/regime_report.hpp):
// the pooled rate over the runs' windows, with the replicas' scatter where it exceeds blocking's.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "analysis/regime_report.hpp"

using namespace granchain;
using namespace granchain::analysis;

namespace {
const std::vector<double> kGrid = {1e5, 1e6, 1e7, 1e8, 1e9, 1e10};
}

// Equal windows and errors: the mean, and from four runs on the error widened by the Birge ratio
// where the runs scatter more than their errors say, never narrowed.
TEST(CombineReplicas, ReplicasThatScatterMoreThanTheirErrorsWidenTheCombinedError) {
  // Four runs with errors 1: chi^2 = (1.5^2 + 0.5^2) * 2 = 5 on 3 dof -> 0.5 x sqrt(5/3).
  const auto [mean, err] = combine_replicas({{8.5, 1.0, 100}, {9.5, 1.0, 100}, {10.5, 1.0, 100}, {11.5, 1.0, 100}});
  EXPECT_DOUBLE_EQ(mean, 10.0);
  EXPECT_NEAR(err, 0.5 * std::sqrt(5.0 / 3.0), 1e-12);
  // The same runs with errors 2: chi^2 = 1.25 on 3 dof, below 1 per dof: the blocking error stands.
  EXPECT_NEAR(combine_replicas({{8.5, 2.0, 100}, {9.5, 2.0, 100}, {10.5, 2.0, 100}, {11.5, 2.0, 100}}).second, 1.0, 1e-12);
  // One run is itself; two or three keep the propagated blocking error however they scatter.
  EXPECT_EQ(combine_replicas({{3.0, 0.5, 100}}), std::make_pair(3.0, 0.5));
  EXPECT_NEAR(combine_replicas({{0.0, 1.0, 50}, {10.0, 1.0, 50}, {20.0, 1.0, 50}}).second, 1.0 / std::sqrt(3.0), 1e-12);
  // Through the analysis: n_coll(k) of a point with scattering replicas carries the wider error.
  std::vector<NcollRun> runs;
  for (double k : kGrid)
    for (double dx : {-1.5, -0.5, 0.5, 1.5}) runs.push_back({EngineKind::Exact, 25, 1.0, 0.5, k, 100.0 + dx, 1.0, true});
  const RegimeReport r = analyze_runs(runs, 1e6);
  ASSERT_EQ(r.families.size(), 1u);
  for (const auto& p : r.families[0].curves[0].n_coll_of_k) EXPECT_NEAR(p.error, 0.5 * std::sqrt(5.0 / 3.0), 1e-12);
}

// Windows of different length: the collisions of all windows over their total time, each window's
// blocking error weighted by its length. Unequal errors do not weight the mean.
TEST(CombineReplicas, RunsAreWeightedByTheirWindows) {
  const auto [mean, err] = combine_replicas({{1.0, 0.1, 100}, {2.0, 0.1, 300}});
  EXPECT_NEAR(mean, (100 * 1.0 + 300 * 2.0) / 400, 1e-12);
  EXPECT_NEAR(err, std::sqrt(100.0 * 100 * 0.01 + 300.0 * 300 * 0.01) / 400, 1e-12);
  const auto [m2, e2] = combine_replicas({{1.0, 1.0, 100}, {2.0, 0.5, 100}});
  EXPECT_NEAR(m2, 1.5, 1e-12);
  EXPECT_NEAR(e2, std::sqrt(1.0 + 0.25) / 2, 1e-12);
  // A window that is not known (T <= 0 in any run) weights every run alike.
  EXPECT_NEAR(combine_replicas({{1.0, 0.1, 0}, {2.0, 0.1, 300}}).first, 1.5, 1e-12);
}

// A column whose collisions come in bursts: a window's count and its blocking error grow together
// (error 10 % of the value here), so inverse-variance weights would favour the quiet windows and
// bias the mean low (to about half of it for these windows: E[1/n] / E[1/n^2] against E[n]). The pooled
// rate of 12 windows, drawn from a skewed distribution of mean mu (Gamma of shape 4, relative
// standard deviation 1/2), is unbiased: over 4000 points its average lies within 4 standard errors
// of mu (standard error mu / 2 / sqrt(12 x 4000)), and its error, from the windows' scatter,
// covers mu in the fraction of points that 11 degrees of freedom give (P(|t_11| < 1) = 0.661),
// within 4 binomial standard deviations (0.0075).
TEST(CombineReplicas, BurstyWindowsGiveAnUnbiasedMeanAndErrorsThatCover) {
  std::mt19937_64 rng(20261128);
  std::gamma_distribution<double> gamma(4.0, 0.25);  // mean 1, standard deviation 1/2
  const double mu = 0.62;
  const int points = 4000, windows = 12;
  double sum = 0, inverse_variance_sum = 0;
  int covered = 0;
  for (int p = 0; p < points; ++p) {
    std::vector<PointRun> runs;
    double w = 0, wn = 0;
    for (int i = 0; i < windows; ++i) {
      const double n = mu * gamma(rng);
      runs.push_back({n, 0.1 * n, 200});
      w += 1 / (0.01 * n * n);
      wn += n / (0.01 * n * n);
    }
    const auto [mean, err] = combine_replicas(runs);
    sum += mean;
    inverse_variance_sum += wn / w;
    covered += std::abs(mean - mu) < err;
  }
  const double se = mu * 0.5 / std::sqrt(static_cast<double>(points * windows));
  EXPECT_LT(std::abs(sum / points - mu), 4 * se);
  EXPECT_NEAR(static_cast<double>(covered) / points, 0.661, 4 * 0.0075);
  // The weights the pooled rate replaces are biased by many standard errors on the same windows.
  EXPECT_LT(inverse_variance_sum / points, mu - 20 * se);
}

// Windows that had not settled: where a point has stationary runs after a longer transient, all its
// runs after a shorter transient that some of them fail are left out, named with the reason (the
// passing ones started from the same unsettled column). A shorter transient whose runs all pass
// stays; so does a non-stationary run beside stationary runs of its own transient (a settled column
// fails the check now and then), marked, and one whose point has no settled run at all.
TEST(CombineReplicas, SettledRunsWithALongerTransientSupersedeUnsettledOnes) {
  std::vector<NcollRun> runs;
  std::int64_t id = 0;
  const auto add = [&](double k, double n, bool stationary, double transient) {
    NcollRun r{EngineKind::Exact, 200, 1.0, 0.2, k, n, 1.0, stationary, ++id};
    r.transient = transient;
    r.T = 200;
    runs.push_back(r);
  };
  for (double k : kGrid) {
    if (k == 1e5) {  // three windows after 20 (two flagged, all biased high), four settled ones after 200
      add(k, 130.0, false, 20);
      add(k, 126.0, false, 20);
      add(k, 110.0, true, 20);
      for (double dx : {-1.5, -0.5, 0.5, 1.5}) add(k, 100.0 + dx, true, 200);
    } else if (k == 1e6) {  // a settled point whose third run fails the check by chance
      add(k, 110.0, true, 20);
      add(k, 110.5, true, 20);
      add(k, 113.0, false, 20);
    } else if (k == 1e7) {  // no settled run: the unsettled one is all there is
      add(k, 120.0, false, 20);
    } else if (k == 1e8) {  // settled after 20 already: both transients' runs stay
      add(k, 108.0, true, 20);
      add(k, 108.2, true, 200);
    } else {
      add(k, 100.0 + std::log10(k), true, 20);
    }
  }
  const RegimeReport r = analyze_runs(runs, 1e6);
  ASSERT_EQ(r.excluded.size(), 3u);
  for (const ExcludedRun& x : r.excluded) {
    EXPECT_EQ(x.k, 1e5);
    EXPECT_NE(x.reason.find("transient of 20 had not settled the point (2 of its 3 runs"), std::string::npos) << x.reason;
    EXPECT_NE(x.reason.find("runs after 200 pass"), std::string::npos) << x.reason;
  }
  ASSERT_EQ(r.families.size(), 1u);
  const CurveAnalysis& c = r.families[0].curves[0];
  EXPECT_DOUBLE_EQ(c.n_coll_of_k[0].y, 100.0);                     // the settled runs alone
  EXPECT_DOUBLE_EQ(c.n_coll_of_k[1].y, (110.0 + 110.5 + 113.0) / 3);  // all three kept
  EXPECT_DOUBLE_EQ(c.n_coll_of_k[2].y, 120.0);
  EXPECT_DOUBLE_EQ(c.n_coll_of_k[3].y, 108.1);
  EXPECT_EQ(c.non_stationary_k, (std::vector<double>{1e6, 1e7}));
}
