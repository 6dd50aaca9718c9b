// The closed-form cluster solution (building block of the exact engine) against the reference
// engine run with a step so small that it has converged.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "engines/exact/cluster_modes.hpp"
#include "engines/exact/sine_transform.hpp"
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
  compare_cluster(60, 0.5);  // large clusters project through FFTW's sine transform
  compare_cluster(100, 0.05);
}

TEST(ClusterMotion, SingleParticleFallsFreely) {
  ClusterMotion cm({2.0}, {1.5}, 1.0, 1e4, 10.0, 1.0);
  std::vector<double> z, v;
  cm.state_at(0.8, z, v);
  EXPECT_NEAR(z[0], 2.0 + 1.5 * 0.8 - 0.5 * 0.64, 1e-15);
  EXPECT_NEAR(v[0], 1.5 - 0.8, 1e-15);
}

// The exact engine's gap and floor searches rest on this: compression only pulls a cluster's
// edge particles towards its centre of mass. The mode parts of the bottom and top particle,
// sum_j bottom_j y_j and -sum_j top_j y_j, equal sum_i x_i (n-1-i)/n and sum_i x_i (i+1)/n, so
// they are >= 0 whenever every overlap x_i is.
TEST(ClusterModeTable, EdgeParticlesMoveInwardsUnderCompression) {
  for (int n : {2, 3, 7, 25}) {
    const ClusterModeTable tab(n, 1e8, 3000.0);
    std::vector<double> x(tab.M), y(tab.M);
    for (int trial = 0; trial < 50; ++trial) {
      for (int i = 0; i < tab.M; ++i) x[i] = trial == 0 ? (i == 0 ? 1e-6 : 0.0) : 1e-6 * (1.0 + std::sin(7.0 * trial + 3.0 * i));
      tab.to_modes(x.data(), y.data());
      double bottom = 0, top = 0, want_bottom = 0, want_top = 0;
      for (int j = 0; j < tab.M; ++j) {
        bottom += tab.bottom[j] * y[j];
        top -= tab.top[j] * y[j];
      }
      for (int i = 0; i < tab.M; ++i) {
        want_bottom += x[i] * (n - 1 - i) / n;
        want_top += x[i] * (i + 1.0) / n;
      }
      EXPECT_NEAR(bottom, want_bottom, 1e-15 * n) << "n=" << n;
      EXPECT_NEAR(top, want_top, 1e-15 * n) << "n=" << n;
      EXPECT_GE(bottom, -1e-20);
      EXPECT_GE(top, -1e-20);
    }
  }
}

// The bounds behind the engine's root-free steps: every derivative of a mode stays within
// bound[n] * amplitude(state now) at all later times. Checked on a fine grid of later times for
// under-, critically and over-damped modes, derivatives 0..kTaylorOrder; the underdamped envelope
// bound omega0^n |C| is reached to within 10 per cent (it is tight up to the damping over half a period), so a looser or a wrong
// bound would show.
TEST(ModeConstants, DerivativeBoundsHoldAtAllLaterTimes) {
  for (double beta : {0.05, 0.6, 2.0, 5.0}) {  // omega0 = 2
    const ModeConstants mc(beta, 4.0);
    const double y0 = 0.7, v0 = -1.3;
    const double amp = mc.amplitude(y0, v0);
    double worst_ratio[kTaylorOrder + 1] = {};
    for (int s = 1; s <= 4000; ++s) {
      const double t = 0.005 * s;
      double y, yd;
      mc.evolve(y0, v0, t, y, yd);
      double ym = y, yn = yd;
      for (int n = 0; n <= kTaylorOrder; ++n) {
        const double dn = n == 0 ? y : n == 1 ? yd : mc.acceleration(ym, yn);
        if (n >= 2) {
          ym = yn;
          yn = dn;
        }
        const double ratio = std::abs(dn) / (mc.bound[n] * amp);
        EXPECT_LE(ratio, 1.0 + 1e-12) << "beta=" << beta << " n=" << n << " t=" << t;
        worst_ratio[n] = std::max(worst_ratio[n], ratio);
      }
    }
    if (mc.kind == ModeKind::Under && beta < 0.1) {
      for (int n = 0; n <= kTaylorOrder; ++n) EXPECT_GT(worst_ratio[n], 0.9) << "n=" << n;
    }
  }
}

// FFTW's type-I sine transform against the dense product sum_j S_ij y_j in long double, for sizes
// on both sides of the engine's switch (SineTransform::pays_off) and with n = M + 1 prime (FFTW's
// slowest case), and its own inverse. Round-off: a few ulps of sum_j |S_ij y_j| per O(log n)
// pass of the transform; 1e-14 of the largest such sum leaves room for that and fails on any
// wrong index or scale.
TEST(SineTransform, EqualsTheDenseSineProductAndIsItsOwnInverse) {
  for (int M : {1, 2, 7, 47, 48, 63, 72, 99, 148, 149}) {
    const int n = M + 1;
    const SineTransform dst(M);
    std::vector<double> y(M), x(M), back(M);
    for (int j = 0; j < M; ++j) y[j] = std::sin(1.7 * j + 0.3) * (j % 3 == 0 ? 1e-3 : 1.0);
    dst.apply(y.data(), x.data());
    double scale = 0.0, worst = 0.0;
    for (int i = 0; i < M; ++i) {
      long double sum = 0.0L, abs_sum = 0.0L;
      for (int j = 0; j < M; ++j) {
        const long double term = std::sqrt(2.0L / n) * std::sin((i + 1.0L) * (j + 1.0L) * 3.141592653589793238462643383279L / n) * y[j];
        sum += term;
        abs_sum += std::fabs(term);
      }
      scale = std::max(scale, static_cast<double>(abs_sum));
      worst = std::max(worst, std::abs(x[i] - static_cast<double>(sum)));
    }
    EXPECT_LE(worst, 1e-14 * scale) << "M=" << M;
    dst.apply(x.data(), back.data());
    for (int j = 0; j < M; ++j) EXPECT_NEAR(back[j], y[j], 1e-14) << "M=" << M << " j=" << j;
  }
  // The switch: clusters of 32 particles and more (smaller ones keep the dense product).
  EXPECT_NE(ClusterModeTable(150, 1e6, 100.0).transform, nullptr);
  EXPECT_EQ(ClusterModeTable(25, 1e6, 100.0).transform, nullptr);
}

// A mode come to rest within round-off (amplitudes ~1e-163, squares below the smallest double):
// its amplitude stays positive and equal to the exact one, for every kind of damping, so the
// engine's bounds never claim a moving cluster is at rest.
TEST(ModeConstants, AmplitudeOfAStateNearRestDoesNotUnderflow) {
  for (double beta : {0.05, 2.0, 5.0}) {  // omega0 = 2: under-, critically, over-damped
    const ModeConstants mc(beta, 4.0);
    for (double scale : {1.0, 1e-163, 1e-300}) {
      const double y = 3 * scale, yd = -4 * scale;
      const double a = mc.amplitude(y, yd);
      EXPECT_GT(a, 0.0) << "beta " << beta << ", scale " << scale;
      EXPECT_NEAR(a / scale, mc.amplitude(3.0, -4.0), 1e-12 * mc.amplitude(3.0, -4.0)) << "beta " << beta << ", scale " << scale;
    }
  }
}
