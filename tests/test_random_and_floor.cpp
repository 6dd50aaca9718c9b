// Random streams and the thermal floor's speed distribution (Sec. II.A).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "model/driven_column.hpp"
#include "model/floor.hpp"
#include "model/random.hpp"

using namespace granchain;

TEST(Random, SameSeedSameNumbersDifferentSeedsDiffer) {
  Rng a(42), b(42), c(43);
  for (int i = 0; i < 1000; ++i) {
    const double x = a.uniform01();
    EXPECT_EQ(x, b.uniform01());
    EXPECT_GE(x, 0.0);
    EXPECT_LT(x, 1.0);
  }
  int same = 0;
  Rng a2(42);
  for (int i = 0; i < 1000; ++i) same += a2.bits() == c.bits();
  EXPECT_EQ(same, 0);
  EXPECT_NE(derive_seed(1, 1), derive_seed(1, 2));
  EXPECT_NE(derive_seed(1, 1), derive_seed(2, 1));
}

// Normal deviates: mean 0 and variance 1 within 5 standard errors of n = 4e5 samples.
TEST(Random, NormalMoments) {
  Rng r(7);
  const int n = 400000;
  double s1 = 0, s2 = 0, s4 = 0;
  for (int i = 0; i < n; ++i) {
    const double x = r.normal();
    s1 += x;
    s2 += x * x;
    s4 += x * x * x * x;
  }
  EXPECT_NEAR(s1 / n, 0.0, 5.0 / std::sqrt(n));
  EXPECT_NEAR(s2 / n, 1.0, 5.0 * std::sqrt(2.0 / n));  // var(x^2) = 2
  EXPECT_NEAR(s4 / n, 3.0, 5.0 * std::sqrt(96.0 / n)); // var(x^4) = 105 - 9
}

// p(v) = (m v / kT0) exp(-m v^2 / 2kT0): <v> = sqrt(pi kT0 / 2m), <v^2> = 2 kT0 / m; the whole
// distribution by a Kolmogorov-Smirnov test (critical value 1.63/sqrt(n) at the 1% level).
TEST(ThermalFloor, FluxWeightedMaxwellDistribution) {
  const double kT0 = 2.5, m = 1.5;
  ThermalFloor floor(kT0, m, 12345);
  const int n = 200000;
  std::vector<double> v(n);
  double s1 = 0, s2 = 0;
  for (int i = 0; i < n; ++i) {
    v[i] = floor.next_speed();
    ASSERT_GT(v[i], 0.0);
    s1 += v[i];
    s2 += v[i] * v[i];
  }
  const double mean = std::sqrt(std::numbers::pi * kT0 / (2 * m));
  const double var = 2 * kT0 / m - mean * mean;
  EXPECT_NEAR(s1 / n, mean, 5.0 * std::sqrt(var / n));
  // var(v^2) = <v^4> - <v^2>^2 = 8 (kT0/m)^2 - 4 (kT0/m)^2
  EXPECT_NEAR(s2 / n, 2 * kT0 / m, 5.0 * std::sqrt(4.0 * (kT0 / m) * (kT0 / m) / n));
  std::sort(v.begin(), v.end());
  double dmax = 0;
  for (int i = 0; i < n; ++i) {
    const double F = thermal_floor_speed_cdf(v[i], kT0, m);
    dmax = std::max({dmax, std::abs(F - double(i) / n), std::abs(F - double(i + 1) / n)});
  }
  EXPECT_LT(dmax, 1.63 / std::sqrt(n));
}

TEST(ScriptedFloor, ReplaysThenRefuses) {
  ScriptedFloor f({1.0, 2.0});
  EXPECT_EQ(f.next_speed(), 1.0);
  EXPECT_EQ(f.next_speed(), 2.0);
  EXPECT_THROW(f.next_speed(), std::out_of_range);
}

// Sec. III.A: the initial column has no overlaps, starts above the floor, and is reproducible.
TEST(DrivenColumnSetup, InitialStateHasNoOverlapAndIsReproducible) {
  ChainParameters p{.N = 50, .d = 0.7, .kT0 = 3.0};
  const ChainState a = driven_column_initial_state(p, 99);
  const ChainState b = driven_column_initial_state(p, 99);
  const ChainState c = driven_column_initial_state(p, 100);
  EXPECT_EQ(a.z, b.z);
  EXPECT_EQ(a.v, b.v);
  EXPECT_NE(a.z, c.z);
  EXPECT_GE(a.z[0], floor_contact_height(p));
  for (int i = 0; i + 1 < p.N; ++i) EXPECT_GE(a.z[i + 1] - a.z[i], p.d);
  double k2 = 0;
  for (double v : a.v) k2 += v * v;
  EXPECT_GT(k2, 0.0);
}
