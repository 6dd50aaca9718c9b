// alpha(N) at the same e on both sides: the slopes between neighbouring columns and the largest
// column's excess over the line through the others, on synthetic exponents with a known law
// alpha_e(N) = s log10 N + q_e (Eq. alphafit with an e-dependent intercept, as Table 1's alphas).
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/alpha_across_n.hpp"
#include "model/random.hpp"

using namespace granchain;
using namespace granchain::analysis;

namespace {

const double kSlope = 0.17;
const double kEs[] = {0.1, 0.2, 0.3, 0.4};
double intercept(double e) { return -0.05 + 0.1 * e; }  // alpha depends on e; the slopes must not

std::vector<ColumnExponents> columns_on_law(const std::vector<int>& Ns, double sigma, Rng* rng, double last_offset = 0) {
  std::vector<ColumnExponents> cols;
  for (int N : Ns) {
    ColumnExponents c{N, {}};
    for (double e : kEs) {
      double a = kSlope * std::log10(static_cast<double>(N)) + intercept(e) + (N == Ns.back() ? last_offset : 0.0);
      if (rng) a += sigma * rng->normal();
      c.by_e[e] = {0.0, a, sigma};
    }
    cols.push_back(c);
  }
  return cols;
}

}  // namespace

// On the exact law the neighbour slopes are the law's slope and the largest column lies on the
// line; an offset of the largest column is its excess, e by e.
TEST(AlphaAcrossN, ExactLawGivesItsSlopeAndNoExcess) {
  const std::vector<int> Ns = {25, 50, 100, 150, 300};
  const auto slopes = neighbour_slopes(columns_on_law(Ns, 0.002, nullptr));
  ASSERT_EQ(slopes.size(), 4u);
  for (const auto& s : slopes) {
    EXPECT_NEAR(s.slope, kSlope, 1e-12);
    EXPECT_EQ(s.e_count, 4);
  }
  EXPECT_EQ(slopes.back().N1, 150);
  EXPECT_EQ(slopes.back().N2, 300);
  LineExcess x;
  ASSERT_TRUE(excess_over_line(columns_on_law(Ns, 0.002, nullptr, 0.0), x));
  EXPECT_EQ(x.N, 300);
  EXPECT_EQ(x.others, (std::vector<int>{25, 50, 100, 150}));
  EXPECT_NEAR(x.excess, 0.0, 1e-12);
  ASSERT_TRUE(excess_over_line(columns_on_law(Ns, 0.002, nullptr, 0.013), x));
  EXPECT_NEAR(x.excess, 0.013, 1e-12);
  ASSERT_EQ(x.per_e.size(), 4u);
  for (const auto& p : x.per_e) EXPECT_NEAR(p.y, 0.013, 1e-12);
}

// Through two columns the line's prediction at x0 is y1 + t (y2 - y1), t = (x0 - x1) / (x2 - x1),
// with variance sigma1^2 (1 - t)^2 + sigma2^2 t^2; the excess's error adds the column's own.
TEST(AlphaAcrossN, ExtrapolationErrorOfTheLine) {
  std::vector<ColumnExponents> cols = {{50, {{0.3, {0, 0.25, 0.004}}}}, {100, {{0.3, {0, 0.29, 0.003}}}},
                                       {400, {{0.3, {0, 0.40, 0.005}}}}};
  LineExcess x;
  ASSERT_TRUE(excess_over_line(cols, x));
  const double x1 = std::log10(50.0), x2 = std::log10(100.0), x0 = std::log10(400.0), t = (x0 - x1) / (x2 - x1);
  EXPECT_NEAR(x.excess, 0.40 - (0.25 + t * 0.04), 1e-12);
  EXPECT_NEAR(x.per_e[0].error, std::sqrt(0.004 * 0.004 * (1 - t) * (1 - t) + 0.003 * 0.003 * t * t + 0.005 * 0.005), 1e-12);
  // A column with another e only gives no line: no excess at all.
  cols.back().by_e = {{0.4, {0, 0.40, 0.005}}};
  EXPECT_FALSE(excess_over_line(cols, x));
  EXPECT_TRUE(neighbour_slopes(cols).size() == 1u);  // 50 -> 100 only; 100 -> 400 share no e
}

// With noise of known size the errors are calibrated: over 3000 synthetic sets the pulls of the
// neighbour slopes and of the per-e excess (three columns: the line has no dof to rescale by) have
// mean 0 and standard deviation 1, each within 4 of its sampling error (1/sqrt(n), 1/sqrt(2n)).
TEST(AlphaAcrossN, ErrorsAreCalibrated) {
  Rng rng(36);
  const int trials = 3000;
  double s1 = 0, s2 = 0, x1 = 0, x2 = 0;
  int ns = 0, nx = 0;
  for (int t = 0; t < trials; ++t) {
    const auto cols = columns_on_law({100, 150, 200}, 0.004, &rng);
    for (const auto& e : kEs) {  // per e, so the mean over e's max(propagated, scatter) is not in the way
      std::vector<ColumnExponents> one;
      for (const auto& c : cols) one.push_back({c.N, {{e, c.by_e.at(e)}}});
      const auto s = neighbour_slopes(one);
      const double p = (s[0].slope - kSlope) / s[0].error;
      s1 += p;
      s2 += p * p;
      ++ns;
      LineExcess x;
      ASSERT_TRUE(excess_over_line(one, x));
      const double q = x.excess / x.error;
      x1 += q;
      x2 += q * q;
      ++nx;
    }
  }
  const double ms = s1 / ns, sds = std::sqrt(s2 / ns - ms * ms), mx = x1 / nx, sdx = std::sqrt(x2 / nx - mx * mx);
  EXPECT_NEAR(ms, 0.0, 4.0 / std::sqrt(ns));
  EXPECT_NEAR(sds, 1.0, 4.0 / std::sqrt(2.0 * ns));
  EXPECT_NEAR(mx, 0.0, 4.0 / std::sqrt(nx));
  EXPECT_NEAR(sdx, 1.0, 4.0 / std::sqrt(2.0 * nx));
}
