// The partially condensed state's test (analysis/condensation.*, paper Fig. partial_cond): the
// inversion of K_i and the interior hot layer on synthetic profiles shaped like the stored columns',
// and its threshold, whose chance of a false flag on a column without an inversion does not grow
// with N.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "analysis/condensation.hpp"
#include "model/random.hpp"

using namespace granchain;
using namespace granchain::analysis;

namespace {

double upper_tail(double z) { return 0.5 * std::erfc(z / std::numbers::sqrt2); }

// A profile without an inversion (K_i flat: the hardest case, every pair a fair coin) with
// independent normal errors of standard deviation `error`, as the per-particle means of a run.
std::vector<ParticleValue> flat_profile(int n, double error, Rng& rng) {
  std::vector<ParticleValue> K;
  for (int i = 0; i < n; ++i) K.push_back({0.2 + error * rng.normal(), error});
  return K;
}

// The largest rise K_j - K_i (i in the lower half, j > i) in its standard errors: what the test
// compares with its threshold.
double largest_pull(const std::vector<ParticleValue>& K) {
  double best = -INFINITY;
  for (std::size_t i = 0; i < (K.size() + 1) / 2; ++i)
    for (std::size_t j = i + 1; j < K.size(); ++j)
      best = std::max(best, (K[j].value - K[i].value) / std::hypot(K[j].error, K[i].error));
  return best;
}

}  // namespace


// A K_i profile falling monotonically with height (energy dissipated upward from the floor) is not
// condensed; one with a dip at particle 4 and a warmer layer above it is, by more than 3 errors.
TEST(PartialCondensation, InversionAboveADipNearTheFloor) {
  std::vector<ParticleValue> falling, dipped;
  for (int i = 1; i <= 25; ++i) {
    falling.push_back({0.5 * std::exp(-0.05 * i), 0.005});
    const double low[4] = {0.45, 0.30, 0.15, 0.08};  // cooling fast above the floor, coldest at 4
    dipped.push_back({i <= 4 ? low[i - 1] : 0.08 + 0.2 * (1.0 - std::exp(-(i - 4) / 2.0)) * std::exp(-0.01 * i), 0.005});
  }
  const CondensationCheck f = detect_partial_condensation(falling);
  EXPECT_FALSE(f.condensed);
  EXPECT_EQ(f.dip, 13);  // the lowest of the lower half; nothing above it is warmer
  // A shallow dip at particle 2 with a warmer layer above it, the top still the coldest of all
  // (as at e = 0.90 in the quick preset): condensed.
  std::vector<ParticleValue> shallow;
  for (int i = 1; i <= 25; ++i)
    shallow.push_back({i <= 2 ? 0.062 - 0.002 * i : 0.058 + 0.010 * std::sin(3.14159 * (i - 2) / 23.0) - 0.0008 * (i - 2), 0.0005});
  const CondensationCheck sh = detect_partial_condensation(shallow);
  EXPECT_TRUE(sh.condensed);
  EXPECT_EQ(sh.dip, 2);
  const CondensationCheck d = detect_partial_condensation(dipped);
  EXPECT_TRUE(d.condensed);
  EXPECT_EQ(d.dip, 4);
  EXPECT_GT(d.rise, 3 * d.rise_error);
  // The same dip buried in noise 10 times larger is not claimed.
  for (auto& k : dipped) k.error = 0.05;
  EXPECT_FALSE(detect_partial_condensation(dipped).condensed);
  // sigma_i / sigma_0,i: its minimum is found.
  std::vector<ParticleValue> sigma(25, {1.0, 0.01});
  sigma[5].value = 0.3;
  const CondensationCheck s = detect_partial_condensation(falling, sigma, std::vector<double>(25, 2.0));
  EXPECT_EQ(s.sigma_dip, 6);
  EXPECT_NEAR(s.sigma_ratio_min, 0.15, 1e-12);
}

