// The collision sequence of a collapse (analysis/collision_sequence): gaps, per-pair gaps and
// collapse events on a hand-made sequence; a geometric and a power-law approach to a collapse
// told apart and their ratio and exponent recovered; and the hard-sphere three-body collapse
// (e < e_c(3)) read as geometric with the ratio of Eq. (deltat12), q per (1,2)+(2,3) cycle.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/collision_sequence.hpp"
#include "simulation/collapse_run.hpp"
#include "theory/collapse_theory.hpp"

using namespace granchain;
using namespace granchain::analysis;

namespace {

// Free-space launches of hard spheres (Sec. III.D), on two threads.
CollapseSpec hard_launches(int N, double e, int launches) {
  CollapseSpec spec;
  spec.params.N = N;
  spec.params.e = e;
  spec.params.g = 0.0;
  spec.engine.kind = EngineKind::Hard;
  spec.realizations = launches;
  spec.threads = 2;
  return spec;
}

}  // namespace

TEST(CollisionSequence, GapsPairsAndEventsOfAHandMadeSequence) {
  // Pairs 1, 2, 1 close together, a long flight, then 4, 5 close together, then 7 alone.
  const std::vector<Collision> c = {{0.0, 0.1, 1}, {0.15, 0.2, 2}, {0.22, 0.3, 1}, {5.0, 5.1, 4}, {5.12, 5.2, 5}, {9.0, 9.1, 7}};
  const std::vector<double> g = system_gaps(c);
  ASSERT_EQ(g.size(), 5u);
  EXPECT_NEAR(g[0], 0.05, 1e-12);
  EXPECT_NEAR(g[2], 4.7, 1e-12);
  const std::vector<double> p = pair_gaps(c);
  ASSERT_EQ(p.size(), 1u);  // only pair 1 collides twice
  EXPECT_NEAR(p[0], 0.12, 1e-12);
  const std::vector<CollapseEvent> ev = collapse_events(c, 0.5, 2);
  ASSERT_EQ(ev.size(), 2u);
  EXPECT_EQ(ev[0].first, 0u);
  EXPECT_EQ(ev[0].collisions, 3u);
  EXPECT_EQ(ev[0].particles, 3);  // particles 1, 2, 3
  EXPECT_EQ(ev[1].first, 3u);
  EXPECT_EQ(ev[1].collisions, 2u);
  EXPECT_EQ(ev[1].particles, 3);  // particles 4, 5, 6
  EXPECT_EQ(collapse_events(c, 0.5, 1).size(), 3u);
  EXPECT_EQ(particles_involved({{0, 0, 0}, {0, 0, 1}}, 0, 1), 2);  // the wall is no particle
}

TEST(CollisionSequence, CascadesJoinEventsThatFollowWithinTheWait) {
  // Waits 0.5, 0.5, 3, 0.9, 1: with max_wait 1, cascades of 3, 2 and 1 events (a wait equal to
  // max_wait starts a new cascade).
  const std::vector<EventSpan> ev = {{0, 1}, {1.5, 2}, {2.5, 3}, {6, 7}, {7.9, 8}, {9, 10}};
  const std::vector<Cascade> c = cascades(ev, 1.0);
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c[0].first, 0u);
  EXPECT_EQ(c[0].events, 3u);
  EXPECT_EQ(c[1].first, 3u);
  EXPECT_EQ(c[1].events, 2u);
  EXPECT_EQ(c[2].first, 5u);
  EXPECT_EQ(c[2].events, 1u);
  EXPECT_EQ(cascades(ev, 10.0).size(), 1u);
  EXPECT_EQ(cascades(ev, 0.1).size(), ev.size());
  EXPECT_TRUE(cascades({}, 1.0).empty());
}

