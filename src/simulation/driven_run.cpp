#include "simulation/driven_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <fmt/format.h>

#include "engines/plate_flight.hpp"
#include "model/driven_column.hpp"
#include "model/floor.hpp"
#include "model/state_archive.hpp"
#include "observables/collision_counter.hpp"
#include "observables/contact_durations.hpp"
#include "observables/event_fan_out.hpp"
#include "simulation/cancellation.hpp"

namespace granchain {

namespace {
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}
// The CPU time this thread has used (a run stays on the thread that starts it).
double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}
}  // namespace

bool can_resume(const RunSpec& spec) {
  const EngineInfo& engine = engine_info(spec.engine.kind);
  // A soft start runs the transient on the default engine (EngineChoice{}), then the hard spheres.
  const bool soft_start = engine.hard_spheres && spec.engine.start_k > 0;
  return engine.resumable && (!soft_start || engine_info(EngineChoice{}.kind).resumable);
}

SavedRunPlace saved_run_place(const StateArchive& state) {
  return {saved_value<double>(state, "t"), saved_value<bool>(state, "in_window")};
}

ChainState hard_sphere_start(ChainState s, const ChainParameters& p, const FloorDrive& floor) {
  const PlateMotion* plate = floor.plate();
  const double surface = plate != nullptr ? plate_flight::piece_state(*plate, s.t).z : 0.0;  // as the hard engine reads it
  s.z[0] = std::max(s.z[0], surface + 0.5 * p.d);
  for (std::size_t i = 1; i < s.z.size(); ++i) s.z[i] = std::max(s.z[i], s.z[i - 1] + p.d);
  return s;
}

