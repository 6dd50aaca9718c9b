#include "simulation/trajectory.hpp"

#include <cmath>
#include <memory>

#include "engines/engine.hpp"
#include "engines/engine_factory.hpp"
#include "model/driven_column.hpp"
#include "model/floor.hpp"
#include "model/random.hpp"
#include "simulation/collapse_run.hpp"

namespace granchain {

namespace {

class WindowEvents final : public EventSink {
 public:
  explicit WindowEvents(double from) : from_(from) {}
  void on_event(const Event& e) override {
    if (e.t >= from_) events.push_back(e);
  }
  std::vector<Event> events;

 private:
  double from_;
};

}  // namespace

Trajectory record_trajectory(const TraceSpec& spec) {
  ChainParameters p = spec.run.params;
  std::unique_ptr<ThermalFloor> floor;
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
    floor = std::make_unique<ThermalFloor>(p.kT0, p.m, derive_seed(spec.run.seed, static_cast<std::uint64_t>(RandomStream::Floor)));
    initial = driven_column_initial_state(p, spec.run.seed);
  }
  auto engine = make_engine(spec.run.engine, p, initial, floor.get());
  WindowEvents sink(spec.t_from);
  Trajectory tr;
  const auto samples = static_cast<std::int64_t>(std::floor((spec.t_to - spec.t_from) / spec.dt + 1e-9));
  for (std::int64_t s = 0; s <= samples; ++s) {
    const double t = spec.t_from + static_cast<double>(s) * spec.dt;
    engine->advance_to(t, sink);
    tr.t.push_back(t);
    tr.z.push_back(engine->state().z);
  }
  tr.events = std::move(sink.events);
  return tr;
}

}  // namespace granchain
