// The hard-sphere engine (k = infinity) against the collision law, conservation, the three-body
// collapse theory, Bernu and Mazighi's exact two-sphere wall value and the exact soft engine at
// large k.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "engines/exact/exact_engine.hpp"
#include "engines/hard_sphere_engine.hpp"
#include "model/collapse_setups.hpp"
#include "model/random.hpp"
#include "theory/collapse_theory.hpp"
#include "test_helpers.hpp"

using namespace granchain;
using test_support::EventRecorder;

namespace {

ChainParameters free_space(int N, double e) { return {.N = N, .g = 0.0, .k = 1e5, .e = e}; }

// Runs until no neighbours approach and no floor is involved: the free-space end of all collisions.
// Returns false on inelastic collapse.
bool run_to_separation(HardSphereEngine& engine, EventRecorder& rec, double t_max = 1e6) {
  try {
    engine.advance_to(t_max, rec);
  } catch (const InelasticCollapseError&) {
    return false;
  }
  return true;
}

bool sorted_velocities(const ChainState& s) { return std::is_sorted(s.v.begin(), s.v.end()); }

// How many of R spheres-on-a-wall starts collapse: N spheres a = 1 apart, thrown at the wall with
// velocities -1 + 0.5 xi (xi uniform in [-1, 1)), the wall's restitution e like the spheres'.
int wall_throw_collapses(int N, double e, int R) {
  const ChainParameters p{.N = N, .g = 0.0, .k = 1e5, .e = e};
  int collapsed = 0;
  for (int seed = 1; seed <= R; ++seed) {
    Wall wall(e);
    HardSphereEngine engine(p, wall_throw_state(p, {.a = 1.0, .v0 = 1.0, .dv0 = 0.5}, seed), &wall);
    NullEventSink sink;
    try {
      engine.advance_to(1e4, sink);
    } catch (const InelasticCollapseError&) {
      ++collapsed;
    }
  }
  return collapsed;
}

}  // namespace

// v'_{2} - v'_1 = -e (v_2 - v_1) with the momentum conserved, at the instant the gap closes.
TEST(HardSphereEngine, BinaryCollisionFollowsTheRestitutionLaw) {
  const ChainParameters p = free_space(2, 0.6);
  HardSphereEngine engine(p, ChainState{0.0, {0.0, 2.0}, {1.0, -1.0}}, nullptr);
  EventRecorder rec;
  engine.advance_to(2.0, rec);
  ASSERT_EQ(rec.events.size(), 2u);
  EXPECT_EQ(rec.events[0].kind, EventKind::ContactBegin);
  EXPECT_EQ(rec.events[1].kind, EventKind::ContactEnd);
  EXPECT_DOUBLE_EQ(rec.events[1].t, 0.5);
  EXPECT_DOUBLE_EQ(rec.events[0].speed, 2.0);
  EXPECT_DOUBLE_EQ(rec.events[1].speed, 1.2);
  EXPECT_DOUBLE_EQ(engine.state().v[0], -0.6);
  EXPECT_DOUBLE_EQ(engine.state().v[1], 0.6);
  EXPECT_DOUBLE_EQ(engine.state().z[1] - engine.state().z[0], 1.0 + 1.2 * 1.5);
  EXPECT_EQ(engine.counters().contact_ends, 1u);
}

// e = 1, gravity and an elastic wall: nothing dissipates, so the energy of ten bouncing spheres
// stays constant over a million collisions, to round-off.
TEST(HardSphereEngine, ElasticChainOnElasticWallConservesEnergy) {
  const ChainParameters p{.N = 10, .g = 1.0, .k = 1e5, .e = 1.0};
  Rng rng(5);
  ChainState s;
  for (int i = 0; i < p.N; ++i) {
    s.z.push_back(0.5 + 1.7 * i + rng.uniform01());
    s.v.push_back(rng.normal());
  }
  Wall wall(1.0);
  HardSphereEngine engine(p, s, &wall);
  const double E0 = engine.mechanical_energy_per_mass();
  NullEventSink sink;
  double worst = 0;
  while (engine.counters().contact_ends + engine.counters().floor_hits < 1000000) {
    engine.advance_to(engine.time() + 100.0, sink);
    worst = std::max(worst, std::abs(engine.mechanical_energy_per_mass() - E0) / E0);
  }
  // Each collision re-bases the two velocities at the absolute time t, which carries a round-off
  // of ~eps t; over n collisions the energy random-walks by ~eps t sqrt(n) (relative, with g, v,
  // E ~ 1 per particle). The bound allows 10 times that.
  const double events = static_cast<double>(engine.counters().contact_ends + engine.counters().floor_hits);
  EXPECT_LT(worst, 10 * 1.1e-16 * engine.time() * std::sqrt(events));
  std::printf("t = %g, events %g, relative energy drift %.3g\n", engine.time(), events, worst);
  EXPECT_GT(engine.counters().floor_hits, 10000u);
}

