#pragma once
// What engines report while time advances. Observers count these, so a collision means the same
// thing whichever engine ran (paper Sec. III.A: a particle-particle collision is counted when two
// touching particles separate; each floor hit counts one).
#include <cstdint>

namespace granchain {

enum class EventKind : std::uint8_t {
  ContactBegin,  // the overlap of pair (i, i+1) becomes positive
  ContactEnd,    // the overlap of pair (i, i+1) returns to zero: one counted collision
  FloorHit,      // particle 1 (i = 0) leaves the floor: a thermal floor's hit, the end of a plate contact
  FloorContact,  // particle 1 begins to touch a vibrating plate (its FloorHit comes when it leaves)
};

// "contact_begin", "contact_end", "floor_hit", "floor_contact": as traces write them.
constexpr const char* event_kind_name(EventKind kind) {
  switch (kind) {
    case EventKind::ContactBegin: return "contact_begin";
    case EventKind::ContactEnd: return "contact_end";
    case EventKind::FloorHit: return "floor_hit";
    case EventKind::FloorContact: return "floor_contact";
  }
  return "";
}

struct Event {
  EventKind kind;
  double t;      // time of the event
  int i;         // lower particle of the pair (0-based); 0 for a floor hit
  double speed;  // |v_i - v_{i+1}| for contacts; outgoing speed (relative to a plate) for floor events
  // Engines with a FineTime clock (fine_time.hpp): the time to 106 bits is t + t_low (t is that
  // sum rounded to a double); 0 for the others.
  double t_low = 0.0;
};

class EventSink {
 public:
  virtual ~EventSink() = default;
  virtual void on_event(const Event& event) = 0;

  // An observer may end an advance at the event it was just handed (a stop rule, a window): the
  // engine then returns from advance_to with time() at that event (a time-stepped engine: at the
  // end of the step in which it happened, after reporting that step's other events).
  bool stop_requested() const { return stop_; }
  void clear_stop() { stop_ = false; }

 protected:
  void request_stop() { stop_ = true; }

 private:
  bool stop_ = false;
};

// Discards every event.
class NullEventSink final : public EventSink {
 public:
  void on_event(const Event&) override {}
};

}  // namespace granchain
