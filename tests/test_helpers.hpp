#pragma once
// Small helpers shared by the tests.
#include <cmath>
#include <vector>

#include "engines/events.hpp"

namespace granchain::test_support {

// Records every event an engine reports.
class EventRecorder final : public EventSink {
 public:
  void on_event(const Event& e) override { events.push_back(e); }
  std::size_t count(EventKind k) const {
    std::size_t n = 0;
    for (const auto& e : events) n += e.kind == k;
    return n;
  }
  std::vector<Event> events;
};

// Number of standard errors between a measurement and an exact value.
inline double z_score(double measured, double error, double exact) { return std::abs(measured - exact) / error; }

}  // namespace granchain::test_support
