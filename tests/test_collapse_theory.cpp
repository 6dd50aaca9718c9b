// The paper's closed forms for inelastic collapse, each pinned to a value derived independently of
// the formula under test: exact trigonometric and rational values worked out by hand, the
// three-body hard-sphere collision sequence iterated event by event, and soft-sphere collisions
// from the exact engine.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "engines/exact/exact_engine.hpp"
#include "model/chain_parameters.hpp"
#include "test_helpers.hpp"
#include "theory/collapse_theory.hpp"

using namespace granchain;
using namespace granchain::theory;

namespace {

// Three hard spheres in free space, followed through their collisions with the collision law of
// Appendix A only. State: gaps g12, g23 and their rates u12 = v2 - v1, u23 = v3 - v2 (kept as
// gaps, so a sequence of intervals shrinking over hundreds of orders of magnitude keeps its
// relative precision). Returns the times of the 1-2 collisions; stops when no pair approaches or
// after max_collisions.
struct ThreeBodyRun {
  std::vector<double> t12;   // times of the collisions of particles 1 and 2
  std::vector<double> dt12;  // intervals between them, summed step by step (no cancellation)
  int collisions = 0;
  bool ended = false;  // no pair approaches any more
};

ThreeBodyRun three_hard_spheres(double e, double g12, double g23, double u12, double u23, int max_collisions) {
  const double b = 0.5 * (1.0 + e);
  ThreeBodyRun run;
  double t = 0.0, since12 = 0.0;
  const double inf = std::numeric_limits<double>::infinity();
  while (run.collisions < max_collisions) {
    const double t1 = u12 < 0 ? g12 / -u12 : inf;
    const double t2 = u23 < 0 ? g23 / -u23 : inf;
    if (t1 == inf && t2 == inf) {
      run.ended = true;
      break;
    }
    const double dt = std::min(t1, t2);
    t += dt;
    since12 += dt;
    g12 += u12 * dt;
    g23 += u23 * dt;
    // v1' = a v1 + b v2, v2' = b v1 + a v2 (a = 1 - b): the pair's relative velocity is reversed
    // and scaled by e, and the middle particle's change b * (relative velocity) passes to the
    // other gap's rate.
    if (t1 <= t2) {
      g12 = 0.0;
      u23 += b * u12;
      u12 *= -e;
      run.t12.push_back(t);
      run.dt12.push_back(since12);
      since12 = 0.0;
    } else {
      g23 = 0.0;
      u12 += b * u23;
      u23 *= -e;
    }
    ++run.collisions;
  }
  return run;
}

}  // namespace

TEST(CollapseTheory, WallCriticalValuesMatchExactValues) {
  // N = 2: tan^2(pi/8) = ((1 - cos(pi/4)) / sin(pi/4))^2 = (sqrt 2 - 1)^2 = 3 - 2 sqrt 2.
  EXPECT_NEAR(ec_wall_icw(2), 3.0 - 2.0 * std::sqrt(2.0), 1e-15);
  // N = 3: tan^2(pi/6) = 1/3. N = 1: a single particle against an elastic wall never collapses.
  EXPECT_NEAR(ec_wall_icw(3), 1.0 / 3.0, 1e-15);
  EXPECT_EQ(ec_wall_icw(1), 0.0);
  // Large N: tan(pi/4 - x) = 1 - 2x + O(x^2), so N (1 - e_c) -> pi with an O(1/N) correction.
  for (int N : {100, 10000, 1000000}) {
    EXPECT_NEAR(N * (1.0 - ec_wall_icw(N)), std::numbers::pi, 6.0 / N) << N;
    EXPECT_NEAR(ec_wall_icw_asymptotic(N), 1.0 - std::numbers::pi / N, 1e-15);
  }
}

