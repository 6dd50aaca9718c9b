// Blocking error analysis on synthetic series with known statistics.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "analysis/blocking.hpp"
#include "model/random.hpp"

using namespace granchain;

namespace {

// Mean of an AR(1) series x_t = phi x_{t-1} + sqrt(1 - phi^2) eta_t (unit variance), stored in
// `bins` bins. The exact standard error of the mean of n points is, for n >> 1/(1-phi),
// sqrt((1 + phi) / ((1 - phi) n)).
BinnedSums ar1_bins(double phi, long n, int bins, std::uint64_t seed) {
  Rng r(seed);
  BinnedSums s(bins, 2);
  double x = r.normal();
  const double c = std::sqrt(1 - phi * phi);
  for (long t = 0; t < n; ++t) {
    x = phi * x + c * r.normal();
    double* b = s.bin(static_cast<int>(t * bins / n));
    b[0] += 1.0;
    b[1] += x;
  }
  return s;
}

double mean_of(std::span<const double> s) { return s[1] / s[0]; }

}  // namespace

TEST(Blocking, UncorrelatedDataGiveSigmaOverRootN) {
  const long n = 1 << 18;
  const BinnedSums s = ar1_bins(0.0, n, 1024, 1);
  const Estimate e = blocked_estimate(s, mean_of);
  const double exact = 1.0 / std::sqrt(double(n));
  // Relative noise of an SE from >= 16 blocks is <= 1/sqrt(30): allow 3 of those.
  EXPECT_NEAR(e.error, exact, 3.0 * exact / std::sqrt(30.0));
  EXPECT_TRUE(e.converged);
}

// Strong correlation: the naive SE is too small by sqrt((1+phi)/(1-phi)) = 9.95 for phi = 0.98;
// blocking must recover the true SE.
TEST(Blocking, CorrelatedDataRecoverTrueError) {
  const double phi = 0.98;
  const long n = 1 << 21;
  int within = 0;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    const BinnedSums s = ar1_bins(phi, n, 1024, seed);
    const Estimate e = blocked_estimate(s, mean_of);
    const double exact = std::sqrt((1 + phi) / ((1 - phi) * n));
    EXPECT_TRUE(e.converged) << "seed " << seed;
    EXPECT_GT(e.error, 0.6 * exact) << "seed " << seed;
    EXPECT_LT(e.error, 1.5 * exact) << "seed " << seed;
    within += std::abs(e.value) < 2.0 * exact;
  }
  // The mean itself: |mean| < 2 SE for about 95% of seeds; at least 6 of 8.
  EXPECT_GE(within, 6);
}

// Anticorrelated bins, as the collision counts of a short bin of a quasi-periodic column (a burst
// in one bin, a lull in the next): bin values x_t = eps_t - theta eps_{t-1} (MA(1), theta = 0.5,
// lag-1 autocorrelation -0.4). The naive error of the mean of n bins is sqrt(1 + theta^2) / (1 - theta)
// = 2.2 times the exact sqrt(n (1 + theta^2) - 2 (n - 1) theta) / n; blocking must not stop at a
// level whose blocks are anticorrelated. Blocks of b bins still carry an edge excess of about
// sqrt(1 + 2 theta / (b (1 - theta)^2)) (1.22 at b = 8, 1.12 at b = 16), so the error may come out
// up to about 1.3 times the exact one, never twice.
TEST(Blocking, AnticorrelatedBinsAreNotTakenAsIndependent) {
  const double theta = 0.5;
  const int n = 1024;
  const double exact = std::sqrt(n * (1 + theta * theta) - 2.0 * (n - 1) * theta) / n;
  double sum_ratio = 0;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    Rng r(seed);
    BinnedSums s(n, 2);
    double prev = r.normal();
    for (int t = 0; t < n; ++t) {
      const double eps = r.normal();
      s.bin(t)[0] = 1.0;
      s.bin(t)[1] = eps - theta * prev;
      prev = eps;
    }
    const Estimate e = blocked_estimate(s, mean_of);
    EXPECT_GT(e.error, 0.7 * exact) << "seed " << seed;
    EXPECT_LT(e.error, 1.6 * exact) << "seed " << seed;
    sum_ratio += e.error / exact;
  }
  EXPECT_LT(sum_ratio / 8, 1.4);
  EXPECT_GT(sum_ratio / 8, 0.9);
}

// If the correlation time is as long as the run, no plateau can be seen and the flag says so.
TEST(Blocking, FlagsMissingPlateau) {
  const BinnedSums s = ar1_bins(0.99995, 1 << 18, 1024, 3);
  EXPECT_FALSE(blocked_estimate(s, mean_of).converged);
}

