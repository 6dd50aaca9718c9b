#pragma once
// The event skeleton of the event-driven engines (hard spheres, exact soft spheres), in the manner
// of DynamO's event families. Every event of a chain of N particles belongs to one family, and each
// family has fixed slots in one schedule:
//   - Local: an event inside one body, indexed by the body's lowest particle (the exact engine's
//     clusters: an overlap returns to zero or reaches d, a search resumes). An engine whose bodies
//     are single hard spheres has no local events and no local slots.
//   - Interaction: neighbours i and i+1 (pair i), whose gap closes (a contact begins, or hard
//     spheres collide), or whose gap's search resumes.
//   - Floor: particle 1 reaches the floor, or the floor height's search resumes.
// Each slot holds its predicted time and the engine's own Detail (what kind of event it is). Slots
// are ordered local, interaction, floor, and the earliest time wins with ties going to the lower
// slot (BasicEventQueue): at one instant a body's own event comes before the gaps beside it, and
// the gaps before the floor.
//
// Beside it sit the other two parts every such engine shares: GapLines (each gap a value at its own
// reference time plus a constant rate, since gravity cancels between neighbours) and run_events (the
// event loop, with a guard against events that pile up at one instant).
#include <fmt/format.h>

#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#include "engines/engine.hpp"
#include "engines/event_queue.hpp"
#include "engines/fine_time.hpp"
#include "engines/free_flight.hpp"

namespace granchain {

enum class EventFamily : std::uint8_t { Local, Interaction, Floor };

template <class Time, class Detail>
class ChainSchedule {
 public:
  struct Slot {
    EventFamily family;
    int index;  // the body's lowest particle, the pair, or 0 for the floor
  };

  // N particles; local_events: whether bodies have events of their own (N local slots).
  void reset(int particles, bool local_events) {
    locals_ = local_events ? particles : 0;
    pairs_ = particles > 1 ? particles - 1 : 0;
    details_.assign(static_cast<std::size_t>(locals_ + pairs_ + 1), Detail{});
    queue_.reset(locals_ + pairs_ + 1);
  }

  int local(int lo) const { return lo; }
  int interaction(int i) const { return locals_ + i; }
  int floor() const { return locals_ + pairs_; }
  Slot slot_of(int slot) const {
    if (slot < locals_) return {EventFamily::Local, slot};
    if (slot < locals_ + pairs_) return {EventFamily::Interaction, slot - locals_};
    return {EventFamily::Floor, 0};
  }

  void set(int slot, const Time& t, const Detail& detail = {}) {
    if constexpr (!std::is_empty_v<Detail>) details_[slot] = detail;
    queue_.set(slot, t);
  }
  const Detail& detail(int slot) const { return details_[slot]; }
  const Time& time(int slot) const { return queue_.time(slot); }

  int slots() const { return locals_ + pairs_ + 1; }
  // Every slot's time in slot order: with the details, all a checkpoint needs, since setting them
  // again in slot order after reset() rebuilds the same queue (its order depends on the times alone).
  std::vector<Time> times() const {
    std::vector<Time> t(static_cast<std::size_t>(slots()));
    for (int slot = 0; slot < slots(); ++slot) t[slot] = time(slot);
    return t;
  }

  int next_slot() const { return queue_.next_slot(); }
  Time next_time() const { return queue_.next_time(); }

 private:
  int locals_ = 0, pairs_ = 0;
  std::vector<Detail> details_;
  BasicEventQueue<Time> queue_;
};

// The gap between neighbouring bodies i and i+1 as a line in time: s at the reference time t,
// changing at the rate c, the relative velocity of the two bodies' centres of mass (constant while
// neither changes: gravity cancels). An engine whose bodies deform (the exact engine's clusters)
// adds the change of their edges since t, which it keeps beside these.
template <class Time>
struct GapLines {
  std::vector<Time> t;
  std::vector<double> s, c;

  void reset(int particles, const Time& t0) {
    const std::size_t pairs = particles > 1 ? static_cast<std::size_t>(particles - 1) : 0;
    t.assign(pairs, t0);
    s.assign(pairs, 0.0);
    c.assign(pairs, 0.0);
  }
  double line_at(int i, const Time& now) const { return s[i] + c[i] * (now - t[i]); }
  // Time after t[i] at which the line reaches zero (free_flight::first_root), +inf if never.
  double closing(int i) const { return free_flight::first_root(s[i], c[i], 0.0); }
};

// More events than this at one and the same instant: the engine no longer advances time.
inline constexpr std::uint64_t kMaxSameInstantEvents = 1000000;

// Runs the events of `schedule` due up to t_end in time order, handle(slot, t) for each, until the
// sink asks to stop. Returns the time of the event at which it stopped, or t_end. Throws
// UnphysicalStateError (naming the pair of the last slot) when more than kMaxSameInstantEvents
// events fall on one instant.
template <class Time, class Detail, class Handle>
Time run_events(ChainSchedule<Time, Detail>& schedule, const Time& t_end, EventSink& sink, Handle&& handle) {
  std::uint64_t same_instant = 0;
  Time last = Time(-std::numeric_limits<double>::infinity());
  while (schedule.next_time() <= t_end) {
    const Time t = schedule.next_time();
    const int slot = schedule.next_slot();
    if (t == last) {
      if (++same_instant > kMaxSameInstantEvents) {
        const auto [family, index] = schedule.slot_of(slot);
        const int first = family == EventFamily::Floor ? 1 : index + 1;
        const double at = static_cast<FineTime>(t).value();
        throw UnphysicalStateError(at, first, first + 1,
                                   fmt::format("events pile up at t = {:.17g} without time advancing", at));
      }
    } else {
      same_instant = 0;
      last = t;
    }
    handle(slot, t);
    if (sink.stop_requested()) return t;
  }
  return t_end;
}

}  // namespace granchain