TEST(CollapseTheory, CushionModelAndItsInverse) {
  EXPECT_NEAR(cushion_Nc_wall(0.0), std::log(4.0), 1e-15);
  EXPECT_NEAR(cushion_Nc_wall(0.5), 2.0 * std::log(8.0), 1e-14);
  // The critical e of N particles is the inverse: N_c^wall(e_c(N)) = N.
  for (double N : {2.0, 3.0, 10.0, 15.0, 100.0, 1e4, 1e8}) {
    const double e = ec_wall_cushion(N);
    EXPECT_NEAR(cushion_Nc_wall(e) / N, 1.0, 1e-9) << N;
  }
  // Eq. (ec_cushion) is its large-N form: the relative error of 1 - e shrinks as N grows
  // (6.4%, 2.7%, 1.4%, 0.9% at N = 1e2, 1e4, 1e6, 1e8: corrections of order (ln ln N / ln N)^2).
  double previous = 1.0;
  for (double N : {1e2, 1e4, 1e6, 1e8}) {
    const double rel = std::abs((1.0 - ec_wall_cushion_asymptotic(N)) / (1.0 - ec_wall_cushion(N)) - 1.0);
    EXPECT_LT(rel, previous) << N;
    previous = rel;
  }
  EXPECT_LT(previous, 0.01);
  // The paper: ICW and cushion cross near N = 15 (ICW lower below, cushion lower above).
  EXPECT_LT(ec_wall_icw(10), ec_wall_cushion(10.0));
  EXPECT_GT(ec_wall_icw(20), ec_wall_cushion(20.0));
}

TEST(CollapseTheory, FreeSpaceEstimate) {
  // tan(pi/12) = 2 - sqrt 3, so e_c(3) = (2 - sqrt 3)^2 = 7 - 4 sqrt 3.
  EXPECT_NEAR(ec_free(3), 7.0 - 4.0 * std::sqrt(3.0), 1e-15);
  EXPECT_NEAR(ec3(), 0.0717967697244908, 1e-15);
  // The symmetry e_c(2N) = e_c^wall(N), Eq. (symmetry).
  for (int N : {2, 3, 5, 50}) EXPECT_NEAR(ec_free(2 * N), ec_wall_icw(N), 1e-15) << N;
  EXPECT_THROW(ec_free(2), std::domain_error);
}

TEST(CollapseTheory, FixedPointsQAndFByHand) {
  // By hand at e = 0.05: b = 0.525, b^2 - 4e = 0.075625 = 0.275^2, so m* = -1/8, m'* = -8,
  // q = (m*/(e m'*))^2 = (5/16)^2 = 25/256 and f = (1/8)(1/0.16 - 1) = 21/32.
  EXPECT_NEAR(m_star(0.05), -0.125, 1e-15);
  EXPECT_NEAR(m_prime_star(0.05), -8.0, 1e-13);
  EXPECT_NEAR(q_ratio(0.05), 25.0 / 256.0, 1e-15);
  EXPECT_NEAR(f_shift(0.05), 21.0 / 32.0, 1e-13);
  EXPECT_NEAR(ntot_slope_per_ln_k(0.05), -1.0 / (2.0 * std::log(25.0 / 256.0)), 1e-13);
  // Eq. (def_q) as printed equals the square of m*/(e m'*) everywhere on the range.
  for (double e : {0.001, 0.01, 0.03, 0.06, 0.0717}) {
    const double r = m_star(e) / (e * m_prime_star(e));
    EXPECT_NEAR(q_ratio(e), r * r, 1e-12) << e;
    EXPECT_GT(f_shift(e), 0.0) << e;
  }
  // q -> 1 at e_c(3), where the fixed points merge; no fixed points above it.
  EXPECT_NEAR(q_ratio(ec3()), 1.0, 1e-6);
  EXPECT_THROW(q_ratio(ec3() + 1e-6), std::domain_error);
  EXPECT_THROW(ntot_slope_per_ln_k(0.0), std::domain_error);
}