// The jackknife gives errors to non-linear estimators: the SE of a ratio of independent means
// follows from error propagation.
TEST(Blocking, JackknifeRatioMatchesErrorPropagation) {
  Rng r(11);
  const int n = 1 << 18;
  BinnedSums s(1024, 3);
  for (int t = 0; t < n; ++t) {
    double* b = s.bin(t * 1024 / n);
    b[0] += 1.0;
    b[1] += 2.0 + 0.5 * r.normal();
    b[2] += 4.0 + 1.0 * r.normal();
  }
  const Estimate e = blocked_estimate(s, [](std::span<const double> x) { return x[1] / x[2]; });
  // var(a/b) ~ (a/b)^2 (var a / a^2 + var b / b^2) / n
  const double exact = 0.5 * std::sqrt((0.25 / 4.0 + 1.0 / 16.0) / n);
  EXPECT_NEAR(e.value, 0.5, 5 * exact);
  EXPECT_NEAR(e.error, exact, 3.0 * exact / std::sqrt(30.0));
}

TEST(Blocking, PowerOfTwoBins) {
  EXPECT_EQ(power_of_two_bins(100000, 1024), 1024);
  EXPECT_EQ(power_of_two_bins(100, 1024), 64);
  EXPECT_EQ(power_of_two_bins(1, 1024), 1);
  EXPECT_THROW(BinnedSums(100, 1), std::invalid_argument);
}

// The halves check on a settled series: white noise and AR(1) with phi = 0.9, 400 seeds each.
// With |z| <= 3 and errors estimated from 16 or more blocks per half (z then follows roughly a
// Student t with >= 15 degrees of freedom, P(|t| > 3) < 1 %), the false alarms expected are about
// 4 of 400 (standard deviation 2); more than 16 would mean the check fires on stationary data.
TEST(Blocking, HalvesCheckRarelyFlagsAStationarySeries) {
  for (double phi : {0.0, 0.9}) {
    int flagged = 0;
    for (std::uint64_t seed = 1; seed <= 400; ++seed) flagged += !halves_check(ar1_bins(phi, 1 << 14, 1024, seed), mean_of).stationary;
    std::printf("phi = %.1f: %d of 400 stationary series flagged\n", phi, flagged);
    EXPECT_LE(flagged, 16) << "phi = " << phi;
  }
}

// A linear drift a t/n added to unit white noise of n points moves the mean of the second half
// above the first by a/2, whose standard error is 2/sqrt(n): a = 24/sqrt(n) gives z = 6 on average,
// found beyond 3 in all but about 1 run in 1000; a drift four times smaller (z = 1.5) mostly passes.
TEST(Blocking, HalvesCheckFindsADrift) {
  const long n = 1 << 14;
  auto drifting = [n](double a, std::uint64_t seed) {
    Rng r(seed);
    BinnedSums s(1024, 2);
    for (long t = 0; t < n; ++t) {
      double* b = s.bin(static_cast<int>(t * 1024 / n));
      b[0] += 1.0;
      b[1] += r.normal() + a * double(t) / n;
    }
    return s;
  };
  int found = 0, found_small = 0;
  for (std::uint64_t seed = 1; seed <= 200; ++seed) {
    const StationarityCheck c = halves_check(drifting(24.0 / std::sqrt(double(n)), seed), mean_of);
    found += !c.stationary;
    EXPECT_GT(c.z, 0.0);
    found_small += !halves_check(drifting(6.0 / std::sqrt(double(n)), seed), mean_of).stationary;
  }
  std::printf("drift z = 6: %d of 200 found; z = 1.5: %d of 200\n", found, found_small);
  EXPECT_GE(found, 196);
  EXPECT_LE(found_small, 100);
}

// A relaxation at the start of the window: unit white noise of n points plus 3 exp(-64 t / n),
// gone after a few per cent of the window. It raises the first half's mean by 3/32 = 0.094 while
// a settled half's standard error is 1/sqrt(n/2) = 0.011, so z_settled = -0.094 / (sqrt(2) 0.011)
// = -6.0 on average (beyond 3 in all but about 1 run in 1000). The first half's blocked error
// takes the relaxation for spread (its first block differs), so the symmetric z stays small: it
// alone finds the relaxation in well under half of the runs.
TEST(Blocking, HalvesCheckFindsAnEarlyRelaxation) {
  const long n = 1 << 14;
  int found = 0, found_by_z = 0;
  double z_settled = 0;
  for (std::uint64_t seed = 1; seed <= 200; ++seed) {
    Rng r(seed);
    BinnedSums s(1024, 2);
    for (long t = 0; t < n; ++t) {
      double* b = s.bin(static_cast<int>(t * 1024 / n));
      b[0] += 1.0;
      b[1] += r.normal() + 3.0 * std::exp(-64.0 * double(t) / n);
    }
    const StationarityCheck c = halves_check(s, mean_of);
    found += !c.stationary;
    found_by_z += std::abs(c.z) > 3.0;
    z_settled += c.z_settled / 200;
  }
  std::printf("relaxation: %d of 200 found, %d by the symmetric z alone; mean z_settled %.2f\n", found, found_by_z, z_settled);
  EXPECT_GE(found, 195);
  EXPECT_LE(found_by_z, 100);
  EXPECT_NEAR(z_settled, -6.0, 0.5);  // the mean of 200 deviates of unit spread: within 0.5 by far
}

