// The closed-form cluster solution (building block of the exact engine) against the reference
// engine run with a step so small that it has converged.
#include <gtest/gtest.h>

#include <cmath>

#include "engines/cluster_modes.hpp"
#include "engines/runge_kutta_engine.hpp"
#include "test_helpers.hpp"

using namespace granchain;

// Each damped-mode form satisfies y'' + 2 beta y' + omega0^2 y = 0 (checked by central
// differences) and its initial conditions.
TEST(DampedMode, SolvesTheOscillatorInAllThreeRegimes) {
  for (double beta : {0.3, 2.0, 5.0}) {  // omega0 = 2: under-, critically and over-damped
    const DampedMode y(beta, 4.0, 0.7, -1.3);
    EXPECT_NEAR(y.value(0), 0.7, 1e-15);
    EXPECT_NEAR(y.rate(0), -1.3, 1e-15);
    for (double t : {0.1, 0.5, 1.7}) {
      const double h = 1e-4;
      const double acc = (y.rate(t + h) - y.rate(t - h)) / (2 * h);
      const double vel = (y.value(t + h) - y.value(t - h)) / (2 * h);
      EXPECT_NEAR(vel, y.rate(t), 1e-7) << "beta=" << beta;
      EXPECT_NEAR(acc + 2 * beta * y.rate(t) + 4.0 * y.value(t), 0.0, 1e-6) << "beta=" << beta;
    }
  }
}

namespace {

// A compressed cluster of n particles under gravity, followed for a fraction of tau_c so that
// every contact stays closed; closed form vs RK with dt = tau_c / 1e5.
void compare_cluster(int n, double e) {
  ChainParameters p{.N = n, .g = 1.0, .k = 1e4, .e = e};
  ChainState s;
  for (int i = 0; i < n; ++i) {
    s.z.push_back(i * (p.d - 0.004) + 0.001 * std::sin(3.0 * i));
    s.v.push_back(0.05 * std::cos(2.0 * i));
  }
  const ContactLaw law = contact_law(p);
  const double t = 0.1 * law.tau_c;
  RungeKuttaEngine rk(p, s, nullptr, {1e5});
  test_support::EventRecorder rec;
  rk.advance_to(t, rec);
  ASSERT_EQ(rec.count(EventKind::ContactEnd), 0u) << "a contact opened: the comparison needs a closed cluster";
  ClusterMotion cm(s.z, s.v, p.d, law.k_over_m, law.D, p.g);
  std::vector<double> z, v;
  cm.state_at(t, z, v);
  for (int i = 0; i < n; ++i) {
    EXPECT_NEAR(z[i], rk.state().z[i], 1e-9) << "n=" << n << " e=" << e << " particle " << i + 1;
    EXPECT_NEAR(v[i], rk.state().v[i], 1e-6 * (1 + std::abs(v[i]))) << "n=" << n << " e=" << e << " particle " << i + 1;
  }
}

}  // namespace

TEST(ClusterMotion, MatchesConvergedReferenceEngine) {
  compare_cluster(2, 0.5);
  compare_cluster(4, 0.5);
  compare_cluster(7, 0.9);
  compare_cluster(5, 0.01);  // e < exp(-pi): the upper modes are overdamped
}

TEST(ClusterMotion, SingleParticleFallsFreely) {
  ClusterMotion cm({2.0}, {1.5}, 1.0, 1e4, 10.0, 1.0);
  std::vector<double> z, v;
  cm.state_at(0.8, z, v);
  EXPECT_NEAR(z[0], 2.0 + 1.5 * 0.8 - 0.5 * 0.64, 1e-15);
  EXPECT_NEAR(v[0], 1.5 - 0.8, 1e-15);
}
