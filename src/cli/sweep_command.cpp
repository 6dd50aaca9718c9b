#include "cli/subcommand.hpp"
#include "cli/exit_codes.hpp"
#include "sweep/sweep_progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>
#include <thread>
#include <tuple>
#include <utility>

#include "config/config_file.hpp"
#include "config/input_error.hpp"
#include "provenance.hpp"
#include "cli/interrupt_message.hpp"
#include "config/run_options.hpp"
#include "config/value_list.hpp"
#include "store/output_file.hpp"
#include "store/results_store.hpp"
#include "sweep/mpi_sweep.hpp"
#include "sweep/sweep_checkpoints.hpp"
#include "sweep/sweep_grid.hpp"
#include "sweep/sweep_runner.hpp"

namespace granchain {

namespace {

struct SweepFlags {
  std::map<std::string, std::string> flag_values;
  std::map<std::string, CLI::Option*> flag_options;
  std::string sweep_path;
  std::string replicas, threads, shard, time_limit, checkpoint_dir;
  double progress_every = 0;
  bool dry_run = false, quiet = false, progress_lines = false;
};

int execute_sweep(const std::shared_ptr<SweepFlags>& impl_, CLI::App* sub_);

}  // namespace

namespace {

bool is_grid(const std::string& name) {
  const auto& g = sweep_grid_parameters();
  return std::find(g.begin(), g.end(), name) != g.end();
}

// A value as the text a flag would carry: text as given, a number of a sweep file as written
// there (a real keeps its ".0", which an integer refuses).
std::string as_text(const RawValue& v) {
  if (const auto* t = std::get_if<std::string>(&v.value)) return *t;
  return v.text();
}

long long integer_in(const std::string& option, const std::string& text, long long lo, long long hi) {
  return parse_integer_in(text, option, lo, hi);
}

// --shard i/n: the whole value is quoted in every message ('1/3/5', not '3/5').
std::pair<int, int> parse_shard(const std::string& text) {
  const std::string range = "i/n with integers 1 <= i <= n <= 100000";
  const auto slash = text.find('/');
  if (slash == std::string::npos || text.find('/', slash + 1) != std::string::npos)
    throw InputError(fmt::format("--shard = '{}' is not valid; valid: {}", text, range));
  long long i = 0, n = 0;
  try {
    n = parse_integer_in(text.substr(slash + 1), "--shard", 1, 100000);
    i = parse_integer_in(text.substr(0, slash), "--shard", 1, n);
  } catch (const InputError&) {
    throw InputError(fmt::format("--shard = '{}' is not valid; valid: {}", text, range));
  }
  return {static_cast<int>(i), static_cast<int>(n)};
}

}  // namespace

Subcommand add_sweep_command(CLI::App& app) {
  auto impl_ = std::make_shared<SweepFlags>();
  CLI::App* sub_;
  sub_ = app.add_subcommand("sweep", "Run a grid of driven-column runs (N, e, k, T0, drive, T, engine, replica) into the results store.");
  sub_->footer(
      "Grid parameters (N, e, k, T0, T, engine) take lists and ranges: 3,4,5  0.80:0.90:0.002 (first:last:step)\n"
      "1e5:1e10:x10 (first:last:xFACTOR); every other parameter takes one value, as in `granchain run`.\n"
      "Each point is one run, stored in one transaction with its key (all its parameters and seed): a\n"
      "sweep started again with the same arguments runs only the points the store lacks, so a killed\n"
      "sweep (even kill -9) is resumed by repeating its command. Each point's seed derives from --seed and\n"
      "the point's own parameters and replica number, so results depend neither on threads, ranks, shards\n"
      "nor order. Points run longest first (estimated from N, T, e, k and the engine).\n"
      "MPI: mpirun -np P granchain sweep ... : rank 0 writes the store and hands out points one at a time;\n"
      "every other rank runs one point at a time (give one rank per core). --threads sets rank 0's own\n"
      "workers (default 1 under MPI). Job arrays: --shard i/n runs share i of n; join the stores with\n"
      "`granchain merge`.\n" +
      exit_codes_help("2 bad input (nothing run), 3 some points turned unphysical (the others are stored), 4 the results "
                      "store could not be written, 75 --time-limit left points for a repeat of the command"));
  auto& impl = *impl_;
  for (const Parameter& p : run_parameters()) {
    if (!(p.uses & kUseSweep)) continue;
    std::string help = p.help();
    if (is_grid(p.name)) help = (p.name == "engine" ? "comma LIST; " : "LIST or range; ") + help;
    if (p.name == "seed") help = "base seed: each point's seed derives from it, the point's parameters and replica; "
                                 "integer 0 <= seed <= 9223372036854775807; default 1";
    impl.flag_options[p.name] = sub_->add_option("--" + p.name, impl.flag_values[p.name], help)
                                    ->type_name(is_grid(p.name) ? "LIST" : p.type_name())
                                    ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  }
  sub_->add_option("--sweep", impl.sweep_path,
                   "read the sweep from a JSON or TOML file: keys as the flags (and replicas), lists as strings "
                   "(\"0.8:0.9:0.01\") or arrays; flags given here override it")
      ->type_name("FILE");
  sub_->add_option("--replicas", impl.replicas, "independent runs (different seeds) per grid point; integer 1 <= replicas <= 1000000; default 1")
      ->type_name("INT");
  sub_->add_option("--threads", impl.threads, "points run at once on this machine; integer 1 <= threads <= 1024; default all cores "
                                              "(1 on rank 0 under MPI)")
      ->type_name("INT");
  sub_->add_option("--shard", impl.shard, "run only share i of n of the grid (1 <= i <= n <= 100000), for job arrays")
      ->type_name("i/n");
  sub_->add_option("--time-limit", impl.time_limit,
                   "a batch job's walltime: start only points predicted (cost model, scaled by the points finished) to end "
                   "within it, leave the rest for a repeat of the command, and exit 75; points whose estimate alone exceeds "
                   "it are refused (exit 2) unless they keep their state (--checkpoint-dir); seconds, 90m, 2.5h or [D-]H:MM:SS")
      ->type_name("DURATION");
  sub_->add_option("--checkpoint-dir", impl.checkpoint_dir,
                   "keep the state of every running point of a resumable engine (" + resumable_engine_list() +
                       ") in this folder, saved every checkpoint-every seconds and "
                       "when SIGINT, SIGTERM or the end of --time-limit stops the sweep; a repeat of the command resumes those points where they stopped "
                       "(bit for bit), so one point may run longer than a job")
      ->type_name("DIR");
  sub_->add_flag("--dry-run", impl.dry_run, "list the points (with their keys, seeds and estimated cost), what the store already holds and, with "
                 "--checkpoint-dir, which points keep their state there; run nothing");
  sub_->add_flag("--quiet,-q", impl.quiet, "print no table of results, no summary, and no progress unless --progress is given");
  sub_->add_flag("--progress", impl.progress_lines, "print progress on standard error even with --quiet");
  sub_->add_option("--progress-every", impl.progress_every,
                   "seconds between progress reports; 0.1 <= seconds <= 86400; default 0.5 on a terminal, 10 otherwise")
      ->type_name("SECONDS");
  return {sub_, [impl_, sub_] { return execute_sweep(impl_, sub_); }};
}

namespace {

int execute_sweep(const std::shared_ptr<SweepFlags>& impl_, CLI::App* sub_) {
  auto& impl = *impl_;
  MpiWorld world;
  const bool rank0 = world.rank() == 0;
  auto fail = [&](const std::string& message, int code) {
    if (rank0) fmt::print(stderr, "granchain: error: {}\n", message);
    return code;
  };

  SweepDefinition def;
  std::string db_path = "granchain.db";
  int threads = 0, shard_i = 1, shard_n = 1;
  double time_limit = 0;  // seconds; 0: none
  std::optional<RawValue> checkpoint_every;  // as given
  std::unique_ptr<SweepCheckpoints> checkpoints;
  std::vector<SweepPoint> points;
  try {
    if (launched_by_mpi_launcher() && !built_with_mpi())
      throw InputError("sweep: started by an MPI launcher, but this granchain was built without MPI "
                       "(install libopenmpi-dev and rebuild); run it without mpirun to use threads");
    std::map<std::string, RawValue> from_file;
    if (!impl.sweep_path.empty()) from_file = read_config_file(impl.sweep_path, "--sweep");
    auto take = [&](const std::string& name, const std::string& flag_text, bool given) -> std::optional<RawValue> {
      if (given) return RawValue{flag_text, ""};
      const auto it = from_file.find(name);
      if (it != from_file.end()) {
        RawValue v = it->second;
        v.source = fmt::format("sweep file '{}'", impl.sweep_path);
        return v;
      }
      return std::nullopt;
    };
    for (const auto& [key, value] : from_file) {
      const bool known = key == "replicas" || impl.flag_options.count(key);
      if (!known) throw InputError(fmt::format("--sweep: '{}': unknown parameter '{}'", impl.sweep_path, key));
    }
    for (const auto& [name, opt] : impl.flag_options) {
      if (auto v = take(name, impl.flag_values[name], opt->count() > 0)) {
        if (name == "seed") {
          def.base_seed = static_cast<std::uint64_t>(integer_in("--seed", as_text(*v), 0, 9223372036854775807LL));
        } else if (name == "checkpoint-every") {
          checkpoint_every = *v;
        } else if (name == "db") {
          db_path = as_text(*v);
          if (db_path.empty()) throw InputError("--db: the path is empty; give a file name");
        } else {
          def.raw[name] = *v;
        }
      }
    }
    // A flag given with an empty value ("--shard ''") is given, and refused as such.
    const auto given = [&](const char* flag) { return sub_->get_option(flag)->count() > 0; };
    if (auto v = take("replicas", impl.replicas, given("--replicas")))
      def.replicas = static_cast<int>(integer_in("--replicas", as_text(*v), 1, 1000000));
    if (given("--threads")) threads = static_cast<int>(integer_in("--threads", impl.threads, 1, 1024));
    if (given("--shard")) std::tie(shard_i, shard_n) = parse_shard(impl.shard);
    if (given("--time-limit")) time_limit = parse_duration(impl.time_limit, "--time-limit");
    if (sub_->get_option("--progress-every")->count() > 0 && !(impl.progress_every >= 0.1 && impl.progress_every <= 86400))
      throw InputError(fmt::format("--progress-every = {} is out of range; valid range: 0.1 <= seconds <= 86400 (a day)",
                                   impl.progress_every));
    points = build_sweep_points(def);
    if (shard_n > 1) points = shard_points(points, shard_i, shard_n);
    checkpoints = make_sweep_checkpoints(given("--checkpoint-dir") ? &impl.checkpoint_dir : nullptr,
                                         checkpoint_every ? &*checkpoint_every : nullptr, points);
    if (checkpoints) checkpoints->announce_resumes(!impl.quiet || impl.progress_lines);
    if (!impl.sweep_path.empty()) check_output_file(db_path, "--db", {{"--sweep", impl.sweep_path}});
    // A dry run only reads the store, if there is one.
    if (rank0 && !impl.dry_run) ResultsStore::preflight(db_path);
    if (rank0 && impl.dry_run && access(db_path.c_str(), F_OK) == 0) ResultsStore::preflight(db_path, ResultsStore::Access::ReadOnly);
    if (rank0 && !impl.dry_run && checkpoints) checkpoints->create_folder();
  } catch (const InputError& e) {
    return fail(e.what(), kExitBadInput);
  } catch (const OutputError& e) {
    return world.broadcast(fail(e.what(), kExitBadInput));
  } catch (const StoreError& e) {
    return world.broadcast(fail(e.what(), kExitBadInput));
  }
  if (world.broadcast(kExitOk) != kExitOk) return kExitBadInput;  // (only reached on ranks != 0)
  if (threads == 0) threads = world.size() > 1 ? 1 : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  set_parallelism(threads, world.size());

  // Rank 0 finds what the store holds; the other ranks only compute what rank 0 hands them.
  std::unique_ptr<ResultsStore> store;
  std::vector<std::size_t> todo;
  std::size_t already = 0;
  int code = kExitOk;
  // Points whose hard spheres collapsed in an earlier sweep: stored as collapses, not run again.
  std::map<std::string, ResultsStore::CollapsedPoint> collapsed;
  if (rank0) {
    try {
      std::unordered_set<std::string> done;
      const auto settled = [&](ResultsStore& s) {
        done = s.point_keys();
        collapsed = s.collapsed_points();
        for (const auto& [key, c] : collapsed) done.insert(key);
      };
      if (impl.dry_run) {
        if (access(db_path.c_str(), F_OK) == 0) {
          try {
            ResultsStore reader(db_path, ResultsStore::Access::ReadOnly);
            settled(reader);
          } catch (const StoreError&) {  // a version-1 store is read as the first write would: upgraded
            ResultsStore writer(db_path);
            settled(writer);
          }
        }
      } else {
        // With a time limit, points that no invocation can fit in it are refused before the store
        // is opened for writing (or created), so nothing is written.
        if (time_limit > 0) {
          if (access(db_path.c_str(), F_OK) == 0) {
            ResultsStore reader(db_path, ResultsStore::Access::ReadOnly);
            settled(reader);
          }
          const std::vector<std::size_t> longer = points_longer_than(points, points_to_run(points, done), time_limit, checkpoints.get());
          if (!longer.empty()) code = fail(time_limit_too_short_message(points, longer, time_limit), kExitBadInput);
        }
        if (code == kExitOk) {
          store = std::make_unique<ResultsStore>(db_path);
          settled(*store);
        }
      }
      todo = points_to_run(points, done);
      already = points.size() - todo.size();
    } catch (const StoreError& e) {
      code = fail(e.what(), kExitStoreFailed);
    }
  }
  if (code == kExitBadInput) return world.broadcast(code);
  if (world.broadcast(code) != kExitOk) return kExitStoreFailed;

  if (impl.dry_run) {
    if (rank0) {
      double cost = 0;
      for (std::size_t i : todo) cost += points[i].cost;
      fmt::print("# {} points{}, {} already in {}, {} to run, estimated {} of one core\n", points.size(),
                 shard_n > 1 ? fmt::format(" (shard {}/{})", shard_i, shard_n) : "", already, db_path, todo.size(),
                 format_duration(cost));
      fmt::print("# order  est_cost_s  replica  seed  key\n");
      std::vector<bool> to_run(points.size(), false);
      for (std::size_t i : todo) to_run[i] = true;
      for (std::size_t i = 0; i < points.size(); ++i)
        fmt::print("{:6d}  {:10.3g}  {:7d}  {}  {}{}\n", i + 1, points[i].cost, points[i].replica, points[i].spec.seed,
                   points[i].key,
                   !to_run[i] ? std::string(collapsed.count(points[i].key) ? "  (stored: collapsed)" : "  (stored)")
                   : !checkpoints || !SweepCheckpoints::covers(points[i]) ? std::string()
                   : checkpoints->has_saved(points[i]) ? fmt::format("  (checkpointed, saved part-way: {})", checkpoints->path(points[i]))
                                                       : std::string("  (checkpointed)"));
    }
    return kExitOk;
  }

  // With checkpoints a signal is recorded: the running points save their states and stop, then
  // the sweep says so and ends by the signal. Without, it ends at once.
  static CancelFlag interrupted{false};
  if (checkpoints) record_interrupts(&interrupted);
  else announce_on_interrupt(fmt::format("every point that finished is stored in {}; repeat the same command to run the rest", db_path));
  if (rank0 && checkpoints) {
    const std::size_t spent = remove_spent_states(*checkpoints, points, todo);
    if (spent > 0) fmt::print(stderr, "sweep: removed {} saved state{} of points stored already from {}\n", spent, spent == 1 ? "" : "s", checkpoints->dir());
  }
  const bool tty = isatty(STDERR_FILENO) != 0;
  // On a terminal one line rewritten in place; otherwise (a batch job's log) a line every 10 s.
  const bool show_progress = rank0 && (impl.progress_lines || !impl.quiet);
  const double every = impl.progress_every > 0 ? impl.progress_every : (tty ? 0.5 : 10.0);
  const SweepProgressPrinter printer(tty, "sweep");
  std::vector<std::string> failures, collapsed_now;
  std::size_t inserted = 0;
  PointSink sink = [&](const SweepPoint& p, const RunResult* r, const std::string& error, const InelasticCollapseError* collapse) {
    if (collapse) {
      store->insert_collapsed_point(p.key, ResultsStore::collapsed_point(*collapse));
      collapsed_now.push_back(fmt::format("{}: {}", p.key, error));
      return;
    }
    if (!r) {
      failures.push_back(fmt::format("{}: {}", p.key, error));
      return;
    }
    if (store->insert_sweep_point(*r, p.key, def.base_seed, p.replica).inserted) ++inserted;
  };
  std::unique_ptr<SweepRunner> runner;
  if (rank0) {
    if (!impl.quiet || show_progress)
      fmt::print(stderr, "sweep: {} points{}, {} already in {}, {} to run on {} thread{}{}\n", points.size(),
                 shard_n > 1 ? fmt::format(" (shard {}/{})", shard_i, shard_n) : "", already, db_path, todo.size(), threads,
                 threads == 1 ? "" : "s", world.size() > 1 ? fmt::format(" + {} MPI ranks", world.size() - 1) : "");
    runner = std::make_unique<SweepRunner>(points, todo, sink);
    if (time_limit > 0) runner->set_time_limit(time_limit);
    if (checkpoints) {
      runner->set_checkpoints(checkpoints.get());
      runner->watch(&interrupted);
    }
  }
  try {
    SweepProgressCallback cb;
    if (show_progress) cb = [&printer](const SweepProgress& p) { printer(p); };
    PointStops rank_stops;  // on ranks other than 0 (rank 0's runner keeps its own)
    rank_stops.cancel = &interrupted;
    if (checkpoints && time_limit > 0) rank_stops.suspend_at = steady_clock_seconds() + checkpoint_deadline(time_limit);
    run_sweep_over_ranks(world, points, runner.get(), threads, cb, every, checkpoints.get(), rank_stops);
  } catch (const StoreError& e) {
    code = fail(fmt::format("{}; the sweep stopped, every point stored so far is complete (repeat the command to resume)", e.what()),
                kExitStoreFailed);
  } catch (const OutputError& e) {  // a point's state could not be saved
    code = fail(fmt::format("{}; the sweep stopped, every point stored so far is complete and the states saved before are kept in {} "
                            "(repeat the command to resume)",
                            e.what(), checkpoints ? checkpoints->dir() : std::string()),
                kExitStoreFailed);
  }
  // Rank 0's signal decides for every rank (each ends by it): a rank that saw a signal of its own
  // has only left the sweep.
  if (const int sig = checkpoints ? world.broadcast(rank0 ? recorded_interrupt() : 0) : 0; sig != 0) {
    if (rank0)
      fmt::print(stderr, "\ngranchain: interrupted by {}; every point that finished is stored in {}, the states of {} running point{} are "
                         "saved in {}; repeat the same command to go on\n",
                 interrupt_name(sig), db_path, runner->saved(), runner->saved() == 1 ? "" : "s", checkpoints->dir());
    reraise_interrupt(sig);
  }
  if (!rank0) return world.broadcast(code);

  if (code == kExitOk) {
    // A collapse of hard spheres is kept as the point's outcome (no n_coll): stored now, or before.
    std::size_t collapsed_before = 0;
    for (const SweepPoint& p : points)
      if (const auto it = collapsed.find(p.key); it != collapsed.end()) {
        fmt::print(stderr, "granchain: error: hard spheres collapsed (kept in {} as a collapse, no n_coll): {}: {}\n", db_path, p.key,
                   it->second.message);
        ++collapsed_before;
      }
    for (const auto& f : collapsed_now) fmt::print(stderr, "granchain: error: hard spheres collapsed, kept as a collapse (no n_coll): {}\n", f);
    for (const auto& f : failures) fmt::print(stderr, "granchain: error: point turned unphysical, not stored: {}\n", f);
    if (!failures.empty() || !collapsed_now.empty() || collapsed_before > 0) code = kExitUnphysical;
    std::map<std::string, ResultsStore::PointSummary> summaries;
    if (!impl.quiet) {
      try {
        summaries = store->point_summaries();
      } catch (const StoreError& e) {
        fmt::print(stderr, "granchain: error: {}; the table of results cannot be shown, every finished point is stored\n", e.what());
        return world.broadcast(kExitStoreFailed);
      }
      // Drive columns where a plate drives a point: its drive, A and omega.
      const bool plates = std::any_of(points.begin(), points.end(), [](const SweepPoint& p) { return p.spec.drive.plate(); });
      fmt::print("{:>6} {:>8} {:>10} {:>6}", "N", "e", "k", "T0");
      if (plates) fmt::print(" {:>9} {:>10} {:>8}", "drive", "A", "omega");
      fmt::print(" {:>8} {:>10} {:>4} {:>10} {:>9} {:>6}\n", "T", "engine", "rep", "n_coll", "error", "run");
      std::vector<const SweepPoint*> order;
      for (std::size_t i : table_order(points)) order.push_back(&points[i]);
      for (const SweepPoint* p : order) {
        const auto it = summaries.find(p->key);
        if (it == summaries.end()) continue;  // failed
        const RunSpec& s = p->spec;
        fmt::print("{:>6} {:>8.6g} {:>10.3g} {:>6.4g}", s.params.N, s.params.e, s.params.k, s.params.kT0);
        if (plates && s.drive.plate()) fmt::print(" {:>9} {:>10.4g} {:>8.4g}", drive_name(s.drive.kind), s.drive.A, s.drive.omega);
        else if (plates) fmt::print(" {:>9} {:>10} {:>8}", drive_name(s.drive.kind), "", "");
        fmt::print(" {:>8.6g} {:>10} {:>4} {:>10.5g} {:>9.2g} {:>6}\n", s.T, engine_name(s.engine.kind), p->replica, it->second.n_coll,
                   it->second.n_coll_err, it->second.id);
      }
    }
    if (!impl.quiet)
      fmt::print(stderr, "sweep: {} points stored now, {} were already there{}, {} failed; store {}\n", inserted, already - collapsed_before,
                 collapsed_now.size() + collapsed_before > 0
                     ? fmt::format(", {} collapsed ({} now)", collapsed_now.size() + collapsed_before, collapsed_now.size())
                     : "",
                 failures.size(), db_path);
    if (const std::size_t left = runner->not_started(), saved = runner->saved(); left > 0 || saved > 0) {
      fmt::print(stderr, "sweep: --time-limit: {} points not started (estimated {} of one core){}; repeat the command to run them\n",
                 left, format_duration(runner->not_started_cost()),
                 saved > 0 ? fmt::format(", {} stopped part-way with their states saved in {}", saved, checkpoints->dir()) : "");
      if (code == kExitOk) code = kExitTimeLimit;
    }
  }
  return world.broadcast(code);
}

}  // namespace

}  // namespace granchain
