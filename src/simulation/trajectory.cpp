#include "simulation/trajectory.hpp"

#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "engines/engine.hpp"
#include "engines/engine_registry.hpp"
#include "model/driven_column.hpp"
#include "model/floor.hpp"
#include "model/random.hpp"
#include "simulation/collapse_run.hpp"

namespace granchain {

namespace {

class WindowEvents final : public EventSink {
 public:
  WindowEvents(double from, const CancelFlag* cancel) : from_(from), cancel_(cancel) {}
  void on_event(const Event& e) override {
    if (e.t >= from_) events.push_back(e);
    if (cancel_requested(cancel_)) request_stop();
  }
  std::vector<Event> events;

 private:
  double from_;
  const CancelFlag* cancel_;
};

}  // namespace

Trajectory record_trajectory(const TraceSpec& spec, const CancelFlag* cancel) {
  ChainParameters p = spec.run.params;
  std::unique_ptr<FloorDrive> floor;
  ChainState initial;
  if (spec.free_space) {
    p.g = 0.0;
    CollapseSpec c;
    c.params = p;
    c.launch = spec.launch;
    c.seed = spec.run.seed;
    initial = collapse_initial_state(c, spec.realization);
  } else {
    // As run_driven_column: the same streams from the same seed.
    floor = column_drive(p, spec.run.drive, spec.run.seed);
    initial = driven_column_initial_state(p, spec.run.seed, spec.run.drive);
  }
  auto engine = make_engine(spec.run.engine, p, initial, floor.get());
  const PlateMotion* plate = floor ? floor->plate() : nullptr;
  WindowEvents sink(spec.t_from, cancel);
  Trajectory tr;
  const auto samples = static_cast<std::int64_t>(std::floor((spec.t_to - spec.t_from) / spec.dt + 1e-9));
  for (std::int64_t s = 0; s <= samples; ++s) {
    const double t = spec.t_from + static_cast<double>(s) * spec.dt;
    engine->advance_to(t, sink);
    if (cancel_requested(cancel)) {  // the samples so far are whole; the events up to the last of them kept
      tr.interrupted = true;
      const double last = tr.t.empty() ? -1.0 : tr.t.back();
      std::erase_if(sink.events, [last](const Event& e) { return e.t > last; });
      break;
    }
    tr.t.push_back(t);
    tr.z.push_back(engine->state().z);
    tr.v.push_back(engine->state().v);
    if (plate) {
      tr.plate.push_back(plate->z(t));
      tr.plate_v.push_back(plate->v(t));
      tr.plate_phase.push_back(std::fmod(plate->omega() * t + plate->phase(), 2 * std::numbers::pi));
    }
  }
  tr.events = std::move(sink.events);
  return tr;
}

std::string samples_csv(const Trajectory& tr) {
  std::string csv = "t";
  const std::size_t N = tr.z.empty() ? 0 : tr.z.front().size();
  for (std::size_t i = 1; i <= N; ++i) csv += fmt::format(",z{}", i);
  const bool plate = !tr.plate.empty();
  csv += plate ? ",z_plate\n" : "\n";
  for (std::size_t s = 0; s < tr.t.size(); ++s) {
    csv += fmt::format("{:.17g}", tr.t[s]);
    for (double z : tr.z[s]) csv += fmt::format(",{:.17g}", z);
    if (plate) csv += fmt::format(",{:.17g}", tr.plate[s]);
    csv += "\n";
  }
  return csv;
}

std::string events_csv(const Trajectory& tr) {
  std::string ev = "t,kind,i,j,speed\n";
  for (const Event& e : tr.events) {
    const bool floor = e.kind == EventKind::FloorHit || e.kind == EventKind::FloorContact;
    ev += fmt::format("{:.17g},{},{},{},{:.17g}\n", e.t, event_kind_name(e.kind), floor ? 0 : e.i + 1, floor ? 1 : e.i + 2, e.speed);
  }
  return ev;
}

}  // namespace granchain
