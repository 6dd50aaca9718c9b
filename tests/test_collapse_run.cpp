// Collision counts of the free-space collapse (paper Sec. III.D) against the three-body theory,
// and the properties of the stop rules and of the parallel driver.
#include <gtest/gtest.h>

#include <cmath>

#include "engines/engine.hpp"
#include "engines/engine_registry.hpp"
#include "simulation/collapse_run.hpp"
#include "theory/collapse_theory.hpp"

using namespace granchain;

namespace {

// Free-space launches of N particles (Sec. III.D), no gravity.
CollapseSpec free_space(int N, double e, double k) {
  CollapseSpec s;
  s.params.N = N;
  s.params.e = e;
  s.params.k = k;
  s.params.g = 0.0;
  return s;
}

CollapseSpec three_body(double e, double k, int R) {
  CollapseSpec s;
  s.params.N = 3;
  s.params.e = e;
  s.params.k = k;
  s.realizations = R;
  s.threads = 2;
  return s;
}

// Advances a free-space launch with no contact open until its ends separate (the rule `ends`)
// or, with one_body, until it moves as one body; false if t_max came first.
bool run_launch_to_end(Engine& engine, const CollapseSpec& spec, bool one_body) {
  struct Ends final : EventSink {
    int open = 0;
    void on_event(const Event& ev) override {
      if (ev.kind == EventKind::ContactBegin) ++open;
      if (ev.kind == EventKind::ContactEnd && --open == 0) request_stop();
    }
  } sink;
  for (;;) {
    sink.clear_stop();
    engine.advance_to(spec.t_max, sink);
    if (!sink.stop_requested()) return false;
    const ChainState& s = engine.state();
    if (sink.open == 0 && (s.v.back() > s.v.front() || (one_body && moves_as_one_body(spec, s)))) return true;
  }
}

// |total momentum now - at the launch| over the sum of the launch's |v_i| (unit masses).
double momentum_drift(const ChainState& initial, const ChainState& now) {
  double p0 = 0, p1 = 0, scale = 0;
  for (std::size_t i = 0; i < initial.v.size(); ++i) p0 += initial.v[i], p1 += now.v[i], scale += std::abs(initial.v[i]);
  return std::abs(p1 - p0) / scale;
}

}  // namespace

// Below e_c(3) every collision of the three-body sequence shrinks the interval between collisions
// of the same pair by q(e) per (1,2)+(2,3) cycle, and the sequence ends when that interval reaches
// ~2 tau_c ~ k^(-1/2): all collisions grow as -ln k / ln q, twice Eq. (ntot-log), whose n counts the
// intervals of one pair. Measured from 400 launches at k = 1e12 and 1e14 (the same launches at both,
// so the difference is paired), the slope agrees with -ln 10 / ln q within 4 standard errors and
// is far from Eq. (ntot-log)'s half of it.
TEST(CollapseRun, ThreeBodyCollisionsGrowLikeLogKWithTwiceThePaperSlope) {
  const double e = 0.05;
  const CollapseResult a = run_collapse(three_body(e, 1e12, 400));
  const CollapseResult b = run_collapse(three_body(e, 1e14, 400));
  const KSlope ks = k_slope(a, b);
  const double slope = ks.per_log10_k, error = ks.error;
  const double total = std::log(10.0) * theory::collisions_slope_per_ln_k(e);
  const double paper = std::log(10.0) * theory::ntot_slope_per_ln_k(e);
  EXPECT_LT(std::abs(slope - total), 4 * error) << slope << " +- " << error << " vs " << total;
  EXPECT_GT(std::abs(slope - paper), 50 * error);
  EXPECT_EQ(a.collapsed, 0);
}

// Above e_c(3) the count converges as k grows: two collisions (1-2 and 2-3, or 2-3 and 1-2) for
// almost every launch once tau_c is far below the time between them.
TEST(CollapseRun, ThreeBodyCountConvergesAboveCriticalRestitution) {
  const CollapseResult r = run_collapse(three_body(0.5, 1e12, 200));
  EXPECT_DOUBLE_EQ(r.n_tot_mean, 2.0);
  EXPECT_EQ(r.n_tot_min, 2u);
  EXPECT_EQ(r.n_tot_max, 2u);
}

