// The Engine contract (src/engines/engine.hpp, events.hpp), run by every engine that make_engine
// knows: the same suite for each, so an engine added to the registry (engines()) is held to it at once.
//   - advance_to(t) ends at exactly t and reports every event on the way, in time order, inside
//     the interval it advanced over; an earlier t is refused;
//   - events are well formed (kind, pair in range, floor hits on particle 1, finite speeds >= 0),
//     contact begins and ends alternate per pair, and the counters count what was reported;
//   - the state is finite, ordered (no particle passes its neighbour) and above the floor;
//   - a stop requested by an observer ends the advance at that event (a time-stepped engine: at
//     the end of its step);
//   - the same initial state and floor seed give the same events bit for bit;
//   - in free space without gravity momentum is conserved.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "engines/engine_registry.hpp"
#include "model/collapse_setups.hpp"
#include "model/driven_column.hpp"
#include "model/floor.hpp"
#include "test_helpers.hpp"

using namespace granchain;
using test_support::EventRecorder;

namespace {

// A driven column every engine handles: soft contacts at k = 1e4 (the reference engines step
// tau_c / 100), e = 0.9 keeps the hard engine clear of inelastic collapse.
ChainParameters column() { return ChainParameters{.N = 6, .k = 1e4, .e = 0.9}; }

std::unique_ptr<Engine> engine_for(const std::string& name, const ChainParameters& p, const ChainState& s,
                                   FloorDrive* floor) {
  EngineChoice choice;
  choice.kind = find_engine(name)->kind;
  return make_engine(choice, p, s, floor);
}

std::vector<std::string> registered_names() {
  std::vector<std::string> names;
  for (const EngineInfo& e : engines()) names.push_back(e.name);
  return names;
}

class EngineContract : public ::testing::TestWithParam<std::string> {};

// Stops the advance at its n-th event.
class StopAtEvent final : public EventSink {
 public:
  explicit StopAtEvent(std::size_t n) : n_(n) {}
  void on_event(const Event& e) override {
    events.push_back(e);
    if (events.size() == n_) request_stop();
  }
  std::vector<Event> events;

 private:
  std::size_t n_;
};

}  // namespace

TEST_P(EngineContract, AdvancesToExactTimesAndReportsOrderedWellFormedEvents) {
  const ChainParameters p = column();
  ThermalFloor floor(p.kT0, p.m, 3);
  auto engine = engine_for(GetParam(), p, driven_column_initial_state(p, 3), &floor);
  EventRecorder rec;
  double from = engine->time();
  std::map<int, EventKind> last_of_pair;
  for (double t : {0.123456789, 1.0, 3.3333333, 20.0}) {
    const std::size_t before = rec.events.size();
    engine->advance_to(t, rec);
    EXPECT_EQ(engine->time(), t);
    EXPECT_EQ(engine->state().t, t);
    for (std::size_t q = before; q < rec.events.size(); ++q) {
      const Event& e = rec.events[q];
      EXPECT_GE(e.t, from) << "event " << q;
      EXPECT_LE(e.t, t) << "event " << q;
      if (q > 0) EXPECT_LE(rec.events[q - 1].t, e.t) << "event " << q;
      EXPECT_TRUE(std::isfinite(e.speed) && e.speed >= 0) << "event " << q << " speed " << e.speed;
      if (e.kind == EventKind::FloorHit) {
        EXPECT_EQ(e.i, 0);
      } else {
        ASSERT_TRUE(e.i >= 0 && e.i + 1 < p.N) << "event " << q << " pair " << e.i;
        const auto it = last_of_pair.find(e.i);
        const EventKind previous = it == last_of_pair.end() ? EventKind::ContactEnd : it->second;
        EXPECT_NE(previous, e.kind) << "pair " << e.i << ": begins and ends must alternate (event " << q << ")";
        last_of_pair[e.i] = e.kind;
      }
    }
    from = t;
  }
  ASSERT_GT(rec.count(EventKind::ContactEnd), 20u);
  ASSERT_GT(rec.count(EventKind::FloorHit), 5u);
  const EngineCounters c = engine->counters();
  EXPECT_EQ(c.contact_ends, rec.count(EventKind::ContactEnd));
  EXPECT_EQ(c.floor_hits, rec.count(EventKind::FloorHit));
  EXPECT_THROW(engine->advance_to(1.0, rec), std::logic_error);
}

