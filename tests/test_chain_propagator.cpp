// The fixed-step propagator of a touching cluster in overlap coordinates (chain_propagator.hpp)
// against an independent long-double solution: the cluster's sine modes, each advanced by the
// eigenvalues of its own 2x2 system in complex arithmetic (no shared formula with the kernel's).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include "engines/exact/chain_propagator.hpp"
#include "model/chain_parameters.hpp"

using namespace granchain;

namespace {

using cld = std::complex<long double>;

// x, xd of an n-particle cluster after time t, exactly to long-double round-off: modes
// y = S x (S_ij = sqrt(2/n) sin(i j pi / n), symmetric and its own inverse), each mode
// y'' + D lambda y' + (k/m) lambda y = 0 solved from its characteristic roots r1, r2.
void sine_mode_solution(int n, long double k_over_m, long double D, long double t, const std::vector<double>& x,
                        const std::vector<double>& xd, std::vector<long double>& x_out, std::vector<long double>& xd_out) {
  const int M = n - 1;
  const long double pi = std::numbers::pi_v<long double>;
  std::vector<long double> S(static_cast<std::size_t>(M) * M);
  for (int i = 0; i < M; ++i) {
    for (int j = 0; j < M; ++j) S[i * M + j] = std::sqrt(2.0L / n) * std::sin((i + 1) * (j + 1) * pi / n);
  }
  std::vector<long double> y(M, 0), v(M, 0);
  for (int j = 0; j < M; ++j) {
    for (int i = 0; i < M; ++i) {
      y[j] += S[i * M + j] * x[i];
      v[j] += S[i * M + j] * xd[i];
    }
  }
  for (int j = 0; j < M; ++j) {
    const long double lambda = 4 * std::pow(std::sin((j + 1) * pi / (2 * n)), 2);
    const long double beta = 0.5L * D * lambda, w0sq = k_over_m * lambda;
    const cld root = std::sqrt(cld(beta * beta - w0sq, 0));
    const cld r1 = -beta + root, r2 = -beta - root;  // distinct: no mode here is critically damped
    const cld e1 = std::exp(r1 * t), e2 = std::exp(r2 * t);
    // y = A e^{r1 t} + B e^{r2 t}: A + B = y0, r1 A + r2 B = v0.
    const cld A = (v[j] - r2 * y[j]) / (r1 - r2), B = (r1 * y[j] - v[j]) / (r1 - r2);
    y[j] = (A * e1 + B * e2).real();
    v[j] = (A * r1 * e1 + B * r2 * e2).real();
  }
  x_out.assign(M, 0);
  xd_out.assign(M, 0);
  for (int i = 0; i < M; ++i) {
    for (int j = 0; j < M; ++j) {
      x_out[i] += S[i * M + j] * y[j];
      xd_out[i] += S[i * M + j] * v[j];
    }
  }
}

struct StepError {
  double x = 0, xd = 0;  // largest error over the scale of x (and of h x')
};

StepError propagate_and_compare(const ChainPropagator& prop, const ContactLaw& law, int n, int steps, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double h = prop.step(), w = std::sqrt(law.k_over_m);
  std::vector<double> x(n - 1), xd(n - 1), x2(n - 1), xd2(n - 1);
  for (int i = 0; i < n - 1; ++i) {
    x[i] = 1e-3 * u(rng);
    xd[i] = 1e-3 * w * u(rng);
  }
  const std::vector<double> x0 = x, xd0 = xd;
  for (int s = 0; s < steps; ++s) {
    prop.advance(n, x.data(), xd.data(), x2.data(), xd2.data());
    x.swap(x2);
    xd.swap(xd2);
  }
  std::vector<long double> xe, xde;
  sine_mode_solution(n, law.k_over_m, law.D, static_cast<long double>(h) * steps, x0, xd0, xe, xde);
  double scale = 0;  // |x| + h |x'| at the start: the energy, hence this, never grows
  for (int i = 0; i < n - 1; ++i) scale = std::max(scale, std::abs(x0[i]) + h * std::abs(xd0[i]));
  StepError err;
  for (int i = 0; i < n - 1; ++i) {
    err.x = std::max(err.x, static_cast<double>(std::fabs(x[i] - xe[i])) / scale);
    err.xd = std::max(err.xd, static_cast<double>(std::fabs(xd[i] - xde[i])) * h / scale);
  }
  return err;
}

ContactLaw law_for(double e) { return contact_law(ChainParameters{.N = 2, .k = 1e8, .e = e}); }

}  // namespace

// One step h = tau_c / 2 equals the sine-mode solution to 1e-15 of the overlaps' scale for every
// cluster size 2 ... 300 (across the small-cluster tables, the edge blocks and the Toeplitz rows)
// and e from 0.02 (the highest modes overdamped) to 1.
TEST(ChainPropagator, OneStepEqualsTheSineModeSolution) {
  for (double e : {0.02, 0.1, 0.5, 0.9, 1.0}) {
    const ContactLaw law = law_for(e);
    const ChainPropagator prop(law.k_over_m, law.D, 0.5 * law.tau_c);
    double worst = 0;
    for (int n = 2; n <= 300; n += (n < 60 ? 1 : 17)) {
      const StepError err = propagate_and_compare(prop, law, n, 1, 1000 + n);
      worst = std::max({worst, err.x, err.xd});
      ASSERT_LE(err.x, 1e-15) << "e=" << e << " n=" << n;
      ASSERT_LE(err.xd, 1e-15) << "e=" << e << " n=" << n;
    }
    std::printf("e = %.2f: band %d, worst one-step error %.2e\n", e, prop.band(), worst);
  }
}

// Over many steps the error grows at most linearly (the kernel is rounded once, so its error is
// the same every step), never like an unstable mode: 400 steps (200 tau_c) stay within 400 times
// the one-step tolerance times 4, the most that |x| + h |x'| can grow over the motion relative to
// its start for modes with h omega0 <= pi (their energy never grows).
TEST(ChainPropagator, ManyStepsStayOnTheSineModeSolution) {
  for (double e : {0.1, 0.9, 1.0}) {
    const ContactLaw law = law_for(e);
    const ChainPropagator prop(law.k_over_m, law.D, 0.5 * law.tau_c);
    for (int n : {3, 30, 150}) {
      const StepError err = propagate_and_compare(prop, law, n, 400, 7 + n);
      EXPECT_LE(err.x, 1.6e-12) << "e=" << e << " n=" << n;
      EXPECT_LE(err.xd, 1.6e-12) << "e=" << e << " n=" << n;
    }
  }
}

// The kernel decays faster than exponentially: its band at h = tau_c / 2 is a few tens of sites
// for every e, wider where damping couples sites more (small e); the entries are even in l.
TEST(ChainPropagator, KernelIsNarrowAndEven) {
  int previous = 0;
  for (double e : {1.0, 0.9, 0.5, 0.1, 0.02}) {
    const ContactLaw law = law_for(e);
    const ChainPropagator prop(law.k_over_m, law.D, 0.5 * law.tau_c);
    EXPECT_GE(prop.band(), 6) << e;
    EXPECT_LE(prop.band(), 32) << e;
    EXPECT_GE(prop.band(), previous) << e;
    previous = prop.band();
    for (int l = 0; l <= prop.band(); ++l) EXPECT_EQ(prop.kernel(0, 1, l), prop.kernel(0, 1, -l));
    EXPECT_EQ(prop.kernel(1, 0, prop.band() + 1), 0.0);
  }
}