// The strict rule never stops before the paper's (every sorted state has v_N > v_1), and the
// counts do not depend on the number of threads.
TEST(CollapseRun, StrictRuleCountsAtLeastTheEndsRuleAndThreadsDoNotMatter) {
  CollapseSpec s;
  s.params.N = 6;
  s.params.e = 0.6;
  s.params.k = 1e6;
  s.realizations = 60;
  s.threads = 1;
  const CollapseResult ends1 = run_collapse(s);
  s.threads = 3;
  const CollapseResult ends3 = run_collapse(s);
  s.rule = StopRule::Strict;
  const CollapseResult strict = run_collapse(s);
  int more = 0;
  for (int r = 0; r < s.realizations; ++r) {
    EXPECT_EQ(ends1.outcomes[r].n_tot(), ends3.outcomes[r].n_tot());
    EXPECT_EQ(ends1.outcomes[r].t_stop, ends3.outcomes[r].t_stop);
    EXPECT_GE(strict.outcomes[r].n_tot(), ends1.outcomes[r].n_tot());
    more += strict.outcomes[r].n_tot() > ends1.outcomes[r].n_tot();
  }
  EXPECT_GT(more, 0) << "inner pairs still approach when the ends separate, in some launches";
}

// Hard spheres below e_c(3): launches that reach the collapsing sequence before the ends separate
// collapse (reported, not averaged), under the strict rule at least as many; the TC model lets
// every launch finish.
TEST(CollapseRun, HardSpheresCollapseUnlessTheTcModelIsOn) {
  CollapseSpec s = three_body(0.05, std::numeric_limits<double>::infinity(), 50);
  s.engine.kind = EngineKind::Hard;
  const CollapseResult ends = run_collapse(s);
  EXPECT_GT(ends.collapsed, 0);
  s.rule = StopRule::Strict;
  const CollapseResult strict = run_collapse(s);
  EXPECT_GE(strict.collapsed, ends.collapsed);
  for (int r = 0; r < 50; ++r)
    if (ends.outcomes[r].collapsed) EXPECT_TRUE(strict.outcomes[r].collapsed) << r;
  s.engine.hard.tc = 1e-6;
  const CollapseResult tc = run_collapse(s);
  EXPECT_EQ(tc.collapsed, 0);
  EXPECT_TRUE(std::isfinite(tc.n_tot_mean));
}

// Free-space collapses at N = 25, e = 0.3, k = 1e8 end with pairs whose two sides rest against
// each other with relative speeds far below the particles' speeds. While the engine kept absolute
// velocities, such relative speeds fell below round-off (~1e-17 of the speeds): pairs touched and
// parted every 1e-6 tau_c, and one launch once stopped with "events pile up" after 5 minutes
// (hence the held contacts of ExactEngine::merge). With relative velocities as primary variables
// they stay resolved: launches 0..199 (a few seconds) all end (no stall, no error) with no
// contact beginning below resolution, and momentum, which every contact conserves exactly in the
// model, is conserved to round-off in each.
TEST(CollapseRun, RestingPairsStayResolvedAndEveryLaunchEnds) {
  const CollapseSpec spec = free_space(25, 0.3, 1e8);
  std::uint64_t held = 0, grazing = 0;
  for (int launch = 0; launch < 200; ++launch) {
    const ChainState initial = collapse_initial_state(spec, launch);
    auto engine = make_engine(spec.engine, spec.params, initial, nullptr);
    ASSERT_TRUE(run_launch_to_end(*engine, spec, false)) << "launch " << launch << ": no end before t_max";
    held += engine->below_resolution().held_contacts;
    grazing += engine->below_resolution().grazing_contacts;
    EXPECT_LT(momentum_drift(initial, engine->state()), 1e-12) << "launch " << launch;
  }
  EXPECT_EQ(grazing, 0u);
  EXPECT_EQ(held, 0u);
}

