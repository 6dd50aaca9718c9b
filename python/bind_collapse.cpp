// granchain.collapse: one collapse count (simulation/collapse_run.hpp) at one (e, k), validated
// with the messages of `granchain collapse` (cli/collapse_command.cpp), per-launch numpy arrays;
// granchain.k_slope: the slope of n_tot against log10 k between two counts of the same launches.
#include <fmt/format.h>
#include <pybind11/numpy.h>

#include <charconv>
#include <cmath>
#include <limits>
#include <thread>
#include <vector>

#include "bindings.hpp"
#include "config/input_error.hpp"
#include "config/value_list.hpp"
#include "config/run_options.hpp"
#include "store/collapse_json.hpp"
#include "store/results_store.hpp"
#include "theory/collapse_theory.hpp"

namespace granchain::python {

namespace {

// A number from a keyword argument, read as the CLI reads flag text.
double real_arg(const std::string& name, const py::object& v) {
  const std::string t = flag_text(v);
  double x = 0;
  const auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), x);
  if (!t.empty() && ec == std::errc::result_out_of_range && p == t.data() + t.size())
    throw InputError(fmt::format("--{} = '{}' is out of range of a double", name, t));
  if (t.empty() || ec != std::errc() || p != t.data() + t.size())
    throw InputError(fmt::format("--{} = '{}' is not a number", name, t));
  return x;
}

std::string text_arg(const std::string& name, const py::object& v) {
  if (!PyUnicode_Check(v.ptr())) throw InputError(fmt::format("--{} = {} is not a name", name, std::string(py::repr(v))));
  return v.cast<std::string>();
}

struct CollapseRequest {
  CollapseSpec spec;
  std::string db;  // "" : not stored
  bool record = false;
};