// tau_n = t* - t_n = q^n exactly (q = 0.8) and tau_n = n^-1.5 (beta = 2.5): each is a straight
// line in its own coordinates, recovered to round-off, and the other line fits worse.
TEST(CollisionSequence, GeometricAndPowerLawApproachesAreToldApart) {
  const double t_star = 3.0;
  std::vector<Collision> geo, pow;
  for (int n = 1; n <= 200; ++n) {
    const double tg = t_star - std::pow(0.8, n), tp = t_star - std::pow(static_cast<double>(n), -1.5);
    geo.push_back({tg, tg, 1 + n % 2});
    pow.push_back({tp, tp, 1 + n % 2});
  }
  // Above tau = 1e-9 the subtraction t* - t_n keeps tau to 1e-6 relative (t* = 3, 16 digits).
  const ShrinkFit g = fit_remaining_time(geo, t_star, 1e-9, 1.0), p = fit_remaining_time(pow, t_star, 1e-9, 1.0);
  EXPECT_NEAR(g.ln_q, std::log(0.8), 1e-5);
  EXPECT_LT(g.rms_geometric, 1e-5);
  EXPECT_GT(g.rms_power, 100 * g.rms_geometric + 0.1);
  EXPECT_NEAR(p.beta, 2.5, 1e-5);
  EXPECT_LT(p.rms_power, 1e-5);
  EXPECT_GT(p.rms_geometric, 100 * p.rms_power + 0.1);
  // n(tau): collisions with tau_n >= tau; for q^n >= 1e-3, n <= ln(1e-3)/ln(0.8) = 30.96.
  EXPECT_EQ(collisions_before_remaining(geo, t_star, {1e-3})[0], 30.0);
  EXPECT_EQ(collisions_before_remaining(pow, t_star, {1e-3})[0], 99.0);  // n^-1.5 >= 1e-3 for n <= 100, tau exactly 1e-3 at n = 100 loses to round-off
  EXPECT_LT(fit_remaining_time(geo, t_star, 0.5, 1.0).points, 4);
  // Two pairs alternating: each pair's interval shrinks by q^2 = 0.64 from one of its collisions
  // to the next.
  EXPECT_NEAR(mean_pair_log_ratio(geo, 0, 60), 2 * std::log(0.8), 1e-9);
  EXPECT_TRUE(std::isnan(mean_pair_log_ratio(geo, 0, 3)));
}

// Three hard spheres below e_c(3) collapse with the interval of each pair shrinking by q per cycle
// of two collisions (Eq. deltat12): the remaining time falls by sqrt(q) per collision on average.
// The fit over tau = 1e-9 ... 1e-2 (well above the time resolution of t ~ 1) reads ln q / 2 to 3 %
// (the two collisions of a cycle shrink tau by unequal factors, which the straight line averages),
// and a power of n fits far worse.
TEST(CollisionSequence, ThreeHardSpheresCollapseGeometrically) {
  for (double e : {0.03, 0.05}) {
    const CollapseSpec spec = hard_launches(3, e, 20);
    std::vector<std::vector<Collision>> seq(20);
    const CollapseResult r = run_collapse(spec, [&](const std::vector<CollisionRecord>& recs) {
      for (const auto& x : recs) seq[static_cast<std::size_t>(x.realization)].push_back({x.t_begin, x.t_end, x.i});
    });
    // Not every launch collapses: some end with the three separating before the sequence sets in.
    std::size_t l = 0;
    while (l < r.outcomes.size() && !r.outcomes[l].collapsed) ++l;
    ASSERT_LT(l, r.outcomes.size()) << "no launch collapsed at e = " << e;
    const ShrinkFit f = fit_remaining_time(seq[l], r.outcomes[l].t_stop, 1e-9, 1e-2);
    ASSERT_GE(f.points, 8) << "e = " << e;
    EXPECT_NEAR(f.ln_q, 0.5 * std::log(theory::q_ratio(e)), 0.03 * 0.5 * std::abs(std::log(theory::q_ratio(e)))) << "e = " << e;
    EXPECT_LT(f.rms_geometric * 3, f.rms_power) << "e = " << e;
  }
}

