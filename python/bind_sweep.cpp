// granchain.sweep: a grid of driven-column runs, the points, seeds and keys of `granchain sweep`
// (sweep/sweep_grid.hpp), run on threads by its SweepRunner while the calling thread shows progress
// and watches for Ctrl-C; with db=PATH the points the store holds are read back, not run again, and
// each finished point is stored at once (resume by calling again).
#include <fmt/format.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <optional>
#include <thread>
#include <unordered_set>

#include "bindings.hpp"
#include "config/input_error.hpp"
#include "config/run_options.hpp"
#include "config/value_list.hpp"
#include "store/output_file.hpp"
#include "provenance.hpp"
#include "simulation/driven_run.hpp"
#include "store/results_store.hpp"
#include "store/run_json.hpp"
#include "sweep/sweep_grid.hpp"
#include "sweep/sweep_runner.hpp"

namespace granchain::python {

namespace {

bool is_grid(const std::string& name) {
  const auto& g = sweep_grid_parameters();
  return std::find(g.begin(), g.end(), name) != g.end();
}

// A grid axis as the sweep's text: a str as given ("0.8:0.9:0.01"), a number, or any sequence of
// numbers or names (a list, a tuple, a numpy array) joined by commas, each number exactly.
RawValue axis_value(const py::handle& value, const Parameter* p) {
  if (py::isinstance<py::str>(value) || !py::hasattr(value, "__iter__") || (py::hasattr(value, "ndim") && value.attr("ndim").cast<int>() == 0))
    return keyword_value(value, p);
  std::string text;
  for (const py::handle item : value) {
    const RawValue v = keyword_value(item, p);
    text += (text.empty() ? "" : ",") + v.text();
  }
  if (text.empty()) throw InputError(fmt::format("--{}: the list is empty; give at least one value", p->name));
  return RawValue{text, ""};
}

struct SweepRequest {
  SweepDefinition def;
  std::string db;  // "": nothing stored
  int threads = 0;
  std::optional<py::object> progress;
  std::optional<std::string> checkpoint_dir;  // as `sweep --checkpoint-dir`
  std::optional<RawValue> checkpoint_every;
};

SweepRequest sweep_request_checked(const py::kwargs& kwargs) {
  auto args = flag_arguments(kwargs);
  SweepRequest q;
  q.progress = take(args, "progress");
  if (q.progress && !PyCallable_Check(q.progress->ptr())) throw InputError("progress: expected a callable taking one dict (or None)");
  if (const auto db = take(args, "db")) {
    q.db = path_text(*db, "db");
    try {
      ResultsStore::preflight(q.db);
    } catch (const StoreError& e) {
      throw InputError(e.what());
    }
  }
  const auto integer = [&](const char* name, long long lo, long long hi) -> std::optional<long long> {
    const auto v = take(args, name);
    if (!v) return std::nullopt;
    return parse_integer_in(keyword_value(*v, nullptr).text(), std::string("--") + name, lo, hi);
  };
  if (const auto r = integer("replicas", 1, 1000000)) q.def.replicas = static_cast<int>(*r);
  if (const auto t = integer("threads", 1, 1024)) q.threads = static_cast<int>(*t);
  if (const auto s = integer("seed", 0, 9223372036854775807LL)) q.def.base_seed = static_cast<std::uint64_t>(*s);
  if (const auto dir = take(args, "checkpoint-dir")) q.checkpoint_dir = path_text(*dir, "checkpoint_dir", "folder name");
  if (const auto every = take(args, "checkpoint-every"))
    q.checkpoint_every = keyword_value(*every, find_parameter(run_parameters(), "checkpoint-every"));
  for (const auto& [name, value] : args) {
    const Parameter* p = find_parameter(run_parameters(), name);
    if (p == nullptr || !(p->uses & kUseSweep))
      throw InputError(fmt::format("--{}: sweep takes no such parameter; valid: {}, replicas, threads, progress, checkpoint-dir", name,
                                   parameter_names(run_parameters(), kUseSweep)));
    q.def.raw[name] = is_grid(name) ? axis_value(value, p) : keyword_value(value, p);
  }
  if (q.threads == 0) q.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return q;
}

py::dict progress_dict(const SweepProgress& p, std::size_t reused) {
  py::dict d;
  d["done"] = p.done;
  d["failed"] = p.failed;
  d["total"] = p.total;
  d["reused"] = reused;
  d["elapsed"] = p.elapsed;
  d["eta"] = p.eta;
  d["collisions_per_second"] = p.collisions_per_second;
  return d;
}

py::dict sweep(const py::kwargs& kwargs) {
  SweepRequest q;
  std::vector<SweepPoint> points;
  std::unique_ptr<SweepCheckpoints> checkpoints;
  try {
    q = sweep_request_checked(kwargs);
    points = build_sweep_points(q.def);
    checkpoints = make_sweep_checkpoints(q.checkpoint_dir ? &*q.checkpoint_dir : nullptr, q.checkpoint_every ? &*q.checkpoint_every : nullptr,
                                         points);
    if (checkpoints) {
      checkpoints->announce_resumes(false);  // counted in the result's `resumed` instead
      try {
        checkpoints->create_folder();
      } catch (const OutputError& e) {
        throw InputError(e.what());  // as the CLI: bad input, nothing run
      }
    }
  } catch (const InputError& e) {
    throw InputError(keyword_message(e.what(), run_parameters(), {"replicas", "threads", "progress", "checkpoint-dir"}));
  }
  set_parallelism(q.threads, 1);

  // What the store holds already is read back in point order; the rest is run.
  std::vector<std::optional<RunResult>> results(points.size());
  std::vector<std::int64_t> ids(points.size(), 0);
  std::vector<std::string> json_texts(points.size());
  std::vector<char> reused(points.size(), 0);
  std::unique_ptr<ResultsStore> store;
  std::vector<std::size_t> todo;
  std::vector<std::pair<std::string, std::string>> failures;
  {
    py::gil_scoped_release nogil;
    std::unordered_set<std::string> stored;
    if (!q.db.empty()) {
      store = std::make_unique<ResultsStore>(q.db);
      stored = store->point_keys();
      // Hard spheres that collapsed at a point in an earlier sweep: failed, and not run again.
      const auto collapsed = store->collapsed_points();
      for (const SweepPoint& p : points)
        if (const auto it = collapsed.find(p.key); it != collapsed.end()) {
          stored.insert(p.key);
          failures.emplace_back(p.key, it->second.message + " (stored as a collapse)");
        }
    }
    todo = points_to_run(points, stored);
    std::vector<char> to_run(points.size(), 0);
    for (std::size_t i : todo) to_run[i] = 1;
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (to_run[i]) continue;
      if (auto back = store->read_back_run(points[i].spec)) {
        ids[i] = back->id;
        json_texts[i] = back->json.dump(2);
        results[i] = std::move(back->result);
        reused[i] = 1;
      }
    }
  }
  std::size_t n_reused = static_cast<std::size_t>(std::count(reused.begin(), reused.end(), 1));
  // Points that go on from a saved state, and the time each goes on from (a file that does not read
  // as the point's state is no resumption: the point starts anew, as run_sweep_point says).
  std::vector<std::optional<double>> resumed_at(points.size());
  std::size_t resumed = 0;
  if (checkpoints) {
    py::gil_scoped_release nogil;
    remove_spent_states(*checkpoints, points, todo);
    for (std::size_t i : todo) {
      try {
        if (const auto saved = checkpoints->saved(points[i])) resumed_at[i] = saved_run_place(saved->state).t;
      } catch (const std::exception&) {  // CheckpointError, StateArchiveError: the sweep warns when it reaches the point
      }
      resumed += resumed_at[i] ? 1 : 0;
    }
  }