// Partial or whole: profiles shaped like the quick preset's N = 25 columns at k = 1e8. A cold dip
// near the floor under a fluid layer that is warmest inside the column and cooler again towards the
// top (e = 0.88: dip at 4, maximum at 13) is partially condensed; a column cold throughout whose K_i
// rises only towards its free surface (e = 0.7) is condensed as a whole; a monotonically cooling
// one (e = 0.92) is neither. A hot layer whose top particle is as warm as its maximum, with a cooler
// stretch in between (e = 0.84), is partial too.
TEST(PartialCondensation, PartialHasAnInteriorHotLayerWholeOnlyAWarmSurface) {
  std::vector<ParticleValue> partial, whole, none;
  for (int i = 1; i <= 25; ++i) {
    const double x = i;
    partial.push_back({i <= 4 ? 0.027 - 0.0035 * (i - 1) : 0.0165 + 0.02 * std::exp(-(x - 13) * (x - 13) / 40.0), 0.0005});
    whole.push_back({i <= 3 ? 0.018 - 0.004 * (i - 1) : 0.008 + 0.027 * std::exp(-(25 - x) / 1.5), 0.0005});
    none.push_back({0.135 * std::exp(-0.027 * (x - 1)), 0.0005});
  }
  const CondensationCheck p = detect_partial_condensation(partial);
  EXPECT_TRUE(p.condensed);
  EXPECT_EQ(p.state, CondensedState::Partial);
  EXPECT_NEAR(p.hot, 13, 2);
  EXPECT_GT(p.hot_drop, 3 * p.hot_drop_error);
  const CondensationCheck w = detect_partial_condensation(whole);
  EXPECT_TRUE(w.condensed);
  EXPECT_EQ(w.state, CondensedState::Whole);
  EXPECT_EQ(detect_partial_condensation(none).state, CondensedState::None);
  std::vector<ParticleValue> surface_warm = partial;
  for (int i = 20; i <= 24; ++i) surface_warm[i - 1].value = 0.02 - 0.001 * (i - 19);
  surface_warm[24].value = 0.0365;  // the top particle as warm as the layer's maximum
  EXPECT_EQ(detect_partial_condensation(surface_warm).state, CondensedState::Partial);
  // The interior maximum must beat the top by 3 errors: with errors 20 times larger it does not.
  for (auto& k : partial) k.error = 0.01;
  EXPECT_NE(detect_partial_condensation(partial).state, CondensedState::Partial);
  EXPECT_STREQ(condensed_state_name(CondensedState::Partial), "partial");
}

// The threshold: z = 3 at N = 25 (and below), and above it the z whose Bonferroni bound
// pairs * Q(z) equals N = 25's 234 * Q(3), Q the normal upper tail.
TEST(PartialCondensation, ThresholdKeepsTheBoundOnAChanceFlagOfNEquals25) {
  EXPECT_EQ(inversion_pairs(3), 3u);  // (1,2), (1,3), (2,3)
  EXPECT_EQ(inversion_pairs(25), 234u);
  EXPECT_DOUBLE_EQ(pair_test_threshold(inversion_pairs(25)), 3.0);
  EXPECT_DOUBLE_EQ(pair_test_threshold(inversion_pairs(20)), 3.0);
  const double bound = 234 * upper_tail(3.0);
  for (int n : {50, 100, 200, 500, 1000}) {
    const std::size_t pairs = inversion_pairs(n);
    EXPECT_EQ(pairs, static_cast<std::size_t>((n + 1) / 2) * (n - 1) - static_cast<std::size_t>((n + 1) / 2) * ((n + 1) / 2 - 1) / 2);
    const double z = pair_test_threshold(pairs);
    EXPECT_NEAR(pairs * upper_tail(z), bound, 1e-9 * bound) << n;
  }
  EXPECT_NEAR(pair_test_threshold(inversion_pairs(1000)), 4.79, 0.005);
}