// The checks and messages of execute_collapse, for one e and one k.
CollapseRequest collapse_request(const py::kwargs& kwargs) {
  auto args = flag_arguments(kwargs);
  CollapseRequest q;
  CollapseSpec& s = q.spec;
  auto real = [&](const char* name, double dflt) { auto v = take(args, name); return v ? real_arg(name, *v) : dflt; };
  // Integers as the CLI reads them (config/value_list.hpp): decimal, whole, in range, the same message.
  auto integer = [&](const char* name, long long dflt, long long lo, long long hi) {
    auto v = take(args, name);
    return v ? parse_integer_in(flag_text(*v), std::string("--") + name, lo, hi) : dflt;
  };
  auto text = [&](const char* name, const char* dflt) { auto v = take(args, name); return v ? text_arg(name, *v) : std::string(dflt); };

  const long long N = integer("N", 3, 2, 100000);
  const double e = real("e", 0.03);
  if (!(e > 0 && e <= 1)) throw InputError(fmt::format("--e: {} is out of range; valid range: 0 < e <= 1", e));
  const std::string engine_text = text("engine", engines().front().name);
  const EngineInfo* engine = find_engine(engine_text);
  if (engine == nullptr) throw InputError(fmt::format("--engine = '{}' is not an engine; valid: {}", engine_text, engine_name_list()));
  const bool hard = engine->hard_spheres;
  const auto k_arg = take(args, "k");
  double k = std::numeric_limits<double>::infinity();
  if (hard) {
    if (k_arg) throw InputError("--k: the hard-sphere engine has k = infinity; leave --k out");
  } else {
    if (!k_arg) throw InputError("--k: give the elastic constant (one value per call); valid range: k > 0");
    k = real_arg("k", *k_arg);
    if (!(k > 0 && std::isfinite(k))) throw InputError(fmt::format("--k: {} is out of range; valid range: k > 0", k));
  }
  const auto tc_arg = take(args, "tc");
  if (!hard && tc_arg) throw InputError("--tc: the TC model belongs to --engine hard");
  const std::string setup = text("setup", "free");
  if (setup != "free" && setup != "wall") throw InputError(fmt::format("--setup = '{}'; valid: free, wall", setup));
  s.setup = setup == "free" ? CollapseSetup::FreeSpace : CollapseSetup::Wall;
  const std::string stop = text("stop", s.setup == CollapseSetup::FreeSpace ? "ends" : "strict");
  if (stop != "ends" && stop != "strict") throw InputError(fmt::format("--stop = '{}'; valid: ends, strict", stop));
  s.rule = stop == "ends" ? StopRule::Ends : StopRule::Strict;
  if (s.rule == StopRule::Ends && s.setup == CollapseSetup::Wall)
    throw InputError("--stop = ends compares the end particles in free space; on a wall use --stop strict");
  const double a = real("a", 1.0), v0 = real("v0", 1.0), dv0 = real("dv0", 0.1);
  if (!(a >= 0 && std::isfinite(a))) throw InputError(fmt::format("--a = {} is out of range; valid range: a >= 0", a));
  if (!(v0 > 0 && std::isfinite(v0))) throw InputError(fmt::format("--v0 = {} is out of range; valid range: v0 > 0", v0));
  check_collapse_launch(static_cast<int>(N), a, v0, ChainParameters{}.d);
  if (!hard) check_collapse_contact_time(k, e, ChainParameters{}.m, ChainParameters{}.d, static_cast<int>(N), a, v0, engine->fine_clock);
  if (!(dv0 >= 0 && std::isfinite(dv0))) throw InputError(fmt::format("--dv0 = {} is out of range; valid range: dv0 >= 0", dv0));
  const long long realizations = integer("realizations", 1000, 2, 10000000);
  const long long seed = integer("seed", 1, 0, 9223372036854775807LL);
  const long long threads = integer("threads", std::max(1u, std::thread::hardware_concurrency()), 1, 1024);
  const double dt_factor = real("dt-factor", 100.0);
  if (!(dt_factor >= 10 && dt_factor <= 1e6))
    throw InputError(fmt::format("--dt-factor = {} is out of range; valid range: 10 <= dt-factor <= 1e6", dt_factor));
  const double tc = tc_arg ? real_arg("tc", *tc_arg) : 0.0;
  if (!(tc >= 0 && std::isfinite(tc))) throw InputError(fmt::format("--tc = {} is out of range; valid range: tc >= 0", tc));
  const bool watch_given = args.count("collapse-collisions") > 0 || args.count("collapse-time") > 0;
  const long long cc = integer("collapse-collisions", 1000, 2, 10000000);
  const double ct = real("collapse-time", 1e-9);
  if (!(ct > 0 && std::isfinite(ct))) throw InputError(fmt::format("--collapse-time = {} is out of range; valid range: > 0", ct));
  check_collapse_tc(tc, ct);
  if (!hard && watch_given)
    throw InputError("--collapse-collisions, --collapse-time: the collapse watch belongs to --engine hard");
  if (auto db = take(args, "db")) {
    q.db = path_text(*db, "--db");
    try {
      ResultsStore::preflight(q.db);
    } catch (const StoreError& err) {
      throw py::value_error(err.what());
    }
  }
  if (auto rec = take(args, "record-collisions")) {
    if (!rec->is_none() && !PyBool_Check(rec->ptr()))
      throw InputError(fmt::format("record_collisions = {} is not True or False", std::string(py::repr(*rec))));
    q.record = !rec->is_none() && rec->cast<bool>();
  }
  if (!args.empty()) {
    throw InputError(fmt::format("unknown parameter '{}'; known: N, e, k, engine, setup, a, v0, dv0, stop, realizations, seed, "
                                 "threads, dt_factor, tc, collapse_collisions, collapse_time, db, record_collisions",
                                 args.begin()->first));
  }

  s.params.N = static_cast<int>(N);
  s.params.e = e;
  s.params.k = k;
  s.params.g = 0.0;
  s.engine.kind = engine->kind;
  s.engine.dt_factor = dt_factor;
  s.engine.hard = {tc, static_cast<std::uint64_t>(cc), ct};
  s.launch = {a, v0, dv0};
  s.realizations = static_cast<int>(realizations);
  s.seed = static_cast<std::uint64_t>(seed);
  s.threads = static_cast<int>(threads);
  return q;
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

py::dict collapse(const py::kwargs& kwargs) {
  const CollapseRequest q = collapse_request(kwargs);
  CollapseResult result;
  std::vector<CollisionRecord> recs;
  std::int64_t id = 0;
  {
    py::gil_scoped_release nogil;
    CollisionLog log;
    if (q.record) log = [&recs](const std::vector<CollisionRecord>& r) { recs.insert(recs.end(), r.begin(), r.end()); };
    result = run_collapse(q.spec, log);
    if (!q.db.empty()) {
      ResultsStore store(q.db);
      id = store.insert_collapse(result);
    }
  }
  return collapse_dict(result, recs, q.record, q.db, id);
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
  m.def("k_slope", &slope, py::arg("a"), py::arg("b"),
        "Slope of n_tot against log10 k between two collapse() results of the same launches at k1 and k2, paired "
        "over launches, with alpha = d ln n_tot / d ln k and, for N = 3 in free space below e_c(3), the theory's slopes.");
}

}  // namespace granchain::python