  std::size_t inserted = 0;
  const PointSink sink = [&](const SweepPoint& p, const RunResult* r, const std::string& error, const InelasticCollapseError* collapse) {
    const std::size_t i = static_cast<std::size_t>(&p - points.data());
    if (!r) {
      if (collapse && store) store->insert_collapsed_point(p.key, ResultsStore::collapsed_point(*collapse));
      failures.emplace_back(p.key, error);
      return;
    }
    nlohmann::json j = run_result_to_json(*r);
    if (store) {
      const ResultsStore::Stored s = store->insert_sweep_point(*r, p.key, q.def.base_seed, p.replica);
      inserted += s.inserted;
      ids[i] = s.id;
      j["stored"] = {{"db", q.db}, {"run_id", s.id}};
    }
    json_texts[i] = j.dump(2);
    results[i] = *r;
  };
  SweepRunner runner(points, todo, sink);
  runner.set_point_progress_every(0.2);  // a cancel reaches a running point within about this
  std::atomic<bool> cancel{false};
  runner.watch(&cancel);  // with checkpoints the running points save their states and stop
  if (checkpoints) runner.set_checkpoints(checkpoints.get());
  std::function<void()> progress;
  if (q.progress) progress = [&] { (*q.progress)(progress_dict(runner.progress(), n_reused)); };
  std::optional<py::error_already_set> stop;
  try {
    stop = run_interruptible(cancel, [&] { runner.run(q.threads); }, progress);
  } catch (const OutputError& e) {  // a point's state could not be saved: the sweep stopped (OSError)
    throw OutputError(fmt::format("{}; the sweep stopped, the points finished are {} and the states saved before are kept in {}",
                                  keyword_message(e.what(), run_parameters(), {"checkpoint-dir"}),
                                  store ? "stored in " + q.db : std::string("lost (no db)"), checkpoints ? checkpoints->dir() : ""));
  }
  if (stop && !stop->matches(PyExc_KeyboardInterrupt)) throw std::move(*stop);  // the progress callback's own error
  if (q.progress && !stop) {
    SweepProgress p = runner.progress();
    p.final = true;
    (*q.progress)(progress_dict(p, n_reused));
  }