// A column without an inversion: 600 flat profiles (independent errors, fixed seed) at N = 25,
// 200 and 1000. At a fixed z = 3 the largest chance rise of N = 1000 exceeds 3 errors in nearly
// every profile (the ~375 000 pairs compared); with the test's threshold the fraction flagged at
// N = 200 and 1000 is no larger than N = 25's (binomial errors, 3 of them) and under the bound
// 234 Q(3) = 0.32 at every N.
TEST(PartialCondensation, FalseAlarmRateDoesNotGrowWithN) {
  constexpr int profiles = 600;
  Rng rng(2026);
  auto fraction_flagged = [&](int n, int* over3) {
    int flagged = 0;
    *over3 = 0;
    for (int r = 0; r < profiles; ++r) {
      const auto K = flat_profile(n, 0.01, rng);
      flagged += detect_partial_condensation(K).condensed ? 1 : 0;
      *over3 += largest_pull(K) > 3.0 ? 1 : 0;
    }
    return static_cast<double>(flagged) / profiles;
  };
  int over3_25 = 0, over3_200 = 0, over3_1000 = 0;
  const double f25 = fraction_flagged(25, &over3_25);
  const double f200 = fraction_flagged(200, &over3_200);
  const double f1000 = fraction_flagged(1000, &over3_1000);
  std::printf("flat profiles flagged (of %d): N = 25 %.3f, 200 %.3f, 1000 %.3f; at a fixed z = 3: %.3f, %.3f, %.3f\n",
              profiles, f25, f200, f1000, over3_25 / double(profiles), over3_200 / double(profiles), over3_1000 / double(profiles));
  EXPECT_EQ(f25, static_cast<double>(over3_25) / profiles);  // z = 3 at N = 25
  EXPECT_GT(over3_1000, 0.95 * profiles);                     // a fixed z = 3 flags nearly every N = 1000 column
  EXPECT_GT(over3_200, 0.7 * profiles);
  const double sigma = std::sqrt(2.0 * std::max(f25, 1.0 / profiles) * (1 - f25) / profiles);
  for (double f : {f200, f1000}) {
    EXPECT_LT(f, f25 + 3 * sigma);
    EXPECT_LT(f, 234 * upper_tail(3.0));
  }
  EXPECT_GT(f25, 0.0);  // the threshold is not so high that nothing is ever flagged
}

// A partially condensed column of N = 1000 (synthetic: cooling from the floor to a dip at particle
// 60, level up to an interior hot layer near particle 300 that is warmer than the dip by 6 errors,
// cooler again towards the top; the stored c = 2.4 at k = 1e15 rises by 6.0 errors, dip at 10, hot
// particle at 203) is found, noise-free and in 100 noisy copies (independent normal errors, fixed
// seed: the pull of one 6-error pair exceeds z = 4.79 in 89 % of them, the largest of the pairs
// more often, 100 of 100 here; at least 80 required, 3 binomial errors below 89); the same profile with its rise
// shrunk to 4 errors is flagged at N = 25's z = 3 but not at N = 1000's 4.79, where chance rises of
// 4 errors are expected.
TEST(PartialCondensation, ALargeColumnsHotLayerIsFoundAndAWeakOneIsNot) {
  auto profile = [](double rise_in_errors) {
    std::vector<ParticleValue> K;
    const double err = 0.001, floor_K = 0.26, dip_K = 0.20;
    for (int i = 1; i <= 1000; ++i) {
      const double x = i;
      // Cooling from the floor to the dip at 60, level up to the hot layer, then cooling to the top.
      const double hump = rise_in_errors * err * std::sqrt(2.0) * std::exp(-(x - 300) * (x - 300) / (2 * 80.0 * 80.0));
      const double k = i <= 60 ? floor_K - (floor_K - dip_K) * (x - 1) / 59.0
                               : dip_K + hump - (i > 500 ? 0.02 * (x - 500) / 500.0 : 0.0);
      K.push_back({k, err});
    }
    return K;
  };
  const CondensationCheck strong = detect_partial_condensation(profile(6.0));
  EXPECT_TRUE(strong.condensed);
  EXPECT_EQ(strong.state, CondensedState::Partial);
  EXPECT_NEAR(strong.z, 4.79, 0.005);
  EXPECT_NEAR(strong.hot, 300, 20);
  Rng rng(7);
  int found = 0;
  for (int r = 0; r < 100; ++r) {
    auto noisy = profile(6.0);
    for (auto& k : noisy) k.value += k.error * rng.normal();
    found += detect_partial_condensation(noisy).state == CondensedState::Partial ? 1 : 0;
  }
  std::printf("noisy N = 1000 hot layers of 6 errors found: %d of 100\n", found);
  EXPECT_GE(found, 80);
  const CondensationCheck weak = detect_partial_condensation(profile(4.0));
  EXPECT_GT(weak.rise, 3.0 * weak.rise_error);
  EXPECT_FALSE(weak.condensed);
  EXPECT_EQ(weak.state, CondensedState::None);
}
