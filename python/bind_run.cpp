// granchain.run: one driven column (simulation/driven_run.hpp) from keyword arguments validated by
// the CLI's own resolve_run_options, the result as a dict with numpy profiles.
#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

#include "bindings.hpp"
#include "config/input_error.hpp"
#include "config/run_key.hpp"
#include "config/run_options.hpp"
#include "model/state_archive.hpp"
#include "simulation/cancellation.hpp"
#include "store/output_file.hpp"
#include "store/results_store.hpp"
#include "store/run_checkpoint.hpp"
#include "store/run_json.hpp"
#include "simulation/run_verdicts.hpp"
#include "version.hpp"

namespace granchain::python {

namespace {

py::dict estimate_halves(const StationarityCheck& c) {
  py::dict d;
  d["first"] = c.first.value;
  d["first_err"] = c.first.error;
  d["second"] = c.second.value;
  d["second_err"] = c.second.error;
  d["z"] = c.z;
  d["z_settled"] = c.z_settled;
  d["stationary"] = c.stationary;
  return d;
}

// The set-up and every stored parameter of the table (config/run_options.hpp) under its store
// column's name; k is inf for the hard-sphere engine; None where the store keeps NULL (a
// parameter that does not act: tc of a soft engine, the plate's under the thermal floor).
py::dict spec_dict(const RunSpec& s) {
  py::dict p;
  p["setup"] = "driven_column";
  const auto& stored = stored_run_parameters();
  const auto values = stored_values(s);
  for (std::size_t i = 0; i < stored.size(); ++i) {
    const Parameter& q = *stored[i].parameter;
    const TypedValue& v = values[i].value;
    const py::str key(q.store_column);
    if (stored[i].nullable && !values[i].acts) p[key] = py::none();
    else if (const auto* t = std::get_if<std::string>(&v)) p[key] = *t;
    else if (const auto* n = std::get_if<long long>(&v)) p[key] = unsigned_integer(q) ? py::int_(static_cast<std::uint64_t>(*n)) : py::int_(*n);
    else p[key] = std::get<double>(v);
  }
  return p;
}

// One value per particle (i = 1..N, 1 at the bottom), or per pair.
template <class Item, class Get>
py::array_t<double> per_particle(const std::vector<Item>& profiles, Get get) {
  py::array_t<double> a(static_cast<py::ssize_t>(profiles.size()));
  auto w = a.mutable_unchecked<1>();
  for (std::size_t i = 0; i < profiles.size(); ++i) w(static_cast<py::ssize_t>(i)) = get(profiles[i]);
  return a;
}

}  // namespace

// The result: every scalar of `granchain run --json` (non-finite values kept as inf and nan), the
// profiles as numpy arrays, and the CLI's JSON text itself.
py::dict run_result_dict(const RunResult& r, const std::string& json_text, const std::string& db, std::int64_t run_id) {
  py::dict d;
  d["parameters"] = spec_dict(r.spec);
  d["n_coll"] = r.n_coll.value;
  d["n_coll_err"] = r.n_coll.error;
  d["n_coll_blocks"] = r.n_coll.blocks;
  d["n_coll_converged"] = r.n_coll.converged;
  d["floor_rate"] = r.floor_rate.value;
  d["floor_rate_err"] = r.floor_rate.error;
  d["pp_rate"] = r.pp_rate.value;
  d["pp_rate_err"] = r.pp_rate.error;
  d["particle_collisions"] = r.particle_collisions;
  d["floor_hits"] = r.floor_hits;
  d["stationary"] = r.stationary();
  py::dict st;
  st["n_coll"] = estimate_halves(r.n_coll_halves);
  st["mean_height"] = estimate_halves(r.height_halves);
  d["stationarity"] = st;
  // The blocking curves behind the errors: per level, blocks, standard error and lag-1 autocorrelation.
  const auto curve = [](const std::vector<BlockingLevel>& c) {
    py::array_t<std::int64_t> blocks(static_cast<py::ssize_t>(c.size()));
    py::array_t<double> error(static_cast<py::ssize_t>(c.size())), lag1(static_cast<py::ssize_t>(c.size()));
    for (std::size_t l = 0; l < c.size(); ++l) {
      blocks.mutable_at(static_cast<py::ssize_t>(l)) = c[l].blocks;
      error.mutable_at(static_cast<py::ssize_t>(l)) = c[l].error;
      lag1.mutable_at(static_cast<py::ssize_t>(l)) = c[l].lag1;
    }
    py::dict x;
    x["blocks"] = blocks;
    x["error"] = error;
    x["lag1"] = lag1;
    return x;
  };
  py::dict blocking;
  blocking["n_coll"] = curve(r.n_coll_blocking);
  blocking["mean_height"] = curve(r.height_blocking);
  d["blocking"] = blocking;
  d["warnings"] = run_warnings(r);  // the verdicts; the package raises each as granchain.QualityWarning
  py::array_t<std::int64_t> index(static_cast<py::ssize_t>(r.profiles.size()));
  for (py::ssize_t i = 0; i < index.shape(0); ++i) index.mutable_at(i) = i + 1;
  d["i"] = index;
  d["z_mean"] = per_particle(r.profiles, [](const ParticleProfile& p) { return p.z_mean.value; });
  d["z_mean_err"] = per_particle(r.profiles, [](const ParticleProfile& p) { return p.z_mean.error; });
  d["z_std"] = per_particle(r.profiles, [](const ParticleProfile& p) { return p.z_std.value; });
  d["z_std_err"] = per_particle(r.profiles, [](const ParticleProfile& p) { return p.z_std.error; });
  d["K"] = per_particle(r.profiles, [](const ParticleProfile& p) { return p.kinetic.value; });
  d["K_err"] = per_particle(r.profiles, [](const ParticleProfile& p) { return p.kinetic.error; });
  // Contact durations (soft spheres), per pair: index 0 the plate's contact, i the pair (i, i+1);
  // mean and longest in units of tau_c, the fraction of the window in contact (and in contacts
  // longer than long_contact tau_c: long_fraction), the histogram of
  // log2(duration / tau_c) in quarter octaves from bin first_bin (edges 2^(log2_min + b / 4)).
  if (!r.contacts.empty()) {
    py::dict c;
    c["contacts"] = per_particle(r.contacts, [](const PairContacts& p) { return static_cast<double>(p.contacts); });
    c["mean"] = per_particle(r.contacts, [](const PairContacts& p) { return p.mean; });
    c["longest"] = per_particle(r.contacts, [](const PairContacts& p) { return p.longest; });
    c["contact_fraction"] = per_particle(r.contacts, [](const PairContacts& p) { return p.contact_fraction; });
    c["long_fraction"] = per_particle(r.contacts, [](const PairContacts& p) { return p.long_fraction; });
    c["long_contact"] = ContactDurations::kLongContact;
    c["open_at_end"] = per_particle(r.contacts, [](const PairContacts& p) { return static_cast<double>(p.open_at_end); });
    c["began_before"] = per_particle(r.contacts, [](const PairContacts& p) { return static_cast<double>(p.began_before); });
    py::list hist;
    for (const PairContacts& p : r.contacts) hist.append(py::make_tuple(p.first_bin, p.histogram));
    c["histogram"] = hist;
    c["log2_min"] = ContactDurations::kLog2Min;
    c["bins_per_octave"] = ContactDurations::kBinsPerOctave;
    d["contacts"] = c;
  }
  py::dict derived;
  derived["D"] = r.law.D;
  derived["tau_c"] = r.law.tau_c;
  derived["dt"] = r.time_step > 0 ? py::object(py::float_(r.time_step)) : py::object(py::none());  // None: event-driven
  derived["sample_interval"] = r.sample_interval;
  derived["samples"] = r.samples;
  d["derived"] = derived;
  py::dict cost;
  cost["steps"] = r.steps;
  cost["events"] = r.events;
  cost["wall_seconds"] = r.wall_seconds;
  cost["cpu_seconds"] = r.cpu_seconds;
  d["cost"] = cost;
  if (r.spec.engine.audit) {
    py::dict audit;
    audit["instants"] = r.audit_instants;
    audit["values"] = r.audit_values;
    d["audit"] = audit;
  }
  d["code_version"] = code_version();
  if (db.empty()) {
    d["stored"] = py::none();
  } else {
    py::dict stored;
    stored["db"] = db;
    stored["run_id"] = run_id;
    d["stored"] = stored;
  }
  d["json"] = json_text;
  return d;
}

namespace {

// Called about every half second of wall time from inside the run (without the GIL): takes the
// GIL, lets Ctrl-C (KeyboardInterrupt) and an exception from the user's callback end the run. With
// a checkpoint (save_on_interrupt) Ctrl-C cancels the run, which saves its state, and the
// KeyboardInterrupt is raised after that.
ProgressCallback progress_callback(const std::optional<py::object>& user, bool save_on_interrupt = false) {
  return [user, save_on_interrupt](const RunProgress& p) {
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) {
      if (!save_on_interrupt || !PyErr_ExceptionMatches(PyExc_KeyboardInterrupt)) throw py::error_already_set();
      PyErr_Clear();  // raised again, saying where the state is, once it is saved
      throw RunCancelled{};
    }
    if (!user) return;
    py::dict d;
    d["t"] = p.t;
    d["t_total"] = p.t_total;
    d["in_transient"] = p.in_transient;
    d["steps"] = p.steps;
    d["events"] = p.events;
    d["wall_seconds"] = p.wall_seconds;
    try {
      (*user)(d);
    } catch (py::error_already_set& e) {  // Ctrl-C while the callback ran is Ctrl-C all the same
      if (!save_on_interrupt || !e.matches(PyExc_KeyboardInterrupt)) throw;
      throw RunCancelled{};
    }
  };
}

// A UserWarning (an error where warnings are turned into errors).
void warn(const std::string& message) {
  if (PyErr_WarnEx(PyExc_UserWarning, message.c_str(), 1) != 0) throw py::error_already_set();
}

py::dict run_keywords(const py::kwargs& kwargs) {
  auto args = flag_arguments(kwargs);
  const std::optional<py::object> audit = take(args, "audit");
  const std::optional<py::object> progress = take(args, "progress");
  if (progress && !PyCallable_Check(progress->ptr()))
    throw py::value_error("progress: expected a callable taking one dict (or None)");
  const std::optional<py::object> db = take(args, "db");

  std::map<std::string, RawValue> raw;
  for (const auto& [name, value] : args) raw[name] = keyword_value(value, find_parameter(run_parameters(), name));
  if (db) raw["db"] = RawValue{path_text(*db, "db"), ""};
  RunOptions opts = resolve_run_options(raw);  // InputError -> ValueError, the CLI's message
  opts.use_db = db.has_value();
  if (audit && !audit->is_none() && !PyBool_Check(audit->ptr()))
    throw InputError(fmt::format("--audit: audit = {} is not True or False", std::string(py::repr(*audit))));
  if (audit && !audit->is_none() && audit->cast<bool>()) request_audit(opts);
  check_outputs({{"--db", opts.use_db ? opts.db_path : ""}, {"--checkpoint", opts.checkpoint_path}}, {});  // not one file for both
  if (opts.use_db) {
    try {
      ResultsStore::preflight(opts.db_path);
    } catch (const StoreError& e) {
      throw InputError(e.what());  // the CLI's exit 2: bad input, nothing run (ValueError)
    }
  }

  // The same rule as `granchain run`: a run whose identity (every parameter and the seed) is
  // stored already is read back with a warning, never run or stored twice.
  if (opts.use_db && !opts.spec.engine.audit && std::filesystem::exists(opts.db_path)) {
    std::optional<ResultsStore::ReadBack> stored;
    {
      py::gil_scoped_release nogil;
      stored = ResultsStore(opts.db_path).read_back_run(opts.spec);
    }
    if (stored) {
      if (!opts.checkpoint_path.empty() && remove_spent_run_checkpoint(opts.checkpoint_path, point_key(opts.spec)))
        warn(fmt::format("checkpoint {} held the state of this stored run; it was removed", opts.checkpoint_path));
      if (PyErr_WarnEx(PyExc_UserWarning,
                   fmt::format("run {} of {} is this run already (the same parameters and seed = {}, so the same "
                               "trajectory); it was read back, not run or stored again; for an independent replica "
                               "pass another seed",
                               stored->id, opts.db_path, opts.spec.seed)
                       .c_str(),
                   1) != 0)
        throw py::error_already_set();  // warnings turned into errors
      py::dict d = run_result_dict(stored->result, stored->json.dump(2), opts.db_path, stored->id);
      d["reused"] = true;
      d["resumed_at"] = py::none();
      return d;
    }
  }

  // With a checkpoint the run resumes from it where it holds this run's state, saves its state
  // every checkpoint_every seconds and on Ctrl-C, and removes it once the result is stored or returned.
  const bool checkpointing = !opts.checkpoint_path.empty();
  const std::string key = checkpointing ? point_key(opts.spec) : "";
  std::optional<RunCheckpoint> checkpoint;
  std::optional<SavedRunPlace> saved;  // where the state in the checkpoint file stands
  if (checkpointing) {
    try {
      checkpoint = read_run_checkpoint_of(opts.checkpoint_path, key);
      if (checkpoint) saved = saved_run_place(checkpoint->state);
    } catch (const std::exception& e) {  // CheckpointError, StateArchiveError: bad input, nothing run
      throw InputError(fmt::format("--checkpoint: {}; nothing was run or written", e.what()));
    }
    if (checkpoint && checkpoint->written_by != code_version())
      warn(fmt::format("checkpoint {} was saved by granchain {}, this is {}: the result is the uninterrupted run's bit for bit only "
                       "if the engine and observers are unchanged",
                       opts.checkpoint_path, checkpoint->written_by, code_version()));
  }
  const ProgressCallback cb = progress_callback(progress, checkpointing);
  const py::object resumed_at = saved ? py::object(py::float_(saved->t)) : py::object(py::none());  // where this call goes on from
  RunResumption resumption;
  if (checkpointing) {
    resumption.resume_from = checkpoint ? &checkpoint->state : nullptr;
    resumption.every = opts.checkpoint_every;
    resumption.save = [&](const StateArchive& state) {
      write_run_checkpoint(opts.checkpoint_path, {key, code_version(), state}, "checkpoint");
      saved = saved_run_place(state);
    };
  }
  RunResult result;
  std::string json_text;
  std::int64_t run_id = 0;
  bool reused = false;
  bool cancelled = false;
  {
    py::gil_scoped_release nogil;
    try {
      result = run_driven_column(opts.spec, cb, 0.5, resumption);
    } catch (const RunCancelled&) {
      cancelled = true;
    }
  }
  if (cancelled) {  // Ctrl-C with a checkpoint: the run saved its state on the way out; the KeyboardInterrupt says where
    const std::string message =
        fmt::format("the run's state at t = {:.6g} of {:.6g} is saved in {}; the same call resumes it (nothing was stored)",
                    saved.value().t, opts.spec.transient + opts.spec.T, opts.checkpoint_path);
    PyErr_SetString(PyExc_KeyboardInterrupt, message.c_str());
    throw py::error_already_set();
  }
  {
    py::gil_scoped_release nogil;
    nlohmann::json j = run_result_to_json(result);
    if (opts.use_db) {
      ResultsStore store(opts.db_path);
      const ResultsStore::Stored s = store.insert_run(result, [&](std::int64_t id) { j["stored"] = {{"db", opts.db_path}, {"run_id", id}}; });
      run_id = s.id;
      reused = !s.inserted;
      if (reused) {
        j["stored"] = {{"db", opts.db_path}, {"run_id", s.id}};
        j["reused"] = true;
      }
    }
    json_text = j.dump(2);
  }
  // The result is whole (and stored): the checkpoint is spent. Ctrl-C after the last report would
  // lose an unstored result with it: then the file is kept, as last saved.
  const bool late_interrupt = checkpointing && PyErr_CheckSignals() != 0;
  if (late_interrupt) {
    if (!PyErr_ExceptionMatches(PyExc_KeyboardInterrupt)) throw py::error_already_set();
    PyErr_Clear();
    if (!opts.use_db) {
      const std::string message =
          saved ? fmt::format("the run finished, but its result is not returned; {} holds its state as last saved (t = {:.6g}), "
                              "from which the same call ends it",
                              opts.checkpoint_path, saved->t)
                : std::string("the run finished, but its result is not returned; no state had been saved yet (the first save "
                              "comes after checkpoint_every seconds)");
      PyErr_SetString(PyExc_KeyboardInterrupt, message.c_str());
      throw py::error_already_set();
    }
  }
  if (checkpointing) {
    std::error_code ec;
    std::filesystem::remove(opts.checkpoint_path, ec);
    if (ec) warn(fmt::format("checkpoint {} could not be removed: {}", opts.checkpoint_path, ec.message()));
  }
  if (late_interrupt) {  // with db: the run is stored
    PyErr_SetString(PyExc_KeyboardInterrupt,
                    fmt::format("the run finished and is stored (run {} in {}); the same call reads it back", run_id, opts.db_path).c_str());
    throw py::error_already_set();
  }
  py::dict d = run_result_dict(result, json_text, opts.use_db ? opts.db_path : "", run_id);
  d["reused"] = reused;
  d["resumed_at"] = resumed_at;
  return d;
}

// Bad input named by the keyword, as a Python caller wrote it (keyword_message).
py::dict run(const py::kwargs& kwargs) {
  try {
    return run_keywords(kwargs);
  } catch (const InputError& e) {
    throw InputError(keyword_message(e.what(), run_parameters(), {"audit", "progress"}));
  }
}

}  // namespace

void bind_run(py::module_& m) {
  m.def("run", &run,
        "Simulate the driven column once (granchain run). Keyword arguments are the flags of `granchain run` "
        "(dt_factor for --dt-factor, sample_interval for --sample-interval), numbers or text; db=PATH stores the "
        "run, audit=True checks the exact engine, progress=callable(dict) is called about every 0.5 s. Bad input "
        "raises ValueError with the CLI's message.");
  m.def("run_parameters", [] { return parameter_list(run_parameters()); },
        "The parameters of run(): name (the CLI flag without --), help text, type, unit (in m, d, g), valid range, "
        "default, the engines that take it (any, soft, hard, time-stepped), whether a sweep takes a list of it, and the "
        "store column that keeps it.");
}

}  // namespace granchain::python