// At k = 1e14 launch 282 of N = 25, e = 0.5 turns the whole chain into one body: by t ~ 19 every
// relative velocity is below 1e-17 and a cluster's mode amplitudes (~1e-163) underflowed when
// squared, so its contacts never closed and the launch ran into t_max ("the stop rule did not
// hold"). With amplitudes that cannot underflow (ModeConstants::amplitude) its contacts close; the
// launch ends, by the stop rule or as one body, and conserves momentum to round-off.
TEST(CollapseRun, AChainAtRestWithinRoundOffStillEnds) {
  CollapseSpec spec;
  spec.params.N = 25;
  spec.params.e = 0.5;
  spec.params.k = 1e14;
  spec.params.g = 0.0;
  const ChainState initial = collapse_initial_state(spec, 282);
  auto engine = make_engine(spec.engine, spec.params, initial, nullptr);
  ASSERT_TRUE(run_launch_to_end(*engine, spec, true)) << "no end before t_max at t = " << engine->time();
  EXPECT_LT(momentum_drift(initial, engine->state()), 1e-12);
  EXPECT_LT(engine->time(), 100.0);
}

// The one-body test: velocities equal to within 1e-13 of the speeds end a launch; a relative
// velocity of 1e-12 of them does not; on a wall a body moving toward it does not.
TEST(CollapseRun, OneBodyMeansEveryRelativeVelocityBelowResolution) {
  CollapseSpec spec;
  spec.params.N = 3;
  ChainState s;
  s.z = {0, 2, 4};
  s.v = {0.0035, std::nextafter(0.0035, 1.0), 0.0035 * (1 - 5e-14)};
  EXPECT_TRUE(moves_as_one_body(spec, s));
  s.v = {1.0, 1.0 + 1e-12, 1.0};
  EXPECT_FALSE(moves_as_one_body(spec, s));
  s.v = {0.0, 0.0, 0.0};
  EXPECT_TRUE(moves_as_one_body(spec, s));
  s.v = {-0.5, -0.5, -0.5};
  EXPECT_TRUE(moves_as_one_body(spec, s));
  spec.setup = CollapseSetup::Wall;
  EXPECT_FALSE(moves_as_one_body(spec, s));
}

// The states handed to a ClosedStateLog: one at each instant when the last open contact closes,
// in record order, at the time that contact ended, with every gap open (z_{i+1} - z_i >= d up to
// round-off of the heights) and the launch's momentum (free space conserves it); each launch's
// states follow its records. N = 10, e = 0.3, k = 1e8, 6 launches on two threads.
TEST(CollapseRun, ClosedStatesFollowTheirRecordsWithEveryContactOpenAndMomentumKept) {
  CollapseSpec s = free_space(10, 0.3, 1e8);
  s.realizations = 6;
  s.threads = 2;
  std::vector<CollisionRecord> recs;
  int launches = 0;
  std::size_t states_seen = 0;
  run_collapse(s, [&](const std::vector<CollisionRecord>& r) { recs = r; }, {},
               [&](const std::vector<ClosedState>& states) {
                 ASSERT_FALSE(recs.empty());
                 ASSERT_FALSE(states.empty());
                 const ChainState launch = collapse_initial_state(s, recs.front().realization);
                 double p0 = 0;
                 for (double v : launch.v) p0 += v;
                 std::size_t previous = 0;
                 for (std::size_t n = 0; n < states.size(); ++n) {
                   const ClosedState& c = states[n];
                   ASSERT_LT(c.after, recs.size());
                   if (n > 0) EXPECT_GT(c.after, previous);
                   previous = c.after;
                   EXPECT_NEAR(c.state.t, recs[c.after].t_end, 1e-12 * (1 + c.state.t));
                   double p = 0;
                   for (double v : c.state.v) p += v;
                   EXPECT_NEAR(p, p0, 1e-12 * s.params.N);
                   for (std::size_t i = 0; i + 1 < c.state.z.size(); ++i)
                     EXPECT_GE(c.state.z[i + 1] - c.state.z[i], s.params.d - 1e-12 * (1 + std::abs(c.state.z[i])));
                 }
                 states_seen += states.size();
                 ++launches;
               });
  EXPECT_EQ(launches, 6);
  EXPECT_GT(states_seen, 6u * 10u);
}
