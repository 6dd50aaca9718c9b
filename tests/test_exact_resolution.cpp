// The exact engine's resolution: a FineTime clock and relative velocities as primary variables.
// Above k = 1e12, where the reference engine cannot go, the engine is tested against what is
// known exactly: the binary law at k = 1e20 late in a long run, Galilean invariance of free space
// to the last bit, and the three-body collapse, whose count grows by a fixed number of collisions
// per decade of k (Sec. III.D, docs/collapse.md).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "engines/exact/exact_engine.hpp"
#include "engines/fine_time.hpp"
#include "model/collapse_setups.hpp"
#include "model/chain_parameters.hpp"
#include "test_helpers.hpp"

using namespace granchain;
using test_support::EventRecorder;

namespace {

FineTime event_time(const Event& e) { return FineTime::from_parts(e.t, e.t_low); }

std::vector<Event> run_events(const ChainParameters& p, const ChainState& s, double t_end) {
  ExactEngine engine(p, s, nullptr);
  EventRecorder rec;
  engine.advance_to(t_end, rec);
  return rec.events;
}

}  // namespace

// The clock adds 2^-53 ulp(t): 1e4 + 1e-20 and 1e4 are different times, and their difference is
// the 1e-20 that was added, to round-off of the difference.
TEST(FineTime, ResolvesIntervalsFarBelowTheUlpOfTheTime) {
  const FineTime t(1e4);
  for (double s : {1e-20, 3.3e-25, 0.1, 1e-12}) {
    const FineTime u = t + s;
    EXPECT_TRUE(t < u);
    EXPECT_NEAR(u - t, s, 1e-15 * s) << s;
  }
  FineTime acc(1e4);
  for (int i = 0; i < 1000; ++i) acc += 1e-18;  // a thousand steps far below ulp(1e4) = 1.8e-12
  EXPECT_NEAR(acc - FineTime(1e4), 1e-15, 1e-27);
  EXPECT_EQ((FineTime(2.0) + 1e-30) - (FineTime(1.0) + 1e-30), 1.0);
}

// A binary contact begun at t0 + 1/8 lasts exactly tau_c (Eq. tauc) and returns the relative
// velocity times -e (Eq. Dd), at k up to 1e20 and at t0 = 1e4, where ulp(t) = 1.8e-12 is ten
// times tau_c at k = 1e20: a double clock could not time the contact at all.
TEST(ExactResolution, BinaryLawHoldsAtK1e20LateInARun) {
  for (double t0 : {0.0, 1e4}) {
    for (double k : {1e12, 1e16, 1e20}) {
      for (double e : {0.02, 0.5, 0.9, 1.0}) {
        for (double g : {0.0, 1.0}) {
          ChainParameters p{.N = 2, .g = g, .k = k, .e = e};
          const std::vector<Event> ev = run_events(p, ChainState{t0, {0.0, 1.25}, {1.0, -1.0}}, t0 + 0.5);
          ASSERT_EQ(ev.size(), 2u) << "k=" << k << " e=" << e << " t0=" << t0;
          ASSERT_EQ(ev[0].kind, EventKind::ContactBegin);
          ASSERT_EQ(ev[1].kind, EventKind::ContactEnd);
          const double tau_c = contact_law(p).tau_c;
          EXPECT_NEAR(event_time(ev[0]) - FineTime(t0), 0.125, 1e-16) << "k=" << k << " t0=" << t0;
          EXPECT_NEAR(event_time(ev[1]) - event_time(ev[0]), tau_c, 1e-12 * tau_c) << "k=" << k << " e=" << e << " t0=" << t0;
          EXPECT_NEAR(ev[1].speed / ev[0].speed, e, 1e-12) << "k=" << k << " e=" << e << " t0=" << t0;
        }
      }
    }
  }
}

