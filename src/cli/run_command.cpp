#include "cli/subcommand.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <optional>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>

#include "config/config_file.hpp"
#include "config/run_key.hpp"
#include "config/input_error.hpp"
#include "cli/interrupt_message.hpp"
#include "store/output_file.hpp"
#include "config/run_options.hpp"
#include "cli/run_report.hpp"
#include "engines/engine.hpp"
#include "store/results_store.hpp"
#include "store/run_checkpoint.hpp"
#include "store/run_json.hpp"
#include "simulation/cancellation.hpp"
#include "version.hpp"

namespace granchain {

namespace {

struct RunFlags {
  std::map<std::string, std::string> flag_values;  // parameter name -> text from the command line
  std::map<std::string, CLI::Option*> flag_options;
  std::string config_path;
  std::string json_path;
  CLI::Option* json_option = nullptr;
  bool no_db = false;
  bool quiet = false;
  bool progress_lines = false;
  bool audit = false;
};

int execute_run(const std::shared_ptr<RunFlags>& impl_);

}  // namespace

Subcommand add_run_command(CLI::App& app) {
  auto impl_ = std::make_shared<RunFlags>();
  CLI::App* sub_;
  sub_ = app.add_subcommand("run", "Simulate the driven column once and measure n_coll and the profiles.");
  sub_->footer(
      "Units: m = d = g = 1 unless set. The floor at z = 0 touches the lower edge of particle 1\n"
      "(a floor hit is z_1 = d/2) and returns it with a speed from p(v) = (m v/kT0) exp(-m v^2/2kT0).\n"
      "n_coll = N_coll / (N T) counts every separation of two touching particles and every floor hit\n"
      "inside the measuring window; errors are one standard error from blocking analysis.\n"
      "Output: a summary on the terminal, JSON with --json [FILE] (stdout without FILE), and one row\n"
      "in the results store (--db).\n" +
      exit_codes_help("2 bad input (nothing written), 3 the simulation turned unphysical (nothing written), 4 the results "
                      "store could not be written"));
  auto& impl = *impl_;
  for (const Parameter& p : run_parameters()) {
    if (!(p.uses & kUseRun)) continue;
    impl.flag_options[p.name] = sub_->add_option("--" + p.name, impl.flag_values[p.name], p.help())
                                    ->type_name(p.type_name())
                                    ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  }
  sub_->add_option("--config", impl.config_path,
                   "read parameters from a JSON or TOML file (keys as the flags); flags given here override it")
      ->type_name("FILE");
  impl.json_option = sub_->add_option("--json", impl.json_path,
                                      "write the result as JSON to FILE, or to standard output if no FILE is given")
                         ->expected(0, 1)
                         ->type_name("[FILE]");
  sub_->add_flag("--no-db", impl.no_db, "do not append the run to the results store");
  sub_->add_flag("--quiet,-q", impl.quiet, "print no summary, and no progress unless --progress is given");
  sub_->add_flag("--progress", impl.progress_lines,
                 "print progress on standard error: a line every 10 s when it is not a terminal");
  sub_->add_flag("--audit", impl.audit,
                 "exact engine: after every event evaluate every overlap, gap and the floor height at random "
                 "instants before the next one and stop with exit 3 if one has the wrong sign (slower; the "
                 "trajectory and results are the same)");
  return {sub_, [impl_] { return execute_run(impl_); }};
}

namespace {

class ProgressPrinter {
 public:
  explicit ProgressPrinter(bool tty) : tty_(tty) {}
  void operator()(const RunProgress& p) {
    const double frac = p.t_total > 0 ? p.t / p.t_total : 1.0;
    const double eta = frac > 0 ? p.wall_seconds * (1.0 - frac) / frac : 0.0;
    const std::string line = fmt::format(
        "run: {:5.1f}% t = {:.6g}/{:.6g} ({}), {:.3g} steps/s, {:.3g} collisions/s, elapsed {:.0f} s, ETA {:.0f} s",
        100.0 * frac, p.t, p.t_total, p.in_transient ? "transient" : "measuring",
        p.wall_seconds > 0 ? p.steps / p.wall_seconds : 0.0, p.wall_seconds > 0 ? p.events / p.wall_seconds : 0.0,
        p.wall_seconds, eta);
    if (tty_) {
      fmt::print(stderr, "\r{:<118}", line);
      printed_ = true;
    } else {
      fmt::print(stderr, "{}\n", line);
    }
    std::fflush(stderr);
  }
  void finish() {
    if (tty_ && printed_) fmt::print(stderr, "\r{:<118}\r", "");
  }