// The hard-sphere three-body sequence started at the fixed-point velocity ratio m* shrinks its
// 1-2 collision intervals by exactly q per cycle (Eq. deltat12).
TEST(CollapseTheory, QIsTheIntervalRatioOfTheThreeBodySequence) {
  for (double e : {0.01, 0.03, 0.05, 0.07}) {
    // Just after a 2-3 collision: 1 approaches 2 at unit speed, 3 leaves 2 at -m* (m = u23/u12).
    const ThreeBodyRun run = three_hard_spheres(e, 1.0, 0.0, -1.0, -m_star(e), 60);
    ASSERT_FALSE(run.ended) << e;
    ASSERT_GE(run.dt12.size(), 20u);
    for (std::size_t n = 2; n < run.dt12.size(); ++n) {
      const double ratio = run.dt12[n] / run.dt12[n - 1];
      EXPECT_NEAR(ratio, q_ratio(e), 1e-9 * (1.0 + q_ratio(e))) << "e=" << e << " n=" << n;
    }
  }
}

// e_c(3) from the collision sequence alone: just below it a sequence started at m* goes on for
// thousands of collisions in a finite time; just above it every start ends after a few.
TEST(CollapseTheory, ThreeBodyCollapseSetsInAtEc3) {
  const double below = ec3() - 1e-3, above = ec3() + 1e-3;
  const ThreeBodyRun collapsing = three_hard_spheres(below, 1.0, 0.0, -1.0, -m_star(below), 4000);
  EXPECT_FALSE(collapsing.ended);
  EXPECT_EQ(collapsing.collisions, 4000);
  // The accumulated time converges (a collapse): the last thousand collisions add < 1e-6 of it.
  const auto& t = collapsing.t12;
  EXPECT_LT(t.back() - t[t.size() - 500], 1e-6 * t.back());
  for (double m0 : {-0.05, -0.15, -0.2, -0.25, -0.3, -0.5, -1.0, -3.0}) {
    const ThreeBodyRun run = three_hard_spheres(above, 1.0, 0.0, -1.0, -m0, 4000);
    EXPECT_TRUE(run.ended) << m0;
    EXPECT_LT(run.collisions, 200) << m0;
  }
}

// Appendix B: soft spheres repeat the hard-sphere velocity sequence, and the interval between
// contact ends of the same pair obeys t12(n) = q t12(n-1) - f tau_c. Measured with the exact
// engine at k = 1e14 (tau_c ~ 2e-7) from the fixed-point start, e = 0.05.
TEST(CollapseTheory, SoftSphereShiftFMatchesExactEngine) {
  const double e = 0.05;
  ChainParameters p{.N = 3, .g = 0.0, .k = 1e14, .e = e};
  const double tau_c = contact_law(p).tau_c;
  // Particles 2 and 3 touch and separate at -m*, particle 1 approaches 2 at unit speed.
  const ChainState s0{0.0, {0.0, 2.0, 3.0}, {1.0, 0.0, -m_star(e)}};
  ExactEngine engine(p, s0, nullptr);
  test_support::EventRecorder rec;
  engine.advance_to(3.0, rec);
  std::vector<double> ends12;
  for (const Event& ev : rec.events) {
    if (ev.kind == EventKind::ContactEnd && ev.i == 0) ends12.push_back(ev.t);
  }
  int checked = 0;
  for (std::size_t n = 2; n < ends12.size(); ++n) {
    const double prev = ends12[n - 1] - ends12[n - 2], cur = ends12[n] - ends12[n - 1];
    if (cur < 20.0 * tau_c) break;  // beyond this the three contacts start to overlap in time
    const double f_measured = (q_ratio(e) * prev - cur) / tau_c;
    EXPECT_NEAR(f_measured, f_shift(e), 1e-6) << "n=" << n << " t12=" << cur;
    ++checked;
  }
  EXPECT_GE(checked, 3);
}