// A stored run's halves judged again give what the check gave on its bins.
TEST(Blocking, JudgingStoredHalvesGivesTheSameVerdict) {
  for (std::uint64_t seed = 1; seed <= 50; ++seed) {
    const StationarityCheck c = halves_check(ar1_bins(0.9, 1 << 12, 256, seed), mean_of);
    const StationarityCheck j = judge_halves(c.first, c.second);
    EXPECT_EQ(j.z, c.z);
    EXPECT_EQ(j.z_settled, c.z_settled);
    EXPECT_EQ(j.stationary, c.stationary);
  }
}

// No spread at all (every bin the same): stationary exactly when the halves are equal.
TEST(Blocking, HalvesCheckWithoutSpreadComparesTheValues) {
  BinnedSums flat(64, 2), step(64, 2);
  for (int b = 0; b < 64; ++b) {
    flat.bin(b)[0] = step.bin(b)[0] = 1.0;
    flat.bin(b)[1] = 2.0;
    step.bin(b)[1] = b < 32 ? 2.0 : 3.0;
  }
  EXPECT_TRUE(halves_check(flat, mean_of).stationary);
  EXPECT_FALSE(halves_check(step, mean_of).stationary);
}

// Replicas drawn with their stated errors give chi2/dof near 1 (z within 4 of N(0, 1) over 300
// groups of 4); errors stated at half their size give chi2/dof near 4; groups of one run or with a
// zero error are skipped.
TEST(ReplicaScatter, ChiSquaredPerDegreeOfFreedomIsOneWhenErrorsAreRightAndFourWhenHalved) {
  Rng rng(41);
  std::vector<std::vector<std::pair<double, double>>> right, halved;
  for (int g = 0; g < 300; ++g) {
    std::vector<std::pair<double, double>> a, b;
    for (int i = 0; i < 4; ++i) {
      const double err = 0.1 * (1 + i);  // unequal errors: the weighted mean matters
      const double x = 5.0 + g + err * rng.normal();
      a.push_back({x, err});
      b.push_back({x, 0.5 * err});
    }
    right.push_back(a);
    halved.push_back(b);
  }
  right.push_back({{1.0, 0.1}});              // one run: skipped
  right.push_back({{1.0, 0.1}, {2.0, 0.0}});  // no error: skipped
  const ReplicaScatter r = replica_scatter(right);
  EXPECT_EQ(r.groups, 300);
  EXPECT_EQ(r.dof, 900);
  EXPECT_LT(std::abs(r.chi2_z), 4.0) << r.chi2 / r.dof;
  const ReplicaScatter h = replica_scatter(halved);
  EXPECT_NEAR(h.chi2 / h.dof, 4.0, 4.0 * 4.0 * std::sqrt(2.0 / 900));
  EXPECT_GT(h.chi2_z, 10.0);
}

// Level by level: replicas whose true scatter is 0.2 while their curves rise from 0.05 (1024
// blocks) to 0.2 at 64 blocks and stay there. chi^2/dof is 16 with the shortest blocks' errors, 1
// from 64 blocks on, and 4 with the reported errors (0.1, the level of 256 blocks): the check says
// from which block length on the errors see the scatter.
TEST(ReplicaScatter, LevelByLevelTheChiSquaredFallsToOneWhereTheCurveReachesTheScatter) {
  Rng rng(43);
  const std::vector<std::pair<int, double>> curve = {{1024, 0.05}, {512, 0.07}, {256, 0.1}, {128, 0.14}, {64, 0.2}, {32, 0.2}, {16, 0.2}};
  std::vector<std::vector<ReplicaRun>> groups;
  for (int g = 0; g < 300; ++g) {
    std::vector<ReplicaRun> runs;
    for (int i = 0; i < 4; ++i) {
      ReplicaRun r{3.0 + g + 0.2 * rng.normal(), 0.1, {}};
      for (const auto& [b, err] : curve) r.curve.push_back({b, err, 0.0});
      runs.push_back(r);
    }
    groups.push_back(runs);
  }
  groups.push_back({ReplicaRun{1.0, 0.1, {{16, 0.2, 0.0}}}});  // one run: skipped
  const CurveScatter s = replica_scatter_by_level(groups);
  EXPECT_EQ(s.groups, 300);
  EXPECT_EQ(s.dof, 900);
  ASSERT_EQ(s.levels.size(), curve.size());
  const double sd = std::sqrt(2.0 / 900);  // of chi^2/dof, relative
  EXPECT_NEAR(s.chi2_reported / s.dof, 4.0, 4.0 * 4.0 * sd);
  for (std::size_t l = 0; l < curve.size(); ++l) {
    const double expected = 0.04 / (curve[l].second * curve[l].second);
    EXPECT_EQ(s.levels[l].blocks, curve[l].first);
    EXPECT_NEAR(s.levels[l].chi2 / s.dof, expected, 4.0 * expected * sd) << curve[l].first << " blocks";
  }
}