// Free space has no preferred frame: boosting every velocity by V changes no gap, overlap or
// relative velocity. The engine works in relative quantities only (absolute velocities enter the
// reported state and the floor), so a launch boosted by V = 2^26 gives the same events as the
// launch itself, bit for bit: times, pairs and speeds. (V is a power of two and the unboosted
// velocities are first rounded to V's grid, so both launches start from exactly the same relative
// state.) An engine that differenced absolute velocities would lose 26 bits of every relative
// speed here: relative speeds of 1e-10 of the particles' (the three-body collapse at k = 1e20)
// would be 1e-18 of the boosted speeds, below double precision.
TEST(ExactResolution, FreeSpaceIsGalileanInvariantToTheLastBit) {
  const double V = 0x1p26;
  struct Case {
    ChainParameters p;
    std::uint64_t seed;
    double t_end;
  };
  const std::vector<Case> cases{{{.N = 25, .g = 0.0, .k = 1e8, .e = 0.3}, 3, 40.0},
                                {{.N = 10, .g = 0.0, .k = 1e16, .e = 0.5}, 5, 40.0},
                                {{.N = 3, .g = 0.0, .k = 1e20, .e = 0.05}, 7, 40.0}};
  for (const Case& c : cases) {
    ChainState s = free_space_launch_state(c.p, LaunchParameters{}, c.seed);
    ChainState boosted = s;
    for (std::size_t i = 0; i < s.v.size(); ++i) {
      s.v[i] = (s.v[i] + V) - V;  // exact: both sums land on V's grid of 2^-26
      boosted.v[i] = s.v[i] + V;
    }
    const std::vector<Event> a = run_events(c.p, s, c.t_end);
    const std::vector<Event> b = run_events(c.p, boosted, c.t_end);
    ASSERT_GT(a.size(), 20u) << "N=" << c.p.N;
    ASSERT_EQ(a.size(), b.size()) << "N=" << c.p.N << " k=" << c.p.k;
    for (std::size_t q = 0; q < a.size(); ++q) {
      ASSERT_EQ(a[q].kind, b[q].kind) << "event " << q;
      ASSERT_EQ(a[q].i, b[q].i) << "event " << q;
      ASSERT_EQ(a[q].t, b[q].t) << "event " << q;
      ASSERT_EQ(a[q].t_low, b[q].t_low) << "event " << q;
      ASSERT_EQ(a[q].speed, b[q].speed) << "event " << q;
    }
  }
}

// e < e_c(3) = 7 - 4 sqrt 3: the soft three-body collapse alternates 1-2 and 2-3 collisions whose
// intervals shrink by q per pair (Eq. ntot-log) until they reach tau_c ~ k^-1/2, so each decade of
// k adds -ln 10 / (2 ln q) pairs: the count of one launch grows by the same number per decade,
// within the +-1 of integer counts, from k = 1e6 up to k = 1e20.
TEST(ExactResolution, ThreeBodyCollapseGainsAFixedCountPerDecadeUpTo1e20) {
  const double e = 0.05;
  auto count = [&](double k) {
    const ChainParameters p{.N = 3, .g = 0.0, .k = k, .e = e};
    const std::vector<Event> ev = run_events(p, {0.0, {0.0, 1.1, 2.25}, {1.0, 0.0, -0.9}}, 10.0);
    int n = 0;
    for (const Event& x : ev) n += x.kind == EventKind::ContactEnd;
    return n;
  };
  std::vector<int> counts;
  for (int decade = 6; decade <= 20; decade += 2) counts.push_back(count(std::pow(10.0, decade)));
  std::vector<int> steps;
  for (std::size_t i = 1; i < counts.size(); ++i) steps.push_back(counts[i] - counts[i - 1]);
  const double mean = static_cast<double>(counts.back() - counts.front()) / steps.size();
  for (std::size_t i = 0; i < steps.size(); ++i) {
    EXPECT_GE(steps[i], 1) << "1e" << 6 + 2 * i << " -> 1e" << 8 + 2 * i;
    EXPECT_LE(std::abs(steps[i] - mean), 1.5) << "1e" << 6 + 2 * i << " -> 1e" << 8 + 2 * i << ": " << steps[i]
                                              << " collisions, mean " << mean;
  }
}
