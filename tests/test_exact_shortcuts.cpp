// The exact engine's short paths (exact_binary.cpp: binary contacts of two free particles; the
// gap and floor bounds tried before an edge function is built) are the same floating-point
// operations as the general ones, so a run with them and a run without them report the same
// events and end in the same state, bit for bit. Driven columns from dilute (almost every contact
// binary) to condensed, and free-space collapses where pairs keep turning into clusters.
#include <gtest/gtest.h>

#include <cstring>
#include <fmt/format.h>
#include <string>
#include <vector>

#include "engines/exact/exact_engine.hpp"
#include "model/collapse_setups.hpp"
#include "model/driven_column.hpp"
#include "model/floor.hpp"
#include "test_helpers.hpp"

using namespace granchain;
using test_support::EventRecorder;

namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

struct Outcome {
  std::vector<Event> events;
  ChainState state;
  ExactCounters counters;
  std::uint64_t shortcut_events = 0;
};

Outcome run(const ChainParameters& p, const ChainState& s, bool driven, std::uint64_t seed, double t_end,
            bool shortcuts) {
  ThermalFloor floor(p.kT0, p.m, seed);
  ExactEngine engine(p, s, driven ? &floor : nullptr, ExactOptions{.pair_shortcuts = shortcuts});
  EventRecorder rec;
  engine.advance_to(t_end, rec);
  return {rec.events, engine.state(), engine.work(), engine.shortcut_events()};
}

void expect_identical(const Outcome& a, const Outcome& b, const std::string& what) {
  ASSERT_EQ(a.events.size(), b.events.size()) << what;
  for (std::size_t i = 0; i < a.events.size(); ++i) {
    const Event &x = a.events[i], &y = b.events[i];
    ASSERT_TRUE(x.kind == y.kind && x.i == y.i && same_bits(x.t, y.t) && same_bits(x.t_low, y.t_low) &&
                same_bits(x.speed, y.speed))
        << what << ": event " << i << " differs (t = " << x.t << " vs " << y.t << ")";
  }
  for (std::size_t i = 0; i < a.state.z.size(); ++i) {
    ASSERT_TRUE(same_bits(a.state.z[i], b.state.z[i]) && same_bits(a.state.v[i], b.state.v[i])) << what << ": particle " << i;
  }
  EXPECT_EQ(a.counters.contact_ends, b.counters.contact_ends) << what;
  EXPECT_EQ(a.counters.floor_hits, b.counters.floor_hits) << what;
}

}  // namespace

TEST(ExactShortcuts, DrivenColumnsAreTheSameBitForBit) {
  struct Case {
    int N;
    double e, k, T;
  };
  for (const Case c : {Case{25, 0.95, 1e8, 200}, Case{25, 0.5, 1e8, 20}, Case{10, 0.7, 1e12, 20},
                       Case{40, 0.1, 1e6, 5}, Case{2, 0.9, 1e10, 300}}) {
    const ChainParameters p{.N = c.N, .k = c.k, .e = c.e};
    for (std::uint64_t seed : {1u, 2u}) {
      const ChainState s = driven_column_initial_state(p, seed);
      const Outcome fast = run(p, s, true, seed, c.T, true), plain = run(p, s, true, seed, c.T, false);
      ASSERT_GT(fast.counters.contact_ends, 100u) << "N=" << c.N;
      EXPECT_GT(fast.shortcut_events, fast.counters.contact_ends / 10) << "N=" << c.N;  // the short paths ran
      EXPECT_EQ(plain.shortcut_events, 0u);
      expect_identical(fast, plain, fmt::format("N={} e={} k={} seed={}", c.N, c.e, c.k, seed));
    }
  }
}

TEST(ExactShortcuts, FreeSpaceCollapsesAreTheSameBitForBit) {
  for (double k : {1e8, 1e14}) {
    const ChainParameters p{.N = 25, .g = 0.0, .k = k, .e = 0.3};
    for (std::uint64_t seed : {1u, 7u}) {
      const ChainState s = free_space_launch_state(p, LaunchParameters{}, seed);
      const Outcome fast = run(p, s, false, seed, 40.0, true), plain = run(p, s, false, seed, 40.0, false);
      ASSERT_GT(fast.counters.contact_ends, 100u);
      EXPECT_GT(fast.shortcut_events, 10u);
      expect_identical(fast, plain, fmt::format("free space k={} seed={}", k, seed));
    }
  }
}
