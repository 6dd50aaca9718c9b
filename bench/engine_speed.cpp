// Exact event-driven engine against the reference Runge-Kutta engine on the same work, in one
// invocation. The N = 25 workloads are the driven column of the paper (thermal floor) run through
// run_driven_column, the code path of `granchain run`, so both engines do the same sampling and
// observation; the settled columns (N = 150 at e = 0.1, N = 40 and 100 at k = 1e10) time the
// engines alone.
// The ratio is reference wall time / exact wall time.
//
//   build/bench/engine_speed            # full: the k = 1e8 reference runs take ~10 s each
//   build/bench/engine_speed --quick    # every N = 25 reference time extrapolated from a short run
//   build/bench/engine_speed --skip-large  # without the settled columns (about 4 minutes)
//   build/bench/engine_speed --free-space  # also free-space collapses at N = 25 (up to 20 minutes)
//   build/bench/engine_speed --observers   # only the observers' share of a run (collision counter, contact durations)
//   build/bench/engine_speed --plates      # also N = 10 columns on each vibrating plate against the reference,
//                                          # and a condensed N = 40 column at k = 1e10 on each drive (about 1 minute)
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fmt/format.h>
#include <numbers>
#include <string>
#include <vector>

#include "bench_cli.hpp"
#include "engines/engine_registry.hpp"
#include "engines/exact/exact_engine.hpp"
#include "model/chain_parameters.hpp"
#include "model/driven_column.hpp"
#include "model/floor.hpp"
#include "simulation/collapse_run.hpp"
#include "observables/collision_counter.hpp"
#include "observables/contact_durations.hpp"
#include "observables/event_fan_out.hpp"
#include "simulation/driven_run.hpp"

using namespace granchain;