// Three spheres below e_c(3) = 7 - 4 sqrt 3 collapse: the interval between successive collisions of
// the same pair shrinks by the factor q(e) of Eq. (def_q) (hard spheres: no contact-time shift),
// and the engine stops with a report naming the three particles.
TEST(HardSphereEngine, ThreeBodyCollapseFollowsTheGeometricSequence) {
  for (double e : {0.02, 0.05}) {
    const ChainParameters p = free_space(3, e);
    HardSphereEngine engine(p, free_space_launch_state(p, {}, 3), nullptr);
    EventRecorder rec;
    try {
      engine.advance_to(1e6, rec);
      ADD_FAILURE() << "no collapse at e = " << e;
    } catch (const InelasticCollapseError& err) {
      EXPECT_EQ(err.particle_a(), 1);
      EXPECT_EQ(err.particle_b(), 3);
      EXPECT_GE(err.collisions(), 1000u);
      EXPECT_TRUE(std::isfinite(err.time()));
    }
    std::vector<double> t12;
    for (const Event& ev : rec.events)
      if (ev.kind == EventKind::ContactEnd && ev.i == 0) t12.push_back(ev.t);
    ASSERT_GT(t12.size(), 20u);
    // Ratios of successive intervals: the sequence converges to q, and the absolute time t ~ 1
    // resolves an interval b only to ~1e-16 / b, so the ratios are read while b > 1e-11.
    double last = 0;
    int checked = 0;
    for (std::size_t n = 1; n + 1 < t12.size(); ++n) {
      const double a = t12[n] - t12[n - 1], b = t12[n + 1] - t12[n];
      if (b < 1e-11) break;
      last = b / a;
      ++checked;
    }
    EXPECT_NEAR(last, theory::q_ratio(e), 1e-4 * theory::q_ratio(e)) << "e = " << e;
    EXPECT_GE(checked, 2);
  }
}

// Above e_c(3) three spheres stop colliding: the velocities end sorted (every pair separating).
TEST(HardSphereEngine, ThreeBodiesAboveCriticalRestitutionSeparate) {
  const ChainParameters p = free_space(3, 0.08);
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    HardSphereEngine engine(p, free_space_launch_state(p, {}, seed), nullptr);
    EventRecorder rec;
    ASSERT_TRUE(run_to_separation(engine, rec)) << "seed " << seed;
    EXPECT_TRUE(sorted_velocities(engine.state())) << "seed " << seed;
    EXPECT_LT(rec.count(EventKind::ContactEnd), 1000u);
  }
}

// The TC model (Luding and McNamara) makes a collision within tc of a particle's previous one
// elastic, so the same three spheres that collapse at e = 0.05 now separate, after finitely many
// collisions, with momentum conserved.
TEST(HardSphereEngine, TcModelContinuesPastTheCollapse) {
  const ChainParameters p = free_space(3, 0.05);
  const ChainState s = free_space_launch_state(p, {}, 3);
  HardSphereEngine engine(p, s, nullptr, {.tc = 1e-4});
  EventRecorder rec;
  ASSERT_TRUE(run_to_separation(engine, rec));
  EXPECT_TRUE(sorted_velocities(engine.state()));
  EXPECT_GT(engine.elastic_by_tc(), 0u);
  double p0 = 0, p1 = 0;
  for (int i = 0; i < 3; ++i) {
    p0 += s.v[i];
    p1 += engine.state().v[i];
  }
  EXPECT_NEAR(p1, p0, 1e-12);
}

// A collapse report says what would continue past it: without the TC model, the TC model with
// tc at least the span the engine watches; with a TC time shorter than that span (here below the
// resolution of t, so that no collision inside the span is made elastic), that tc is too short.
TEST(HardSphereEngine, CollapseReportNamesTheTcTimeThatWouldContinue) {
  const ChainParameters p = free_space(3, 0.05);
  const auto report = [&](double tc) -> std::string {
    HardSphereEngine engine(p, free_space_launch_state(p, {}, 3), nullptr, {.tc = tc, .collapse_collisions = 10});
    NullEventSink sink;
    try {
      engine.advance_to(1e6, sink);
    } catch (const InelasticCollapseError& err) {
      return err.what();
    }
    return "no collapse";
  };
  const std::string off = report(0.0);
  EXPECT_NE(off.find("Use the TC model (tc >= 1e-09)"), std::string::npos) << off;
  const std::string too_short = report(1e-300);
  EXPECT_NE(too_short.find("the TC model did not prevent it: tc = 1e-300 is shorter than the span"), std::string::npos) << too_short;
  EXPECT_NE(too_short.find("use tc >= 1e-09"), std::string::npos) << too_short;
}

