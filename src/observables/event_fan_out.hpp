#pragma once
// One engine, several observers: every event goes to each sink in turn, and a stop that any of
// them requests ends the advance (engines/events.hpp).
#include <initializer_list>
#include <vector>

#include "engines/events.hpp"

namespace granchain {

class EventFanOut final : public EventSink {
 public:
  EventFanOut(std::initializer_list<EventSink*> sinks) : sinks_(sinks) {}
  void on_event(const Event& event) override {
    for (EventSink* s : sinks_) {
      s->on_event(event);
      if (s->stop_requested()) {
        s->clear_stop();
        request_stop();
      }
    }
  }

 private:
  std::vector<EventSink*> sinks_;
};

}  // namespace granchain