namespace {

struct Workload {
  double k, e, T;
};

struct Timing {
  double wall = 0;        // seconds for the whole run (transient + window)
  double simulated = 0;   // simulated time covered
  std::uint64_t events = 0, steps = 0;
  double n_coll = 0, n_coll_err = 0;
  double wall_time() const { return wall; }
};

// One run through run_driven_column, the code path of `granchain run`, timed.
Timing time_spec(const RunSpec& spec) {
  const auto t0 = std::chrono::steady_clock::now();
  const RunResult r = run_driven_column(spec, {}, 1.0);
  Timing out;
  out.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out.simulated = spec.T + spec.transient;
  out.events = r.events;
  out.steps = r.steps;
  out.n_coll = r.n_coll.value;
  out.n_coll_err = r.n_coll.error;
  return out;
}

Timing time_run(const Workload& w, EngineKind engine, double T, std::uint64_t seed) {
  RunSpec spec;
  spec.params = ChainParameters{.N = 25, .k = w.k, .e = w.e};
  spec.engine.kind = engine;
  spec.T = T;
  spec.transient = 0.1 * T;
  spec.seed = seed;
  return time_spec(spec);
}

// The engine alone (no sampling, no observers): wall time and root-search steps per reported
// collision event, and its counters (the same in every repeat: the run is deterministic).
struct EngineOnly {
  double ns = 0, search_steps = 0;
  ExactCounters counters;
  double collisions = 0;
  double wall_time() const { return ns; }
};
EngineOnly engine_only_per_collision(const Workload& w, std::uint64_t seed) {
  const ChainParameters p{.N = 25, .k = w.k, .e = w.e};
  ThermalFloor floor(p.kT0, p.m, seed);
  ExactEngine engine(p, driven_column_initial_state(p, seed), &floor);
  NullEventSink none;
  const auto t0 = std::chrono::steady_clock::now();
  engine.advance_to(1.1 * w.T, none);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const ExactCounters c = engine.work();
  const double collisions = static_cast<double>(c.contact_ends + c.floor_hits);
  return {1e9 * wall / collisions, static_cast<double>(c.search_steps) / collisions, c, collisions};
}

// A settled column: the exact engine runs the transient [0, settle], and from its state at
// `settle` both engines run the
// window, the exact one for `window`, the reference for `ref_window` (its wall time scaled to
// `window`: its cost is a fixed number of steps per unit time). Engines alone, no observers.
struct LargeColumn {
  double k;
  double ref_window;  // reference window, shorter where its steps are many
};
struct LargeTiming {
  double exact_s = 0, ref_s = 0;  // wall seconds over the window (reference: scaled)
  double events = 0, collisions = 0;
  ExactCounters window;           // exact engine's counters over the window
};
LargeTiming time_large_column(const LargeColumn& w, int N, double e, double settle, double window,
                              std::uint64_t seed) {
  const ChainParameters p{.N = N, .k = w.k, .e = e};
  ThermalFloor floor(p.kT0, p.m, seed);
  ExactEngine engine(p, driven_column_initial_state(p, seed), &floor);
  NullEventSink none;
  engine.advance_to(settle, none);
  const ChainState settled = engine.state();
  const ExactCounters before = engine.work();
  LargeTiming out;
  auto t0 = std::chrono::steady_clock::now();
  engine.advance_to(settle + window, none);
  out.exact_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const ExactCounters after = engine.work();
  out.events = static_cast<double>(after.steps - before.steps);
  out.collisions = static_cast<double>(after.contact_ends + after.floor_hits - before.contact_ends - before.floor_hits);
  out.window = after;
  out.window.search_steps -= before.search_steps;
  out.window.cluster_searches -= before.cluster_searches;
  out.window.cluster_search_steps -= before.cluster_search_steps;
  out.window.edge_searches -= before.edge_searches;
  ThermalFloor ref_floor(p.kT0, p.m, seed + 1);
  EngineChoice reference;
  reference.kind = EngineKind::Reference;
  auto ref = make_engine(reference, p, settled, &ref_floor);
  t0 = std::chrono::steady_clock::now();
  ref->advance_to(settle + w.ref_window, none);
  out.ref_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() * (window / w.ref_window);
  return out;
}

// The observers' share of a run: the exact engine over one window (N = 25, k = 1e8, T = 1000 after
// the same engine's transient of 100) handing its events to nothing (0), to the collision counter
// (1), or to the counter and the contact durations together, as run_driven_column does (2).
struct ObserverTiming {
  double ns = 0;  // wall nanoseconds per collision event of the window
  double wall_time() const { return ns; }
};
ObserverTiming time_observers(double e, int observers, std::uint64_t seed) {
  const ChainParameters p{.N = 25, .k = 1e8, .e = e};
  ThermalFloor floor(p.kT0, p.m, seed);
  ExactEngine engine(p, driven_column_initial_state(p, seed), &floor);
  NullEventSink none;
  engine.advance_to(100.0, none);
  CollisionCounter counter(100.0, 1100.0, 1024);
  ContactDurations contacts(p.N, contact_law(p).tau_c, 100.0, 1100.0);
  EventFanOut both{&counter, &contacts};
  EventSink& sink = observers == 0 ? static_cast<EventSink&>(none) : observers == 1 ? static_cast<EventSink&>(counter) : both;
  const auto before = engine.counters();
  const auto t0 = std::chrono::steady_clock::now();
  engine.advance_to(1100.0, sink);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto after = engine.counters();
  return {1e9 * wall / static_cast<double>(after.contact_ends + after.floor_hits - before.contact_ends - before.floor_hits)};
}

}  // namespace

// A column of N = 10 on a vibrating plate (omega = 5), through run_driven_column as `granchain run`.
Timing time_plate_run(const DriveSpec& drive, double k, EngineKind engine, double T, std::uint64_t seed) {
  RunSpec spec;
  spec.params = ChainParameters{.N = 10, .k = k, .e = 0.5};
  spec.drive = drive;
  spec.engine.kind = engine;
  spec.T = T;
  spec.transient = 0.1 * T;
  spec.seed = seed;
  return time_spec(spec);
}