RunResult run_driven_column(const RunSpec& spec, const ProgressCallback& progress, double progress_every,
                            const RunResumption& resumption) {
  const auto wall0 = Clock::now();
  const double cpu0 = thread_cpu_seconds();
  RunResult r;
  r.spec = spec;
  r.law = contact_law(spec.params);

  const auto floor = column_drive(spec.params, spec.drive, spec.seed);
  const ChainState initial = driven_column_initial_state(spec.params, spec.seed, spec.drive);
  // A soft start (EngineChoice::start_k): the exact engine at start_k runs the transient, then the
  // hard spheres take over. Both draw on the one drive, so the floor's random speeds run on.
  const bool soft_start = engine_info(spec.engine.kind).hard_spheres && spec.engine.start_k > 0;
  std::unique_ptr<Engine> engine;
  if (soft_start) {
    ChainParameters soft = spec.params;
    soft.k = spec.engine.start_k;
    engine = make_engine(EngineChoice{}, soft, initial, floor.get());
  } else {
    engine = make_engine(spec.engine, spec.params, initial, floor.get());
  }
  r.time_step = soft_start ? 0.0 : engine->time_quantum();

  // Samples at t0 + j*dt_s, j = 1..n; dt_s a whole number of engine steps so that a time-stepped
  // engine samples on its own grid.
  double dt_s = spec.sample_interval;
  if (r.time_step > 0) dt_s = std::max(1.0, std::round(dt_s / r.time_step)) * r.time_step;
  const auto n_samples = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::floor(spec.T / dt_s)));
  r.sample_interval = dt_s;

  const int bins = power_of_two_bins(n_samples, spec.bins);
  const double t0 = spec.transient;
  const double t1 = spec.transient + spec.T;
  CollisionCounter counter(t0, t1, bins);
  ProfileSampler sampler(spec.params.N, spec.params.m, n_samples, bins);
  // Contact durations (soft spheres: a hard collision lasts no time). They watch the transient too,
  // so that a contact begun before the window and ended in it counts whole.
  const bool soft_contacts = !engine_info(spec.engine.kind).hard_spheres;
  ContactDurations contacts(soft_contacts ? spec.params.N : 0, r.law.tau_c, t0, t1);
  EventFanOut window(soft_contacts ? EventFanOut{&counter, &contacts} : EventFanOut{&counter});

  EngineCounters before_switch{};  // the soft engine's counts, for a soft start's totals
  bool hard_running = false;        // a soft start's hard spheres have taken over
  // Sample j's time (j = 0: the window's start); the last ends exactly at t1.
  const auto sample_time = [&](std::int64_t j) { return j > 0 ? std::min(t1, t0 + static_cast<double>(j) * dt_s) : t0; };

  // Where the run stands: the transient done up to t_reached, then the window's samples 1 .. j_done.
  double t_reached = 0.0;
  std::int64_t j_done = 0;
  bool in_window = false;
  double wall_before = 0.0, cpu_before = 0.0;  // spent in the sittings before a resumption
  const bool saving = static_cast<bool>(resumption.save);
  if ((saving || resumption.resume_from != nullptr) && !can_resume(spec)) {
    throw std::logic_error("run_driven_column: a run of this engine cannot be saved or resumed (EngineInfo::resumable)");
  }
  if (resumption.resume_from != nullptr) {
    const StateArchive& a = *resumption.resume_from;
    const SavedRunPlace place = saved_run_place(a);
    in_window = place.in_window;
    t_reached = in_window ? t0 : place.t;
    j_done = saved_value<std::int64_t>(a, "samples_done");
    if (saved_value<std::int64_t>(a, "samples") != n_samples || saved_value<int>(a, "bins") != bins ||
        !(place.t >= 0.0 && place.t <= (in_window ? t1 : t0)) || j_done < 0 || j_done > n_samples || (j_done > 0 && !in_window)) {
      throw StateArchiveError("saved state: its place in the run does not fit this run's transient, window and samples");
    }
    wall_before = saved_value<double>(a, "wall_seconds");
    cpu_before = saved_value<double>(a, "cpu_seconds");
    for (const char* part : {"engine", "floor", "counter", "sampler", "contacts"})
      if (!a.contains(part)) throw StateArchiveError(fmt::format("saved state: no part '{}'", part));
    if (soft_start) {  // saved in the window: the hard spheres had taken over, with the soft engine's counts
      const std::vector<std::uint64_t> counts = unpack_array<std::uint64_t>(a, "before_switch", 3);
      before_switch = {counts[0], counts[1], counts[2]};
      if (in_window) {
        engine = make_engine(spec.engine, spec.params, hard_sphere_start(initial, spec.params, *floor), floor.get());
        hard_running = true;
      }
    }
    engine->restore(a.at("engine"));
    floor->restore(a.at("floor"));
    counter.restore(a.at("counter"));
    sampler.restore(a.at("sampler"));
    contacts.restore(a.at("contacts"));
    if (engine->time() != (in_window ? sample_time(j_done) : t_reached)) {
      throw StateArchiveError("saved state: the engine's time is not the run's place");
    }
  }
  auto last_save = wall0;
  auto save_state = [&] {
    StateArchive a = StateArchive::object();
    a["t"] = in_window ? engine->time() : t_reached;
    a["in_window"] = in_window;
    a["samples_done"] = j_done;
    a["samples"] = n_samples;
    a["bins"] = bins;
    a["wall_seconds"] = wall_before + seconds_since(wall0);
    a["cpu_seconds"] = cpu_before + (thread_cpu_seconds() - cpu0);
    if (soft_start) a["before_switch"] = pack_array(std::vector<std::uint64_t>{before_switch.steps, before_switch.contact_ends,
                                                                                before_switch.floor_hits});
    engine->save(a["engine"]);
    floor->save(a["floor"]);
    counter.save(a["counter"]);
    sampler.save(a["sampler"]);
    contacts.save(a["contacts"]);
    resumption.save(a);
    last_save = Clock::now();
  };
  auto save_if_due = [&] {
    if (saving && seconds_since(last_save) >= resumption.every) save_state();
  };

  RunProgress prog;
  prog.t_total = t1;
  auto last_report = wall0;
  auto report = [&](double t, bool transient) {
    if (!progress) return;
    const auto now = Clock::now();
    if (std::chrono::duration<double>(now - last_report).count() < progress_every) return;
    last_report = now;
    const EngineCounters c = engine->counters();
    prog.t = t;
    prog.in_transient = transient;
    prog.steps = c.steps + before_switch.steps;
    prog.events = c.contact_ends + c.floor_hits + before_switch.contact_ends + before_switch.floor_hits;
    prog.wall_seconds = wall_before + seconds_since(wall0);
    progress(prog);
  };

  // Transient, in chunks so that progress can be reported.
  NullEventSink discard;
  EventSink& transient_sink = soft_contacts ? static_cast<EventSink&>(contacts) : discard;
  const double chunk = std::max(dt_s, 1.0);
  try {
    for (double t = t_reached; t < t0;) {
      t = std::min(t0, t + chunk);
      engine->advance_to(t, transient_sink);
      t_reached = t;
      report(t, true);
      save_if_due();
    }
    if (soft_start && !hard_running) {
      before_switch = engine->counters();
      engine = make_engine(spec.engine, spec.params, hard_sphere_start(engine->state(), spec.params, *floor), floor.get());
      hard_running = true;
    }
    in_window = true;
    for (std::int64_t j = j_done + 1; j <= n_samples; ++j) {
      const double t = sample_time(j);
      engine->advance_to(t, window);
      sampler.sample(engine->state());
      j_done = j;
      report(t, false);  // a clock read per sample when progress is watched: a cancel is seen within a sample
      save_if_due();
    }
  } catch (const RunCancelled&) {
    if (saving) save_state();  // at the last chunk or sample done: the state between two of them
    throw;
  }
  engine->advance_to(t1, window);  // the window ends at exactly t0 + T

  r.samples = sampler.samples();
  r.n_coll = counter.collision_rate_per_particle(spec.params.N);
  r.floor_rate = counter.floor_hit_rate();
  r.pp_rate = counter.particle_collision_rate();
  r.particle_collisions = counter.particle_collisions();
  r.floor_hits = counter.floor_hits();
  r.profiles = sampler.profiles();
  if (soft_contacts) r.contacts = contacts.pairs();
  r.n_coll_halves = counter.collision_rate_stationarity(spec.params.N);
  r.height_halves = sampler.height_stationarity();
  r.n_coll_blocking = counter.collision_rate_blocking(spec.params.N);
  r.height_blocking = sampler.height_blocking();
  const EngineCounters c = engine->counters();
  r.steps = c.steps + before_switch.steps;
  r.events = c.contact_ends + c.floor_hits + before_switch.contact_ends + before_switch.floor_hits;
  r.wall_seconds = wall_before + seconds_since(wall0);
  r.cpu_seconds = cpu_before + (thread_cpu_seconds() - cpu0);
  // The audit evaluated every overlap, gap and the floor height at random instants between
  // events: a value of the wrong sign means an event was missed, and the run is not a result.
  const AuditCounters audit = engine->audit();
  if (audit.violations > 0) {
    throw UnphysicalStateError(t1, 0, 0,
                               fmt::format("the audit found {} of {} overlaps, gaps or floor heights of the wrong sign "
                                           "between events (an event was missed)",
                                           audit.violations, audit.values));
  }
  r.audit_instants = audit.instants;
  r.audit_values = audit.values;
  return r;
}

}  // namespace granchain