  py::list out;
  for (std::size_t i : table_order(points)) {
    if (!results[i]) continue;
    py::dict d = run_result_dict(*results[i], json_texts[i], store ? q.db : "", ids[i]);
    d["reused"] = static_cast<bool>(reused[i]);
    d["resumed_at"] = resumed_at[i] ? py::object(py::float_(*resumed_at[i])) : py::object(py::none());
    d["replica"] = points[i].replica;
    d["key"] = points[i].key;
    out.append(d);
  }
  py::list failed_points;
  for (const auto& [key, error] : failures) failed_points.append(py::make_tuple(key, error));
  py::dict d;
  d["results"] = out;
  d["failed"] = failed_points;
  d["points"] = points.size();
  d["stored_now"] = inserted;
  d["reused"] = n_reused;
  d["db"] = store ? py::object(py::str(q.db)) : py::object(py::none());
  d["base_seed"] = q.def.base_seed;
  d["interrupted"] = stop.has_value();
  d["not_run"] = points.size() - out.size() - failures.size();
  d["checkpoint_dir"] = checkpoints ? py::object(py::str(checkpoints->dir())) : py::object(py::none());
  d["resumed"] = resumed;
  d["saved"] = runner.saved();
  return d;
}

}  // namespace

void bind_sweep(py::module_& m) {
  m.def("sweep", &sweep,
        "Run a grid of driven-column runs (granchain sweep): grid parameters take lists; replicas, seed (base), "
        "threads, db=PATH (resume: stored points are read back), progress=callable(dict). Returns a dict with results "
        "(one dict per point, in the sweep's order), failed, interrupted.");
}

}  // namespace granchain::python