// Two spheres thrown against a wall collapse for e < 3 - 2 sqrt 2 and never above (the ICW value,
// exact for N = 2, paper Eq. icw; the inelastic wall makes them half of a symmetric four-sphere
// chain, e_c^wall(2) = e_c(4)). Just above e_c the sequence lingers near the vanishing fixed point
// long enough for intervals to reach round-off, so the test keeps 0.01 from it.
TEST(HardSphereEngine, TwoSpheresOnAWallCollapseBelowTheExactCriticalValue) {
  const double ec = 3.0 - 2.0 * std::sqrt(2.0);
  EXPECT_NEAR(theory::ec_wall_icw(2), ec, 1e-12);
  EXPECT_EQ(wall_throw_collapses(2, ec - 0.01, 20), 20);
  EXPECT_EQ(wall_throw_collapses(2, ec + 0.01, 20), 0);
  EXPECT_EQ(wall_throw_collapses(3, 1.0 / 3.0 - 0.01, 20), 20);  // ICW: tan^2(pi/6) = 1/3
  EXPECT_EQ(wall_throw_collapses(3, 1.0 / 3.0 + 0.01, 20), 0);
}

// The soft engine converges to the hard one as k grows. When every contact is binary the soft
// engine's collision law is the hard one exactly (v' = -e v after tau_c), so 25 spheres launched
// in free space (e = 0.9 > e_c(25)) end with the hard-sphere velocities to round-off at any k.
// Where three spheres meet within a time delta, the soft contacts overlap while tau_c > delta and
// the outcome differs; it becomes the hard one once tau_c << delta. Both hold up to k = 1e20.
TEST(HardSphereEngine, SoftExactEngineConvergesToHardSpheres) {
  auto max_diff = [](const ChainState& a, const ChainState& b) {
    double d = 0;
    for (std::size_t i = 0; i < a.v.size(); ++i) d = std::max(d, std::abs(a.v[i] - b.v[i]));
    return d;
  };
  const ChainParameters hard = free_space(25, 0.9);
  const ChainState s = free_space_launch_state(hard, {}, 11);
  HardSphereEngine h(hard, s, nullptr);
  EventRecorder hr;
  ASSERT_TRUE(run_to_separation(h, hr, 200.0));
  for (double k : {1e6, 1e9, 1e12, 1e16, 1e20}) {
    ChainParameters soft = hard;
    soft.k = k;
    ExactEngine x(soft, s, nullptr);
    EventRecorder xr;
    x.advance_to(200.0, xr);
    EXPECT_EQ(xr.count(EventKind::ContactEnd), hr.count(EventKind::ContactEnd)) << "k = " << k;
    EXPECT_LT(max_diff(x.state(), h.state()), 1e-9) << "k = " << k;
  }
  // Particle 2 at rest, hit from below at t = 0.5 and from above at t = 0.5 + 1e-5.
  const ChainParameters three = free_space(3, 0.9);
  const ChainState s3{0.0, {0.0, 1.5, 3.0 + 1e-5}, {1.0, 0.0, -1.0}};
  HardSphereEngine h3(three, s3, nullptr);
  ASSERT_TRUE(run_to_separation(h3, hr, 100.0));
  for (double k : {1e8, 1e10, 1e12, 1e14, 1e17, 1e20}) {
    ChainParameters soft = three;
    soft.k = k;
    ExactEngine x(soft, s3, nullptr);
    NullEventSink sink;
    x.advance_to(100.0, sink);
    const double diff = max_diff(x.state(), h3.state());
    const double tau_c = contact_law(soft).tau_c;
    if (tau_c > 2e-5) EXPECT_GT(diff, 1e-3) << "k = " << k << ": tau_c > delta, a genuine three-body contact";
    if (tau_c < 5e-6) EXPECT_LT(diff, 1e-9) << "k = " << k << ": tau_c < delta, binary contacts";
  }
}

// An observer may stop the engine at an event; the engine's time is then that event's.
TEST(HardSphereEngine, StopsAtTheEventAnObserverAsksFor) {
  class StopAtFirstEnd final : public EventSink {
   public:
    void on_event(const Event& ev) override {
      if (ev.kind == EventKind::ContactEnd) {
        t = ev.t;
        request_stop();
      }
    }
    double t = -1;
  } stop;
  const ChainParameters p = free_space(2, 0.6);
  HardSphereEngine engine(p, ChainState{0.0, {0.0, 2.0}, {1.0, -1.0}}, nullptr);
  engine.advance_to(10.0, stop);
  EXPECT_DOUBLE_EQ(stop.t, 0.5);
  EXPECT_DOUBLE_EQ(engine.time(), 0.5);
  EXPECT_DOUBLE_EQ(engine.state().z[1] - engine.state().z[0], 1.0);
}

TEST(HardSphereEngine, RejectsOverlappingStart) {
  const ChainParameters p = free_space(2, 0.6);
  EXPECT_THROW(HardSphereEngine(p, ChainState{0.0, {0.0, 0.5}, {0.0, 0.0}}, nullptr), UnphysicalStateError);
}
