// granchain.collapse: one collapse count (simulation/collapse_run.hpp) at one (e, k), validated
// by the command's own resolve_collapse_options (config/collapse_options.hpp), per-launch numpy arrays;
// granchain.k_slope: the slope of n_tot against log10 k between two counts of the same launches.
#include <fmt/format.h>
#include <pybind11/numpy.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

#include "bindings.hpp"
#include "config/input_error.hpp"
#include "config/collapse_options.hpp"
#include "store/collapse_json.hpp"
#include "store/results_store.hpp"
#include "theory/collapse_theory.hpp"

namespace granchain::python {

namespace {

struct CollapseRequest {
  CollapseSpec spec;
  std::string db;  // "" : not stored
  bool record = false;
  std::optional<py::object> progress;  // callable(dict), called about every 0.5 s
};

// One e and one k, read and checked by the command's own resolve_collapse_options.
CollapseRequest collapse_request_checked(const py::kwargs& kwargs) {
  auto args = flag_arguments(kwargs);
  CollapseRequest q;
  const std::optional<py::object> db = take(args, "db");
  const std::optional<py::object> record = take(args, "record-collisions");
  q.progress = take(args, "progress");
  if (q.progress && !PyCallable_Check(q.progress->ptr()))
    throw InputError("progress: expected a callable taking one dict (or None)");
  std::map<std::string, RawValue> raw;
  for (const auto& [name, value] : args) raw[name] = keyword_value(value, find_parameter(collapse_parameters(), name));
  // The command's default k is a list; a call counts one k, which a soft engine needs given.
  const EngineInfo* engine = raw.count("engine") ? find_engine(raw.at("engine").text()) : &engines().front();
  if (engine != nullptr && !engine->hard_spheres && !raw.count("k"))
    throw InputError("--k: give the elastic constant (one value per call); valid range: k > 0");
  const CollapseOptions opts = resolve_collapse_options(raw);
  for (const auto& [name, values] : {std::pair<const char*, const std::vector<double>*>{"e", &opts.es}, {"k", &opts.ks}})
    if (values->size() != 1)
      throw InputError(fmt::format("--{} = '{}' holds {} values; granchain.collapse counts one (e, k) per call", name,
                                   raw.at(name).text(), values->size()));
  q.spec = opts.base;
  q.spec.params.e = opts.es.front();
  q.spec.params.k = opts.ks.front();
  if (db) {
    q.db = path_text(*db, "db");
    try {
      ResultsStore::preflight(q.db);
    } catch (const StoreError& err) {
      throw py::value_error(err.what());
    }
  }
  if (record) {
    if (!PyBool_Check(record->ptr()))
      throw InputError(fmt::format("record_collisions = {} is not True or False", std::string(py::repr(*record))));
    q.record = record->cast<bool>();
  }
  if (!q.db.empty()) check_storable(q.spec);
  return q;
}

// Bad input named by the keyword, as a Python caller wrote it (keyword_message).
CollapseRequest collapse_request(const py::kwargs& kwargs) {
  try {
    return collapse_request_checked(kwargs);
  } catch (const InputError& e) {
    throw InputError(keyword_message(e.what(), collapse_parameters(), {"record-collisions", "progress"}));
  }
}

// One numpy column: get(item) of every item (launch outcomes, recorded collisions), in order.
template <class T, class Item, class Get>
py::array_t<T> column(const std::vector<Item>& items, Get get) {
  py::array_t<T> a(static_cast<py::ssize_t>(items.size()));
  auto w = a.template mutable_unchecked<1>();
  for (std::size_t i = 0; i < items.size(); ++i) w(static_cast<py::ssize_t>(i)) = static_cast<T>(get(items[i]));
  return a;
}

py::dict collapse_dict(const CollapseResult& r, const std::vector<CollisionRecord>& recs, bool recorded,
                       const std::string& db, std::int64_t id) {
  const CollapseSpec& s = r.spec;
  py::dict p;
  p["setup"] = setup_name(s.setup);
  p["N"] = s.params.N;
  p["e"] = s.params.e;
  p["k"] = s.params.k;
  p["m"] = s.params.m;
  p["d"] = s.params.d;
  p["a"] = s.launch.a;
  p["v0"] = s.launch.v0;
  p["dv0"] = s.launch.dv0;
  p["stop"] = rule_name(s.rule);
  p["realizations"] = s.realizations;
  p["seed"] = s.seed;
  p["engine"] = engine_name(s.engine.kind);
  p["dt_factor"] = s.engine.dt_factor;
  p["tc"] = s.engine.hard.tc;
  p["collapse_collisions"] = s.engine.hard.collapse_collisions;
  p["collapse_time"] = s.engine.hard.collapse_time;
  p["threads"] = s.threads;
  py::dict d;
  d["parameters"] = p;
  d["D"] = r.law.D;
  d["tau_c"] = r.law.tau_c;
  d["n_tot"] = r.n_tot_mean;
  d["n_tot_err"] = r.n_tot_error;
  d["n_tot_min"] = r.n_tot_min;
  d["n_tot_max"] = r.n_tot_max;
  d["collapsed"] = r.collapsed;
  d["collisions"] = r.collisions;
  d["grazing_contacts"] = r.grazing_contacts;
  d["held_contacts"] = r.held_contacts;
  d["one_body"] = r.one_body;
  d["wall_seconds"] = r.wall_seconds;
  py::dict per;
  const auto& o = r.outcomes;
  per["n_tot"] = column<std::int64_t>(o, [](const RealizationOutcome& x) { return x.n_tot(); });
  per["particle_collisions"] = column<std::int64_t>(o, [](const RealizationOutcome& x) { return x.particle_collisions; });
  per["wall_hits"] = column<std::int64_t>(o, [](const RealizationOutcome& x) { return x.wall_hits; });
  per["collapsed"] = column<bool>(o, [](const RealizationOutcome& x) { return x.collapsed; });
  per["t_stop"] = column<double>(o, [](const RealizationOutcome& x) { return x.t_stop; });
  per["grazing_contacts"] = column<std::int64_t>(o, [](const RealizationOutcome& x) { return x.grazing_contacts; });
  per["held_contacts"] = column<std::int64_t>(o, [](const RealizationOutcome& x) { return x.held_contacts; });
  per["one_body"] = column<bool>(o, [](const RealizationOutcome& x) { return x.one_body; });
  d["per_realization"] = per;
  if (recorded) {
    py::dict c;  // one entry per collision, as `granchain collapse --events` writes them
    c["realization"] = column<std::int32_t>(recs, [](const CollisionRecord& x) { return x.realization; });
    c["collision"] = column<std::int64_t>(recs, [](const CollisionRecord& x) { return x.index; });
    c["t_begin"] = column<double>(recs, [](const CollisionRecord& x) { return x.t_begin; });
    c["t_end"] = column<double>(recs, [](const CollisionRecord& x) { return x.t_end; });
    c["i"] = column<std::int32_t>(recs, [](const CollisionRecord& x) { return x.i; });
    c["j"] = column<std::int32_t>(recs, [](const CollisionRecord& x) { return x.i + 1; });
    c["speed_in"] = column<double>(recs, [](const CollisionRecord& x) { return x.speed_in; });
    c["speed_out"] = column<double>(recs, [](const CollisionRecord& x) { return x.speed_out; });
    d["collisions_log"] = c;
  }
  if (db.empty()) {
    d["stored"] = py::none();
  } else {
    py::dict st;
    st["db"] = db;
    st["collapse_run_id"] = id;
    d["stored"] = st;
  }
  d["json"] = collapse_result_to_json(r).dump(2);
  return d;
}

// The count runs on a thread of its own while this one watches for Ctrl-C (run_interruptible): an
// interrupted count returns the launches finished before the first unfinished one (complete
// False; not stored), marked interrupted: the package raises granchain.Interrupted holding it.
py::dict collapse(const py::kwargs& kwargs) {
  const CollapseRequest q = collapse_request(kwargs);
  CollapseResult result;
  std::vector<CollisionRecord> recs;
  std::int64_t id = 0;
  std::atomic<bool> cancel{false};
  std::atomic<int> launches_done{0};
  std::atomic<std::uint64_t> collisions{0};
  const auto start = std::chrono::steady_clock::now();
  std::function<void()> progress;
  if (q.progress)
    progress = [&] {
      py::dict d;
      d["done"] = launches_done.load();
      d["total"] = q.spec.realizations;
      d["collisions"] = collisions.load();
      d["elapsed"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      (*q.progress)(d);
    };
  const auto work = [&] {
    CollisionLog log;
    if (q.record) log = [&recs](const std::vector<CollisionRecord>& r) { recs.insert(recs.end(), r.begin(), r.end()); };
    // Progress counts launches done, those carried over from an earlier sitting included (they are
    // not reported one by one, and launches finish out of order).
    const LaunchProgress on_launch = [&](int, std::uint64_t c) {
      ++launches_done;
      collisions += c;
    };
    if (q.db.empty() || q.record) {
      result = run_collapse(q.spec, log, on_launch, {}, &cancel);
      if (!q.db.empty() && !result.interrupted) id = ResultsStore(q.db).insert_collapse(result);
      return;
    }
    // With a store and no records the count is carried over sittings (ResultsStore::launch_checkpoint):
    // an interrupted count keeps its launches there, and the same call continues from them. A count
    // stored whole already is stored again as the same row (insert_collapse).
    ResultsStore store(q.db);
    const LaunchCheckpoint checkpoint = store.launch_checkpoint(q.spec);
    launches_done = static_cast<int>(checkpoint.done.size());
    result = run_collapse(q.spec, log, on_launch, {}, &cancel, &checkpoint);
    if (!result.interrupted) id = store.insert_collapse(result);
  };
  std::optional<py::error_already_set> stop = run_interruptible(cancel, work, progress);
  if (stop && !stop->matches(PyExc_KeyboardInterrupt)) throw std::move(*stop);  // the progress callback's own error
  // Ctrl-C: interrupted, whether or not the count had finished (then it is whole, and stored).
  py::dict d = collapse_dict(result, recs, q.record, q.db, id);
  d["interrupted"] = stop.has_value();
  d["complete"] = !result.interrupted;
  return d;
}

// A CollapseResult rebuilt from a dict of collapse(): what k_slope reads.
CollapseResult from_dict(const py::dict& d) {
  CollapseResult r;
  const py::dict p = d["parameters"];
  r.spec.params.N = p["N"].cast<int>();
  r.spec.params.e = p["e"].cast<double>();
  r.spec.params.k = p["k"].cast<double>();
  r.spec.setup = p["setup"].cast<std::string>() == "wall" ? CollapseSetup::Wall : CollapseSetup::FreeSpace;
  r.n_tot_mean = d["n_tot"].cast<double>();
  r.n_tot_error = d["n_tot_err"].cast<double>();
  const py::dict per = d["per_realization"];
  const auto pc = per["particle_collisions"].cast<py::array_t<std::int64_t, py::array::forcecast>>();
  const auto wh = per["wall_hits"].cast<py::array_t<std::int64_t, py::array::forcecast>>();
  const auto co = per["collapsed"].cast<py::array_t<bool, py::array::forcecast>>();
  if (pc.size() != wh.size() || pc.size() != co.size()) throw py::value_error("k_slope: per_realization arrays differ in length");
  for (py::ssize_t i = 0; i < pc.size(); ++i) {
    RealizationOutcome o;
    o.particle_collisions = static_cast<std::uint64_t>(pc.at(i));
    o.wall_hits = static_cast<std::uint64_t>(wh.at(i));
    o.collapsed = co.at(i);
    r.outcomes.push_back(o);
  }
  return r;
}

py::dict slope(const py::dict& a, const py::dict& b) {
  const py::dict pa = a["parameters"], pb = b["parameters"];
  for (const char* key : {"setup", "N", "e", "a", "v0", "dv0", "stop", "realizations", "seed", "engine", "dt_factor", "tc"}) {
    if (!pa[key].equal(pb[key]))
      throw py::value_error(fmt::format("k_slope: the two counts must be the same launches at two k; they differ in {} "
                                        "({} and {})", key, std::string(py::repr(pa[key])), std::string(py::repr(pb[key]))));
  }
  const CollapseResult ra = from_dict(a), rb = from_dict(b);
  if (!(std::isfinite(ra.spec.params.k) && std::isfinite(rb.spec.params.k) && ra.spec.params.k != rb.spec.params.k))
    throw py::value_error("k_slope: needs two counts at two different finite k");
  const KSlope s = k_slope(ra, rb);
  const bool theory_ok = ra.spec.params.N == 3 && ra.spec.setup == CollapseSetup::FreeSpace && s.e < theory::ec3();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  py::dict d;
  d["e"] = s.e;
  d["k1"] = s.k1;
  d["k2"] = s.k2;
  d["slope_per_log10_k"] = s.per_log10_k;
  d["error"] = s.error;
  d["launches"] = s.launches;
  d["alpha"] = s.alpha;
  d["alpha_error"] = s.alpha_error;
  d["theory_eq_ntot_log"] = theory_ok ? std::log(10.0) * theory::ntot_slope_per_ln_k(s.e) : nan;
  d["theory_all_collisions"] = theory_ok ? std::log(10.0) * theory::collisions_slope_per_ln_k(s.e) : nan;
  return d;
}

}  // namespace

void bind_collapse(py::module_& m) {
  m.def("collapse", &collapse,
        "Count the collisions of an inelastic collapse at one (e, k) over random launches (granchain collapse). "
        "Keyword arguments are the flags of `granchain collapse` with one e and one k (k left out for "
        "engine='hard'); db=PATH stores the count, record_collisions=True returns every collision. Bad input "
        "raises ValueError with the CLI's message.");
  m.def("collapse_parameters", [] { return parameter_list(collapse_parameters()); },
        "The parameters of collapse(), as run_parameters() gives run()'s (e and k: one value per call).");
  m.def("k_slope", &slope, py::arg("a"), py::arg("b"),
        "Slope of n_tot against log10 k between two collapse() results of the same launches at k1 and k2, paired "
        "over launches, with alpha = d ln n_tot / d ln k and, for N = 3 in free space below e_c(3), the theory's slopes.");
}

}  // namespace granchain::python