TEST_P(EngineContract, StateIsFiniteOrderedAndAboveTheFloor) {
  const ChainParameters p = column();
  ThermalFloor floor(p.kT0, p.m, 5);
  auto engine = engine_for(GetParam(), p, driven_column_initial_state(p, 5), &floor);
  NullEventSink sink;
  for (int step = 1; step <= 200; ++step) {
    engine->advance_to(0.1 * step, sink);
    const ChainState& s = engine->state();
    ASSERT_EQ(static_cast<int>(s.z.size()), p.N);
    ASSERT_EQ(static_cast<int>(s.v.size()), p.N);
    // Soft contacts overlap by far less than d at k = 1e4 and these speeds; the floor is soft for
    // the time-stepped engines only within their step.
    EXPECT_GT(s.z[0], 0.5 * p.d - 1e-2) << "t = " << s.t;
    for (int i = 0; i < p.N; ++i) {
      ASSERT_TRUE(std::isfinite(s.z[i]) && std::isfinite(s.v[i])) << "particle " << i + 1;
      if (i + 1 < p.N) EXPECT_GT(s.z[i + 1] - s.z[i], 0.5 * p.d) << "particles " << i + 1 << ", " << i + 2;
    }
  }
}

TEST_P(EngineContract, AnObserverCanStopTheAdvanceAtAnEvent) {
  const ChainParameters p = column();
  ThermalFloor floor(p.kT0, p.m, 7);
  auto engine = engine_for(GetParam(), p, driven_column_initial_state(p, 7), &floor);
  StopAtEvent sink(25);
  engine->advance_to(100.0, sink);
  ASSERT_GE(sink.events.size(), 25u);
  const double at = sink.events[24].t;
  EXPECT_LT(engine->time(), 100.0);
  EXPECT_GE(engine->time(), at);
  EXPECT_LE(engine->time() - at, engine->time_quantum());  // the event's own step at most
  for (const Event& e : sink.events) EXPECT_LE(e.t, engine->time());
  // The advance goes on from there when asked again.
  sink.clear_stop();
  StopAtEvent rest(1000000);
  engine->advance_to(100.0, rest);
  EXPECT_EQ(engine->time(), 100.0);
  ASSERT_FALSE(rest.events.empty());
  EXPECT_GE(rest.events.front().t, at);
}

TEST_P(EngineContract, TheSameStartGivesTheSameEventsBitForBit) {
  const ChainParameters p = column();
  auto run = [&]() {
    ThermalFloor floor(p.kT0, p.m, 11);
    auto engine = engine_for(GetParam(), p, driven_column_initial_state(p, 11), &floor);
    EventRecorder rec;
    engine->advance_to(30.0, rec);
    return rec.events;
  };
  const std::vector<Event> a = run(), b = run();
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GT(a.size(), 50u);
  for (std::size_t q = 0; q < a.size(); ++q) {
    ASSERT_EQ(a[q].kind, b[q].kind) << q;
    ASSERT_EQ(a[q].i, b[q].i) << q;
    ASSERT_EQ(a[q].t, b[q].t) << q;
    ASSERT_EQ(a[q].t_low, b[q].t_low) << q;
    ASSERT_EQ(a[q].speed, b[q].speed) << q;
  }
}

// No floor, no gravity: contacts act in equal and opposite pairs, so the total momentum stays at
// its initial value to round-off of the velocities (1e-12 here, N = 10, e = 0.8 above e_c(10)
// of the hard engine's collapse).
TEST_P(EngineContract, FreeSpaceConservesMomentum) {
  const ChainParameters p{.N = 10, .g = 0.0, .k = 1e4, .e = 0.8};
  const ChainState s = free_space_launch_state(p, LaunchParameters{}, 2);
  auto engine = engine_for(GetParam(), p, s, nullptr);
  double p0 = 0;
  for (double v : s.v) p0 += v;
  EventRecorder rec;
  engine->advance_to(15.0, rec);
  double p1 = 0;
  for (double v : engine->state().v) p1 += v;
  EXPECT_GT(rec.count(EventKind::ContactEnd), 10u);
  EXPECT_NEAR(p1, p0, 1e-12 * p.N);
}

INSTANTIATE_TEST_SUITE_P(EveryEngine, EngineContract, ::testing::ValuesIn(registered_names()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string name;
                           for (char ch : info.param) name += ch == '-' ? '_' : ch;
                           return name;
                         });