int main(int argc, char** argv) {
  CLI::App app{"granchain engine benchmark: exact event-driven vs reference Runge-Kutta (N = 25 driven column)"};
  bool quick = false;
  double short_T = 1.0;
  std::uint64_t seed = 1;
  app.add_flag("--quick", quick, "extrapolate every reference time from a short run");
  app.add_option("--short-T", short_T, "window of the short reference runs used for extrapolation (> 0)");
  app.add_option("--seed", seed, "base seed");
  int repeat = 3;
  bool skip_large = false, free_space = false, plates = false;
  app.add_flag("--plates", plates,
               "also time N = 10, e = 0.5 columns on each vibrating plate (Gamma = 2 or A = 0.1, omega = 5) at k = 1e5 "
               "and 1e7 against the reference, then a condensed N = 40, e = 0.875 column at k = 1e10 on each drive (about 1 minute)");
  app.add_flag("--free-space", free_space,
               "also time free-space collapses, N = 25, e = 0.3, 200 launches at k = 1e8 and 1e10 (exact engine; "
               "up to 20 minutes)");
  app.add_flag("--skip-large", skip_large, "leave out the settled columns (N = 40, 100, 150; about 4 minutes)");
  bool observers = false;
  app.add_flag("--observers", observers,
               "only the observers' share: N = 25, k = 1e8, e = 0.5 and 0.85, the exact engine's window with no observer, the "
               "collision counter, and the counter with the contact durations (about 1 minute)");
  app.add_option("--repeat", repeat, "time every run this many times and keep the fastest (runs are deterministic)")
      ->check(CLI::Range(1, 100));
  if (const auto code = bench::parse_or_exit(app, argc, argv, "engine_speed", [&] {
        if (!(short_T > 0)) throw CLI::ValidationError("--short-T", fmt::format("must be > 0, got {}", short_T));
      })) {
    return *code;
  }
  // Wall times on a shared machine vary by tens of per cent between invocations; the fastest of
  // a few identical runs is the least disturbed measurement.
  auto fastest = [repeat](auto run) {
    auto best = run();
    for (int r = 1; r < repeat; ++r) {
      auto again = run();
      if (again.wall_time() < best.wall_time()) best = again;
    }
    return best;
  };

  if (observers) {
    fmt::print("Observers: N = 25, k = 1e8, window T = 1000 after a transient of 100, exact engine, seed {}; ns per collision "
               "event, fastest of {}, the three in turn\n",
               seed, repeat);
    fmt::print("{:>5} | {:>10} {:>10} {:>18} | {:>14} {:>18}\n", "e", "none", "counter", "counter+contacts", "counter/none",
               "+contacts/counter");
    for (const double e : {0.5, 0.85}) {
      ObserverTiming best[3];
      for (int r = 0; r < repeat; ++r)
        for (int which = 0; which < 3; ++which) {
          const ObserverTiming t = time_observers(e, which, seed);
          if (r == 0 || t.ns < best[which].ns) best[which] = t;
        }
      fmt::print("{:>5} | {:>10.1f} {:>10.1f} {:>18.1f} | {:>14.3f} {:>18.3f}\n", e, best[0].ns, best[1].ns, best[2].ns,
                 best[1].ns / best[0].ns, best[2].ns / best[1].ns);
    }
    return 0;
  }
  const std::vector<Workload> workloads{{1e8, 0.95, 100}, {1e8, 0.88, 100}, {1e8, 0.5, 100},
                                        {1e10, 0.95, 10}, {1e10, 0.88, 10}, {1e10, 0.5, 10}};
  fmt::print("N = 25 driven column, kT0 = 1, transient = T/10, seed {}; times are wall seconds on one core, fastest of {}\n",
             seed, repeat);
  fmt::print("{:>6} {:>5} {:>5} | {:>14} {:>9} {:>9} {:>11} {:>12} | {:>10} {:>12} {:>12} | {:>8}\n", "k", "e",
             "T", "n_coll (exact)", "exact s", "ns/coll", "engine-only", "search/coll", "ref s", "ref source",
             "steps/coll", "ratio");
  std::vector<EngineOnly> work;  // per workload, for the table of prediction work
  for (const Workload& w : workloads) {
    const Timing ex = fastest([&] { return time_run(w, EngineKind::Exact, w.T, seed); });
    const double ns_per_collision = 1e9 * ex.wall / static_cast<double>(ex.events);
    const EngineOnly engine = fastest([&] { return engine_only_per_collision(w, seed); });
    work.push_back(engine);
    // The reference at k = 1e10 (and everywhere with --quick): a short run, its wall time scaled
    // by simulated time (its cost is a fixed number of steps per unit time).
    const bool extrapolate = quick || w.k > 1e8;
    const Timing ref = fastest([&] { return time_run(w, EngineKind::Reference, extrapolate ? short_T : w.T, seed); });
    const double ref_wall = ref.wall * (ex.simulated / ref.simulated);
    const double steps_per_collision =
        static_cast<double>(ref.steps) / ref.simulated * ex.simulated / static_cast<double>(ex.events);
    fmt::print(
        "{:>6.0e} {:>5} {:>5} | {:>8.2f} ± {:<4.2f} {:>9.3f} {:>9.0f} {:>11.0f} {:>12.2f} | {:>10.2f} {:>12} {:>12.0f} | "
        "{:>7.0f}x\n",
        w.k, w.e, w.T, ex.n_coll, ex.n_coll_err, ex.wall, ns_per_collision, engine.ns, engine.search_steps, ref_wall,
        extrapolate ? fmt::format("T={} x{:.0f}", short_T, ex.simulated / ref.simulated) : "measured",
        steps_per_collision, ref_wall / ex.wall);
    std::fflush(stdout);
  }
  fmt::print(
      "ns/coll: exact wall time of the whole run (sampling included) per collision event (contact end or "
      "floor hit, transient included);\nengine-only: the same without sampling or observers; search/coll: root-free "
      "steps of the exact engine's event searches per collision event; steps/coll: "
      "reference steps per collision event; ratio: reference s / exact s.\n");
  // Where the exact engine's prediction work goes (engine-only runs; deterministic counts).
  fmt::print("\nexact engine's event predictions per collision event (engine-only runs):\n");
  fmt::print("{:>6} {:>5} | {:>11} {:>9} | {:>15} {:>10} | {:>15} {:>10}\n", "k", "e", "closed form", "bound",
             "cluster search", "steps each", "gap/floor search", "steps each");
  for (std::size_t i = 0; i < workloads.size(); ++i) {
    const ExactCounters& c = work[i].counters;
    const double per = 1.0 / work[i].collisions;
    const double edge_steps = static_cast<double>(c.search_steps - c.cluster_search_steps);
    auto ratio = [](double a, std::uint64_t b) { return b > 0 ? fmt::format("{:.2f}", a / static_cast<double>(b)) : "-"; };
    fmt::print("{:>6.0e} {:>5} | {:>11.2f} {:>9.2f} | {:>15.2f} {:>10} | {:>15.2f} {:>10}\n", workloads[i].k,
               workloads[i].e, per * static_cast<double>(c.closed_form_predictions),
               per * static_cast<double>(c.bound_exclusions), per * static_cast<double>(c.cluster_searches),
               ratio(static_cast<double>(c.cluster_search_steps), c.cluster_searches),
               per * static_cast<double>(c.edge_searches), ratio(edge_steps, c.edge_searches));
  }
  fmt::print(
      "closed form: a pair's contact end, two free particles, a free particle over the floor; bound: ruled out by "
      "the gap's lower bound with no step;\ncluster search: a cluster's contact ends searched step by step; gap/floor "
      "search: a gap or the floor height next to a cluster, step by step.\n");
  if (free_space) {
    // Sec. III.D's collapse count (granchain collapse --N 25 --e 0.3 --k K --realizations 200), one
    // core, one timing; the reference cannot run these k in any affordable time.
    fmt::print("\nfree-space collapse, N = 25, e = 0.3, a = v0 = 1, dv0 = 0.1, 200 launches, seed {} (exact engine, one timing)\n",
               seed);
    fmt::print("{:>6} | {:>9} {:>12} {:>14} {:>13} {:>9}\n", "k", "wall s", "collisions", "us/collision", "mean n_tot",
               "held");
    for (double k : {1e8, 1e10}) {
      CollapseSpec spec;
      spec.params = ChainParameters{.N = 25, .g = 0.0, .k = k, .e = 0.3};
      spec.realizations = 200;
      spec.seed = seed;
      const CollapseResult r = run_collapse(spec);
      fmt::print("{:>6.0e} | {:>9.1f} {:>12} {:>14.2f} {:>13.1f} {:>9}\n", k, r.wall_seconds, r.collisions,
                 1e6 * r.wall_seconds / static_cast<double>(r.collisions), r.n_tot_mean, r.held_contacts);
      std::fflush(stdout);
    }
  }
  if (plates) {
    // The reference at k = 1e7 from a window of 30, scaled to the exact engine's 300.
    fmt::print("\nN = 10 columns on vibrating plates, e = 0.5, omega = 5, T = 300 (transient 30), seed {}; wall seconds, fastest of {}\n",
               seed, repeat);
    fmt::print("{:>10} {:>6} | {:>15} {:>9} {:>9} | {:>15} {:>9} {:>12} | {:>8}\n", "drive", "k", "n_coll (exact)", "exact s",
               "ns/event", "n_coll (ref)", "ref s", "ref source", "ratio");
    for (const DriveSpec& drive : {DriveSpec{DriveKind::Sine, 2.0 / 25.0, 5.0}, DriveSpec{DriveKind::Quadratic, 2.0 / (gamma_factor(DriveKind::Quadratic) * 25.0), 5.0},
                                   DriveSpec{DriveKind::Sawtooth, 0.1, 5.0}}) {
      for (double k : {1e5, 1e7}) {
        const Timing ex = fastest([&] { return time_plate_run(drive, k, EngineKind::Exact, 300.0, seed); });
        const double ref_T = k > 1e5 ? 30.0 : 300.0;
        const Timing ref = fastest([&] { return time_plate_run(drive, k, EngineKind::ReferenceLocated, ref_T, seed); });
        const double ref_wall = ref.wall * ex.simulated / ref.simulated;
        fmt::print("{:>10} {:>6.0e} | {:>8.3f} ± {:<5.3f} {:>9.3f} {:>9.0f} | {:>8.3f} ± {:<5.3f} {:>9.2f} {:>12} | {:>7.1f}x\n",
                   drive_name(drive.kind), k, ex.n_coll, ex.n_coll_err, ex.wall, 1e9 * ex.wall / static_cast<double>(ex.events),
                   ref.n_coll, ref.n_coll_err, ref_wall, ref_T < 300 ? fmt::format("T={} x{:.0f}", ref_T, ex.simulated / ref.simulated) : "measured",
                   ref_wall / ex.wall);
        std::fflush(stdout);
      }
    }
    fmt::print("ref: reference-located (each step cut at contact switches and the plate's switching instants); ratio: ref s / "
               "exact s; n_coll (ref) is over its own window.\n");
    // A condensed column at large k: the cluster resting on the plate is searched as a whole at every
    // event inside it, so an event costs more than on the thermal floor; the plates of the drives
    // figures (omega = 10, peak speed 1).
    fmt::print("\nN = 40, e = 0.875, k = 1e10, T = 20 (transient 2), seed {}: exact engine, fastest of {}\n", seed, repeat);
    fmt::print("{:>10} | {:>15} {:>9} {:>9} {:>9} | {:>12}\n", "drive", "n_coll", "s", "events", "us/event", "vs thermal");
    double thermal_us = 0.0;
    for (const DriveSpec& drive : {DriveSpec{}, DriveSpec{DriveKind::Sine, 0.1, 10.0}, DriveSpec{DriveKind::Sawtooth, std::numbers::pi / 10.0, 10.0},
                                   DriveSpec{DriveKind::Quadratic, std::numbers::pi / 40.0, 10.0}}) {
      RunSpec spec;
      spec.params = ChainParameters{.N = 40, .k = 1e10, .e = 0.875};
      spec.drive = drive;
      spec.T = 20.0;
      spec.transient = 2.0;
      spec.seed = seed;
      const Timing ex = fastest([&] { return time_spec(spec); });
      const double us = 1e6 * ex.wall / static_cast<double>(ex.events);
      if (!drive.plate()) thermal_us = us;
      fmt::print("{:>10} | {:>8.2f} ± {:<5.2f} {:>9.3f} {:>9} {:>9.2f} | {:>11.1f}x\n", drive.plate() ? drive_name(drive.kind) : "thermal",
                 ex.n_coll, ex.n_coll_err, ex.wall, ex.events, us, us / thermal_us);
      std::fflush(stdout);
    }
  }
  if (skip_large) return 0;
  // Settled columns: one timing each (the transient alone takes minutes at k = 1e10). The N = 150
  // column at e = 0.1 (paper Sec. III.C, the power-law regime) over three decades of k, and the
  // condensed N = 40 (e = 0.1) and N = 100 (e = 0.2) columns at k = 1e10.
  struct Settled {
    int N;
    double e;
    LargeColumn w;
  };
  const double settle = 45.0, window = 5.0;
  fmt::print("\nsettled driven columns, kT0 = 1, seed {}: transient [0, {}] with the exact engine, then both engines "
             "from its state over a window of {} (engines alone, one timing)\n",
             seed, settle, window);
  fmt::print("{:>4} {:>4} {:>6} | {:>8} {:>10} {:>10} {:>9} | {:>9} {:>12} {:>9} | {:>9} {:>8} {:>8}\n", "N", "e", "k",
             "exact s", "events", "collisions", "us/event", "ref s", "ref window", "us/event", "ratio", "cl.steps", "edge");
  for (const Settled& c : {Settled{150, 0.1, {1e6, 5.0}}, Settled{150, 0.1, {1e8, 0.5}}, Settled{150, 0.1, {1e10, 0.05}},
                           Settled{40, 0.1, {1e10, 0.05}}, Settled{100, 0.2, {1e10, 0.05}}}) {
    const LargeColumn& w = c.w;
    const LargeTiming t = time_large_column(w, c.N, c.e, settle, window, seed);
    fmt::print(
        "{:>4} {:>4} {:>6.0e} | {:>8.2f} {:>10.0f} {:>10.0f} {:>9.2f} | {:>9.2f} {:>12} {:>9.2f} | {:>8.2f}x {:>8.2f} "
        "{:>8.2f}\n",
        c.N, c.e, w.k, t.exact_s, t.events, t.collisions, 1e6 * t.exact_s / t.events, t.ref_s,
        w.ref_window < window ? fmt::format("{} x{:.0f}", w.ref_window, window / w.ref_window) : "measured",
        1e6 * t.ref_s / t.events, t.ref_s / t.exact_s, static_cast<double>(t.window.cluster_search_steps) / t.events,
        static_cast<double>(t.window.search_steps - t.window.cluster_search_steps) / t.events);
    std::fflush(stdout);
  }
  fmt::print("events: exact engine's events in the window (contact begins, ends, floor hits, refreshes); ref us/event: the "
             "reference's wall time over the same number of events;\nratio: reference s / exact s; cl.steps, edge: "
             "root-free steps of cluster and of gap/floor searches per event.\n");
  return 0;
}