 private:
  bool tty_;
  bool printed_ = false;
};

}  // namespace

namespace {

// The outputs of a run read back from the store instead of run again (one line on standard error
// says so): its JSON, marked as read back, and its summary.
int report_stored_run(const RunFlags& impl, const RunOptions& opts, const ResultsStore::ReadBack& stored, bool json_stdout) {
  fmt::print(stderr,
             "granchain: run {} of {} is this run already (the same parameters and --seed {}, so the same trajectory); "
             "it was not run or stored again; for an independent replica give another --seed\n",
             stored.id, opts.db_path, opts.spec.seed);
  const std::string where = fmt::format("run {} in {}, stored before and read back", stored.id, opts.db_path);
  try {
    if (impl.json_option->count() > 0 && !json_stdout) write_file_atomically(impl.json_path, stored.json.dump(2) + "\n", "--json");
    if (json_stdout) write_standard_output(stored.json.dump(2) + "\n");
    else if (!impl.quiet) write_standard_output(run_summary(stored.result, where));
  } catch (const std::exception& e) {
    fmt::print(stderr, "granchain: error: {}; the run is stored ({})\n", e.what(), where);
    return kExitStoreFailed;
  }
  return kExitOk;
}

// The checkpoint to resume this run from (key: its point key), nothing when there is none; says
// that it resumes, and from which build. Throws CheckpointError for a checkpoint of another run
// (so that no state goes on under another run's name), StateArchiveError for one without its place.
std::optional<RunCheckpoint> checkpoint_to_resume(const RunOptions& opts, const std::string& key) {
  std::optional<RunCheckpoint> checkpoint = read_run_checkpoint_of(opts.checkpoint_path, key);
  if (!checkpoint) return checkpoint;
  const SavedRunPlace place = saved_run_place(checkpoint->state);
  fmt::print(stderr, "granchain: resuming from --checkpoint {} at t = {:.6g} of {:.6g} ({}; saved by granchain {}{})\n",
             opts.checkpoint_path, place.t, opts.spec.transient + opts.spec.T, place.in_window ? "measuring" : "transient",
             checkpoint->written_by,
             checkpoint->written_by == code_version()
                 ? ""
                 : fmt::format(", this is {}: bit for bit the same result only if the engine and observers are unchanged", code_version()));
  return checkpoint;
}

// A checkpoint of a run found stored already (its process stored it and was stopped before removing
// the checkpoint) is spent: removed, saying so. Anything else at that path is left as it is.
void remove_spent_checkpoint(const RunOptions& opts, const std::string& key) {
  if (remove_spent_run_checkpoint(opts.checkpoint_path, key))
    fmt::print(stderr, "granchain: --checkpoint {} held the state of this stored run; it was removed\n", opts.checkpoint_path);
}

int execute_run(const std::shared_ptr<RunFlags>& impl_) {
  announce_on_interrupt("nothing was run, stored or written");  // also while waiting for a busy store
  auto& impl = *impl_;
  RunOptions opts;
  const bool json_requested = impl.json_option->count() > 0;
  const bool json_stdout = json_requested && (impl.json_path.empty() || is_standard_output(impl.json_path));
  try {
    std::map<std::string, RawValue> raw;
    if (!impl.config_path.empty()) {
      for (auto& [key, value] : read_config_file(impl.config_path)) {
        if (key == "config") throw InputError(fmt::format("--config: '{}' may not name another config file", impl.config_path));
        raw[key] = value;
        raw[key].source = fmt::format("config file '{}'", impl.config_path);
      }
    }
    for (const auto& [name, opt] : impl.flag_options)
      if (opt->count() > 0) raw[name] = RawValue{impl.flag_values[name], ""};
    opts = resolve_run_options(raw);
    opts.use_db = !impl.no_db;
    if (impl.audit) request_audit(opts);
    // The store is written too: it may not be the config file, nor the JSON the store.
    check_outputs({{"--db", opts.use_db ? opts.db_path : ""},
                   {"--json", json_requested && !json_stdout ? impl.json_path : ""},
                   {"--checkpoint", opts.checkpoint_path}},
                  {{"--config", impl.config_path}});
    if (opts.use_db) ResultsStore::preflight(opts.db_path);
  } catch (const InputError& e) {
    fmt::print(stderr, "granchain: error: {}\n", e.what());
    return kExitBadInput;
  } catch (const StoreError& e) {
    fmt::print(stderr, "granchain: error: {}\n", e.what());
    return kExitBadInput;
  }

  // A run whose identity (every parameter and the seed) is stored already is the same trajectory:
  // it is read back, not run or stored again, so that no analysis can count it twice. An audit
  // asks for the run itself: it runs, and is not stored a second time.
  if (opts.use_db && !opts.spec.engine.audit && std::filesystem::exists(opts.db_path)) {
    std::optional<ResultsStore::ReadBack> stored_run;
    try {
      stored_run = ResultsStore(opts.db_path).read_back_run(opts.spec);
    } catch (const StoreError& e) {
      fmt::print(stderr, "granchain: error: {}; nothing was run or written\n", e.what());
      return kExitStoreFailed;
    }
    if (stored_run) {
      if (!opts.checkpoint_path.empty()) remove_spent_checkpoint(opts, point_key(opts.spec));
      return report_stored_run(impl, opts, *stored_run, json_stdout);
    }
  }

  const bool checkpointing = !opts.checkpoint_path.empty();
  const std::string key = checkpointing ? point_key(opts.spec) : "";
  std::optional<RunCheckpoint> checkpoint;
  if (checkpointing) {
    try {
      checkpoint = checkpoint_to_resume(opts, key);
    } catch (const std::exception& e) {  // CheckpointError, StateArchiveError
      fmt::print(stderr, "granchain: error: --checkpoint: {}; nothing was run or written\n", e.what());
      return kExitBadInput;
    }
  }

  if (checkpointing) record_interrupts();  // stop at the next sample, save, then end by the signal
  else announce_on_interrupt("the run did not finish; nothing was stored or written");
  const bool tty = isatty(STDERR_FILENO) != 0;
  const bool show_progress = impl.progress_lines || (tty && !impl.quiet);
  ProgressPrinter printer(tty);
  RunResult result;
  SavedRunPlace saved{};
  bool any_saved = false;
  try {
    ProgressCallback cb;
    const double print_every = tty ? 0.5 : 10.0;
    if (show_progress) cb = [&printer](const RunProgress& p) { printer(p); };
    RunResumption resumption;
    if (checkpointing) {
      // Called every 0.5 s: a signal is seen within that and a sample; lines are printed as before.
      cb = [&printer, show_progress, print_every, last = -1e300](const RunProgress& p) mutable {
        if (recorded_interrupt() != 0) throw RunCancelled{};
        if (show_progress && p.wall_seconds - last >= print_every) {
          last = p.wall_seconds;
          printer(p);
        }
      };
      resumption.resume_from = checkpoint ? &checkpoint->state : nullptr;
      resumption.every = opts.checkpoint_every;
      resumption.save = [&](const StateArchive& state) {
        write_run_checkpoint(opts.checkpoint_path, {key, code_version(), state});
        saved = saved_run_place(state);
        any_saved = true;
      };
    }
    result = run_driven_column(opts.spec, cb, checkpointing ? 0.5 : print_every, resumption);
    printer.finish();
  } catch (const UnphysicalStateError& e) {
    printer.finish();
    fmt::print(stderr, "granchain: error: the simulation became unphysical: {}; no result was written{}\n", e.what(),
               checkpointing ? fmt::format(" (--checkpoint {} is left as it was last saved)", opts.checkpoint_path) : "");
    return kExitUnphysical;
  } catch (const RunCancelled&) {
    printer.finish();
    const int sig = recorded_interrupt();
    fmt::print(stderr, "\ngranchain: interrupted by {}; the run's state at t = {:.6g} of {:.6g} is saved in {} (the same command "
                       "resumes it); nothing was stored or written\n",
               interrupt_name(sig), saved.t, opts.spec.transient + opts.spec.T, opts.checkpoint_path);
    reraise_interrupt(sig);
  } catch (const OutputError& e) {  // a checkpoint that could not be written
    printer.finish();
    fmt::print(stderr, "granchain: error: {}; the run stopped{}; nothing was stored or written\n", e.what(),
               any_saved ? fmt::format(" (its state at t = {:.6g} is in the checkpoint saved before)", saved.t) : "");
    return kExitStoreFailed;
  }
  if (checkpointing) announce_on_interrupt(fmt::format("the run finished but was not stored or written; --checkpoint {} holds "
                                                       "its state as last saved",
                                                       opts.checkpoint_path));

  // The run's outputs, all or none: the JSON file is written in full (to a temporary file) inside
  // the store's transaction and renamed into place only once the run is stored. Only a target that
  // is not a regular file (a device, a FIFO) or standard output is written after the commit; if
  // that fails the message says that the run is stored.
  nlohmann::json j = run_result_to_json(result);
  std::string stored;
  std::unique_ptr<PendingFile> json_file;
  const bool json_to_file = json_requested && !json_stdout;
  try {
    if (opts.use_db) {
      ResultsStore store(opts.db_path);
      const ResultsStore::Stored id = store.insert_run(result, [&](std::int64_t new_id) {
        j["stored"] = {{"db", opts.db_path}, {"run_id", new_id}};
        if (json_to_file) json_file = std::make_unique<PendingFile>(impl.json_path, j.dump(2) + "\n", "--json");
      });
      if (!id.inserted) {  // another process stored the same trajectory while this one ran
        j["stored"] = {{"db", opts.db_path}, {"run_id", id.id}};
        j["reused"] = true;
        if (json_to_file) json_file = std::make_unique<PendingFile>(impl.json_path, j.dump(2) + "\n", "--json");
      }
      stored = fmt::format("run {} in {}{}", id.id, opts.db_path, id.inserted ? "" : " (stored meanwhile by another process; not stored twice)");
    } else if (json_to_file) {
      json_file = std::make_unique<PendingFile>(impl.json_path, j.dump(2) + "\n", "--json");
    }
  } catch (const std::exception& e) {
    fmt::print(stderr, "granchain: error: {}; nothing was stored or written\n", e.what());
    return kExitStoreFailed;
  }
  const std::string kept = stored.empty() ? "" : fmt::format("; the run is stored ({})", stored);
  if (!stored.empty()) announce_on_interrupt(fmt::format("the run is stored ({}); its other outputs may be missing", stored));
  try {
    if (json_file) {
      json_file->commit();
      stored += (stored.empty() ? "JSON in " : ", JSON in ") + impl.json_path;
    }
    if (json_stdout) write_standard_output(j.dump(2) + "\n");
  } catch (const std::exception& e) {
    fmt::print(stderr, "granchain: error: {}{}\n", e.what(), kept);
    return kExitStoreFailed;
  }
  if (!impl.quiet && !json_stdout) {
    try {
      write_standard_output(run_summary(result, stored));
    } catch (const std::exception& e) {
      fmt::print(stderr, "granchain: error: {}{}\n", e.what(), kept);
      return kExitStoreFailed;
    }
  }
  // The run's outputs are whole: its checkpoint is spent.
  if (checkpointing) {
    std::error_code ec;
    std::filesystem::remove(opts.checkpoint_path, ec);
    if (ec) fmt::print(stderr, "granchain: warning: --checkpoint {} could not be removed: {}\n", opts.checkpoint_path, ec.message());
  }
  return kExitOk;
}

}  // namespace

}  // namespace granchain