// Twenty-five hard spheres launched inward collapse with a cluster of exactly n* particles, the
// fewest that can collapse in free space at that e (the least n with e_c(n) > e, Sec. III.B's
// estimate): 6 at e = 0.3 (e_c(5) = 0.260 < 0.3 < e_c(6) = 1/3), 10 at e = 0.5 (e_c(9) = 0.490,
// e_c(10) = 0.528), in each of 50 launches; the particles are those of the last 1000 collisions,
// which the collapse watch needs within 1e-9. The approach is geometric in most launches.
TEST(CollisionSequence, HardSpheresCollapseWithTheFewestParticlesThatCan) {
  for (const auto& [e, n_star] : {std::pair{0.3, 6}, std::pair{0.5, 10}}) {
    ASSERT_LT(theory::ec_free(n_star - 1), e);
    ASSERT_GT(theory::ec_free(n_star), e);
    const CollapseSpec spec = hard_launches(25, e, 50);
    int launches = 0, geometric = 0;
    run_collapse(spec, [&](const std::vector<CollisionRecord>& recs) {
      std::vector<Collision> seq;
      for (const auto& x : recs) seq.push_back({x.t_begin, x.t_end, x.i});
      ASSERT_GE(seq.size(), 1000u);
      ++launches;
      EXPECT_EQ(particles_involved(seq, seq.size() - 1000, seq.size() - 1), n_star) << "e = " << e << ", launch " << recs.front().realization;
      const ShrinkFit f = fit_remaining_time(seq, seq.back().t_begin, 1e-8, 1e-2);
      geometric += f.points >= 4 && f.rms_geometric < f.rms_power;
    });
    EXPECT_EQ(launches, 50);
    // 90 % and 75 % of 1000 launches in docs/beyond.md: at least 25 of 50 is 4 binomial errors below 75 %.
    EXPECT_GE(geometric, 25) << "e = " << e;
  }
}

// The soft free-space launch has one dimensionless number besides e and N: the launch's gaps over
// the distance covered during one contact, a / (v0 tau_c), with tau_c ~ k^-1/2 (Eq. tau_c). Scaling
// lengths by 1/lambda and k by lambda^2, or speeds by lambda and k by lambda^2, leaves the equations
// of motion unchanged up to units of time, so the collision count must not change: k enters only
// through a sqrt(k) / v0, and everything at the scale of one contact (the collapse events and
// cascades of docs/beyond.md) is the same at every k in units of tau_c. 1000 launches each at
// N = 10, e = 0.3; two-sample z < 4 for the equivalent launches, while a hundredfold k at the
// same gaps (n_tot up by ~40 %) is told apart by > 10 standard errors.
TEST(CollisionSequence, SoftLaunchesDependOnKOnlyThroughGapsOverContactLength) {
  const auto count = [](double k, double a, double v0) {
    CollapseSpec spec;
    spec.params.N = 10;
    spec.params.e = 0.3;
    spec.params.k = k;
    spec.params.g = 0.0;
    spec.launch.a = a;
    spec.launch.v0 = v0;
    spec.launch.dv0 = 0.1 * v0;
    spec.realizations = 1000;
    spec.threads = 2;
    return run_collapse(spec);
  };
  const CollapseResult base = count(1e10, 1.0, 1.0);
  const auto z = [&](const CollapseResult& r) { return (r.n_tot_mean - base.n_tot_mean) / std::hypot(r.n_tot_error, base.n_tot_error); };
  EXPECT_LT(std::abs(z(count(1e12, 0.1, 1.0))), 4.0);   // lengths / 10, k * 100
  EXPECT_LT(std::abs(z(count(1e12, 1.0, 10.0))), 4.0);  // speeds * 10, k * 100
  EXPECT_GT(z(count(1e12, 1.0, 1.0)), 10.0);            // k * 100 alone: more collisions
}
