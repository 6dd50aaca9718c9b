// The event skeleton shared by the event-driven engines (chain_schedule.hpp): slot families, the
// order of simultaneous events, gap lines, and the event loop's stop and pile-up guard.
#include <gtest/gtest.h>

#include <vector>

#include "engines/chain_schedule.hpp"

using namespace granchain;

namespace {
struct Kind {
  int code = 0;
};

class StopAfter final : public EventSink {
 public:
  explicit StopAfter(int n) : left_(n) {}
  void on_event(const Event&) override {}
  void count() {
    if (--left_ <= 0) request_stop();
  }

 private:
  int left_;
};
}  // namespace

TEST(ChainSchedule, FamiliesHaveFixedSlotsAndAnEngineWithoutLocalEventsHasNone) {
  ChainSchedule<double, Kind> with;
  with.reset(5, true);
  EXPECT_EQ(with.local(3), 3);
  EXPECT_EQ(with.interaction(0), 5);
  EXPECT_EQ(with.floor(), 9);
  EXPECT_EQ(with.slot_of(7).family, EventFamily::Interaction);
  EXPECT_EQ(with.slot_of(7).index, 2);
  EXPECT_EQ(with.slot_of(9).family, EventFamily::Floor);
  ChainSchedule<double, Kind> without;
  without.reset(5, false);
  EXPECT_EQ(without.interaction(0), 0);
  EXPECT_EQ(without.floor(), 4);
  EXPECT_EQ(without.slot_of(3).family, EventFamily::Interaction);
}

// At one instant a body's own event comes first, then the gaps (lowest pair first), then the floor,
// whatever order they were set in; a later time loses to an earlier one in every family.
TEST(ChainSchedule, SimultaneousEventsGoLocalThenInteractionThenFloor) {
  ChainSchedule<FineTime, Kind> s;
  s.reset(20, true);
  const FineTime t = FineTime(1e4) + 1e-20;  // below a double's resolution at 1e4
  s.set(s.floor(), t, Kind{3});
  s.set(s.interaction(12), t, Kind{2});
  s.set(s.interaction(4), t, Kind{2});
  s.set(s.local(17), t, Kind{1});
  s.set(s.local(2), FineTime(1e4) + 2e-20, Kind{1});
  std::vector<int> order;
  NullEventSink sink;
  run_events(s, FineTime(2e4), sink, [&](int slot, const FineTime& at) {
    order.push_back(slot);
    EXPECT_EQ(s.detail(slot).code, s.slot_of(slot).family == EventFamily::Local         ? 1
                                   : s.slot_of(slot).family == EventFamily::Interaction ? 2
                                                                                        : 3);
    s.set(slot, FineTime::infinity());
    if (slot != s.local(2)) {
      EXPECT_TRUE(at == t);
    }
  });
  EXPECT_EQ(order, (std::vector<int>{s.local(17), s.interaction(4), s.interaction(12), s.floor(), s.local(2)}));
}

TEST(ChainSchedule, EventLoopStopsWhereTheSinkAsksAndReturnsThatTime) {
  ChainSchedule<double, Kind> s;
  s.reset(4, false);
  for (int i = 0; i < 3; ++i) s.set(s.interaction(i), 1.0 + i);
  StopAfter sink(2);
  int handled = 0;
  const double stopped = run_events(s, 10.0, sink, [&](int slot, double) {
    ++handled;
    sink.count();
    s.set(slot, free_flight::kInf);
  });
  EXPECT_EQ(handled, 2);
  EXPECT_EQ(stopped, 2.0);
  NullEventSink none;
  EXPECT_EQ(run_events(s, 2.5, none, [&](int slot, double) { s.set(slot, free_flight::kInf); }), 2.5);
  EXPECT_EQ(s.next_time(), 3.0);  // not due before 2.5
}

// A prediction that keeps returning the same instant would loop forever; the loop stops it.
TEST(ChainSchedule, EventsThatPileUpAtOneInstantStopTheLoop) {
  ChainSchedule<double, Kind> s;
  s.reset(3, true);
  s.set(s.interaction(1), 0.5);
  NullEventSink sink;
  std::uint64_t handled = 0;
  try {
    run_events(s, 1.0, sink, [&](int, double) { ++handled; });
    FAIL() << "no error";
  } catch (const UnphysicalStateError& e) {
    EXPECT_EQ(e.particle_a(), 2);
    EXPECT_EQ(e.particle_b(), 3);
    EXPECT_EQ(e.time(), 0.5);
  }
  EXPECT_EQ(handled, kMaxSameInstantEvents + 1);
}

// A gap line: s at its reference time plus c (t - t_ref), and the instant it closes.
TEST(GapLines, ValueAndClosingTime) {
  GapLines<FineTime> g;
  g.reset(3, FineTime(0.0));
  EXPECT_EQ(g.s.size(), 2u);
  g.t[1] = FineTime(1e4) + 1e-16;
  g.s[1] = 2e-16;
  g.c[1] = -1.0;
  EXPECT_DOUBLE_EQ(g.line_at(1, FineTime(1e4) + 2e-16), 1e-16);
  EXPECT_DOUBLE_EQ(g.closing(1), 2e-16);
  g.c[1] = 0.5;
  EXPECT_EQ(g.closing(1), free_flight::kInf);
}
