// The closed-form e = 1 equilibrium against direct numerical integration of the Gibbs weight.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "theory/equilibrium_column.hpp"

using namespace granchain;

namespace {

// Composite Simpson rule on [a, b] with n (even) intervals.
double simpson(const std::function<double(double)>& f, double a, double b, int n) {
  const double h = (b - a) / n;
  double s = f(a) + f(b);
  for (int i = 1; i < n; ++i) s += f(a + i * h) * (i % 2 ? 4 : 2);
  return s * h / 3;
}

}  // namespace

TEST(ElasticColumnEquilibrium, MatchesQuadratureOfGibbsWeight) {
  const ChainParameters p{.N = 4, .m = 1.3, .d = 0.9, .g = 1.1, .k = 50.0, .e = 1.0, .kT0 = 2.0};
  const ElasticColumnEquilibrium eq = elastic_column_equilibrium(p);
  double mean = 0.5 * p.d, var = 0;
  double rate = 0;
  for (int j = 1; j <= p.N; ++j) {
    const double W = p.m * p.g * (p.N - j + 1);
    auto w = [&](double s) { return std::exp(-(W * s + (s < 0 ? 0.5 * p.k * s * s : 0.0)) / p.kT0); };
    const double lo = j == 1 ? 0.0 : -12.0 * std::sqrt(p.kT0 / p.k) - 2.0 * W / p.k;
    const double hi = 60.0 * p.kT0 / W;
    // Integrate the two sides separately: the weight has a kink at s = 0.
    auto integral = [&](const std::function<double(double)>& f) {
      return (lo < 0 ? simpson(f, lo, 0.0, 20000) : 0.0) + simpson(f, 0.0, hi, 200000);
    };
    const double M0 = integral(w);
    const double M1 = integral([&](double s) { return s * w(s); });
    const double M2 = integral([&](double s) { return s * s * w(s); });
    mean += (j > 1 ? p.d : 0.0) + M1 / M0;
    var += M2 / M0 - (M1 / M0) * (M1 / M0);
    EXPECT_NEAR(eq.z_mean[j - 1], mean, 1e-8);
    EXPECT_NEAR(eq.z_std[j - 1], std::sqrt(var), 1e-8);
    const double flux = j == 1 ? std::sqrt(p.kT0 / (2 * M_PI * p.m)) : std::sqrt(p.kT0 / (M_PI * p.m));
    const double r = flux / M0;
    if (j == 1) {
      EXPECT_NEAR(eq.floor_rate, r, 1e-9);
    } else {
      EXPECT_NEAR(eq.contact_end_rate[j - 2], r, 1e-9);
    }
    rate += r;
  }
  EXPECT_NEAR(eq.n_coll, rate / p.N, 1e-9);
  EXPECT_DOUBLE_EQ(eq.kinetic, 1.0);
}

// Hard-sphere limit: exponential gaps of mean kT0 / W_j (1-d hard rods under gravity).
TEST(ElasticColumnEquilibrium, HardSphereLimit) {
  const ChainParameters p{.N = 3, .k = 1e14, .e = 1.0};
  const ElasticColumnEquilibrium eq = elastic_column_equilibrium(p);
  EXPECT_NEAR(eq.z_mean[0], 0.5 + 1.0 / 3, 1e-6);
  EXPECT_NEAR(eq.z_mean[1], 1.5 + 1.0 / 3 + 1.0 / 2, 1e-6);
  EXPECT_NEAR(eq.z_mean[2], 2.5 + 1.0 / 3 + 1.0 / 2 + 1.0, 1e-6);
  EXPECT_NEAR(eq.z_std[2], std::sqrt(1.0 / 9 + 1.0 / 4 + 1.0), 1e-6);
  EXPECT_NEAR(eq.floor_rate, 3.0 / std::sqrt(2 * M_PI), 1e-12);
}
