#include "config/collapse_options.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <thread>

#include "config/input_error.hpp"
#include "config/run_options.hpp"
#include "engines/engine_registry.hpp"

namespace granchain {

namespace {

int all_cores() { return static_cast<int>(std::max(1u, std::thread::hardware_concurrency())); }

}  // namespace

namespace {

// A parameter of a collapse count and, for those with a store column, its value in one count's
// spec (e and k: the count's own values from their lists).
struct CollapseEntry {
  Parameter info;
  std::function<TypedValue(const CollapseSpec&)> get;
};

// Sec. III.D of the paper (free space) and Sec. II.C (a wall); no gravity, m = d = 1. The defaults
// of N, e, k, engine and setup are the command's own (its fallback texts, which
// resolve_collapse_options reads); the others are CollapseSpec's (simulation/collapse_run.hpp).
const std::vector<CollapseEntry>& collapse_entries() {
  static const std::vector<CollapseEntry> table = [] {
    const CollapseSpec def;
    const HardSphereOptions& hard = def.engine.hard;
    const auto shown = [](double x) { return fmt::format("{:g}", x); };
    const unsigned c = kUseCollapse | kUsePython;
    using T = ParameterType;
    std::vector<CollapseEntry> t;
    t.push_back({{"N", T::Integer, "", "number of particles", "integer 2 <= N <= 100000", "3", c, EngineScope::Any, false, "N",
                 [](double x) { return x >= 2 && x <= 100000; }},
                [](const CollapseSpec& s) -> TypedValue { return static_cast<long long>(s.params.N); }});
    t.push_back({{"e", T::RealList, "", "restitution coefficients: a list or range (0.01,0.03 or 0.1:0.5:0.1)", "0 < e <= 1", "0.03", c,
                 EngineScope::Any, false, "e", [](double x) { return x > 0 && x <= 1; }},
                [](const CollapseSpec& s) -> TypedValue { return s.params.e; }});
    t.push_back({{"k", T::RealList, "m v0^2 / d^2", "elastic constants: a list or range (1e4:1e12:x10; not with --engine hard, whose k is infinite)",
                 "k > 0", "1e4:1e10:x10", c, EngineScope::Soft, false, "k", [](double x) { return x > 0; },
                 "the hard-sphere engine has k = infinity"},
                [](const CollapseSpec& s) -> TypedValue { return s.params.k; }  /* +inf for hard spheres */});
    t.push_back({{"engine", T::Name, "", "time integrator", "one of: " + engine_name_list() + " (reference engines: dt = tau_c/dt-factor; hard: k = infinity)",
                 std::string(engines().front().name), c, EngineScope::Any, false, "engine", {}},
                [](const CollapseSpec& s) -> TypedValue { return std::string(engine_name(s.engine.kind)); }});
    t.push_back({{"setup", T::Name, "", "where the launch plays out: free space (Sec. III.D), or a wall of restitution e that "
                 "Bernu-Mazighi spheres are thrown against (Sec. II.C)", "free or wall", "free", c, EngineScope::Any, false, "setup", {}},
                [](const CollapseSpec& s) -> TypedValue { return std::string(setup_name(s.setup)); }});
    t.push_back({{"a", T::Real, "d", "initial space between neighbours (and particle 1 and the wall)", "a >= 0", shown(def.launch.a), c, EngineScope::Any,
                 false, "a", [](double x) { return x >= 0; }},
                [](const CollapseSpec& s) -> TypedValue { return s.launch.a; }});
    t.push_back({{"v0", T::Real, "", "launch speed (inward in free space, toward the wall)", "v0 > 0", shown(def.launch.v0), c, EngineScope::Any, false, "v0",
                 [](double x) { return x > 0; }},
                [](const CollapseSpec& s) -> TypedValue { return s.launch.v0; }});
    t.push_back({{"dv0", T::Real, "v0", "amplitude of the uniform random velocity part dv0 xi, xi in [-1, 1)", "dv0 >= 0", shown(def.launch.dv0), c,
                 EngineScope::Any, false, "dv0", [](double x) { return x >= 0; }},
                [](const CollapseSpec& s) -> TypedValue { return s.launch.dv0; }});
    t.push_back({{"stop", T::Name, "", "stop rule: ends (the paper's, free space only) or strict (no pair approaches)", "ends or strict", "ends in free space, strict on a wall",
                 c, EngineScope::Any, false, "stop_rule", {}},
                [](const CollapseSpec& s) -> TypedValue { return std::string(rule_name(s.rule)); }});
    t.push_back({{"realizations", T::Integer, "", "random launches per (e, k) (two for an error bar)", "integer 2 <= realizations <= 10000000",
                 shown(def.realizations), c, EngineScope::Any, false, "realizations", [](double x) { return x >= 2 && x <= 10000000; }},
                [](const CollapseSpec& s) -> TypedValue { return static_cast<long long>(s.realizations); }});
    t.push_back({{"seed", T::Integer, "", "base seed; launch r uses derive_seed(seed, r), the same at every e and k",
                 "integer 0 <= seed <= 9223372036854775807", shown(static_cast<double>(def.seed)), c, EngineScope::Any, false, "seed", [](double x) { return x >= 0; }},
                [](const CollapseSpec& s) -> TypedValue { return static_cast<long long>(s.seed); }});
    t.push_back({{"threads", T::Integer, "", "threads over launches (results do not depend on it)", "integer 1 <= threads <= 1024",
                 "all cores", c, EngineScope::Any, false, "", [](double x) { return x >= 1 && x <= 1024; }}, {}});
    t.push_back({{"dt-factor", T::Real, "", "reference engines: dt = tau_c / dt-factor", "10 <= dt-factor <= 1e6", shown(def.engine.dt_factor), c,
                 EngineScope::TimeStepped, false, "dt_factor", [](double x) { return x >= 10 && x <= 1e6; }},
                [](const CollapseSpec& s) -> TypedValue { return s.engine.dt_factor; }});
    t.push_back({{"tc", T::Real, "d / v0",
                 "hard engine: TC model time t_c (a collision within t_c of a particle's previous one is elastic; 0: off)",
                 "tc = 0 (off) or tc >= collapse-time", shown(hard.tc), c, EngineScope::Hard, false, "tc",
                 [](double x) { return x >= 0; }, "the TC model"},
                [](const CollapseSpec& s) -> TypedValue { return s.engine.hard.tc; }});
    t.push_back({{"collapse-collisions", T::Integer, "",
                 "hard engine: collapse when this many consecutive collisions fit in --collapse-time (each launch keeps that many collision times)",
                 "integer 2 <= collapse-collisions <= 10000000", shown(static_cast<double>(hard.collapse_collisions)), c, EngineScope::Hard,
                 false, "", [](double x) { return x >= 2 && x <= 10000000; }, "the collapse watch"}, {}});
    t.push_back({{"collapse-time", T::Real, "d / v0", "hard engine: see --collapse-collisions", "collapse-time > 0",
                 shown(hard.collapse_time), c, EngineScope::Hard, false, "", [](double x) { return x > 0; }, "the collapse watch"}, {}});
    return t;
  }();
  return table;
}

}  // namespace

const std::vector<Parameter>& collapse_parameters() {
  static const std::vector<Parameter> table = [] {
    std::vector<Parameter> t;
    for (const auto& entry : collapse_entries()) t.push_back(entry.info);
    return t;
  }();
  return table;
}

std::vector<const Parameter*> stored_collapse_parameters() {
  std::vector<const Parameter*> out;
  for (const auto& entry : collapse_entries())
    if (!entry.info.store_column.empty()) out.push_back(&entry.info);
  return out;
}

std::vector<TypedValue> stored_collapse_values(const CollapseSpec& spec) {
  std::vector<TypedValue> out;
  for (const auto& entry : collapse_entries())
    if (!entry.info.store_column.empty()) out.push_back(entry.get(spec));
  return out;
}

namespace {

// The clock's scale over a launch: the outer particles reach the middle, or the wall, by
// (N - 1)(a + d) / 2v0 and (N a + (N - 1) d) / v0; a factor 2 for the spread of speeds and the
// rebounds gives t ~ 2 (N + 1)(a + d) / v0.
double launch_time_scale(int N, double a, double v0, double d) { return 2.0 * (N + 1) * (a + d) / v0; }

// The launch must play out well inside the count's clock limit (a launch is given up at t = 1e7,
// simulation/collapse_run.hpp): 2 (N + 1)(a + d) / v0 <= 1e6.
void check_launch(int N, double a, double v0, double d) {
  const double t = launch_time_scale(N, a, v0, d);
  if (!(t <= 1e6))
    throw InputError(fmt::format("--a = {:g}, --v0 = {:g}: the launch's time scale 2 (N + 1)(a + d) / v0 = {:.3g} is out of range; "
                                 "valid range: <= 1e6 (a launch is given up at t = 1e7)", a, v0, t));
}

// A contact must last 1e6 resolutions of the engine's clock over the launch's time scale
// (largest_resolved_k, config/run_options.hpp).
void check_contact_time(double k, double e, double m, double d, int N, double a, double v0, bool fine) {
  const double t = launch_time_scale(N, a, v0, d);
  const double k_max = largest_resolved_k(m, e, t, fine);
  if (!(k <= k_max))
    throw InputError(fmt::format("--k: {:g} is out of range; valid range: 0 < k <= {} at e = {:g}, N = {}, a = {:g}, v0 = {:g} "
                                 "(a contact must last at least 1e6 times the engine's clock resolution, {:.3g}, over the "
                                 "launch's time scale 2 (N + 1)(a + d) / v0 = {:.3g})",
                                 k, rounded_bound(k_max, true), e, N, a, v0, shortest_resolved_time(t, fine) / kResolutionSteps, t));
}

}  // namespace

CollapseOptions resolve_collapse_options(const std::map<std::string, RawValue>& raw) {
  const std::vector<Parameter>& table = collapse_parameters();
  for (const auto& [name, value] : raw)
    if (find_parameter(table, name) == nullptr)
      throw InputError(fmt::format("unknown parameter '{}'{}; known: {}", name, from_where(value), parameter_names(table)));
  const auto given = [&](const char* name) { return raw.count(name) > 0; };
  const auto param = [&](const char* name) -> const Parameter& { return *find_parameter(table, name); };
  // As given, or the table's default.
  const auto value = [&](const char* name) { return given(name) ? raw.at(name) : RawValue{param(name).fallback}; };
  const auto integer = [&](const char* name, long long dflt) { return given(name) ? read_integer(param(name), raw.at(name)) : dflt; };
  const auto real = [&](const char* name, double dflt) { return given(name) ? read_real(param(name), raw.at(name)) : dflt; };

  CollapseOptions o;
  CollapseSpec& s = o.base;
  s.params.N = static_cast<int>(read_integer(param("N"), value("N")));
  s.realizations = static_cast<int>(integer("realizations", s.realizations));
  s.seed = static_cast<std::uint64_t>(integer("seed", static_cast<long long>(s.seed)));
  s.threads = static_cast<int>(integer("threads", all_cores()));
  s.engine.hard.collapse_collisions =
      static_cast<std::uint64_t>(integer("collapse-collisions", static_cast<long long>(s.engine.hard.collapse_collisions)));
  o.es = read_real_list(param("e"), value("e"));

  const RawValue engine_value = value("engine");
  const std::string engine_text = read_name(param("engine"), engine_value);
  const EngineInfo* engine = find_engine(engine_text);
  if (engine == nullptr)
    throw InputError(fmt::format("--engine = '{}'{} is not an engine; valid: {}", engine_text, from_where(engine_value), engine_name_list()));
  const bool hard = engine->hard_spheres;
  check_engine_scope(table, raw, *engine);
  o.ks = hard ? std::vector<double>{std::numeric_limits<double>::infinity()} : read_real_list(param("k"), value("k"));

  const std::string setup = read_name(param("setup"), value("setup"));
  if (setup != "free" && setup != "wall") throw InputError(fmt::format("--setup = '{}'; valid: free, wall", setup));
  s.setup = setup == "free" ? CollapseSetup::FreeSpace : CollapseSetup::Wall;
  s.launch.a = real("a", s.launch.a);
  s.launch.v0 = real("v0", s.launch.v0);
  s.params.g = 0.0;
  check_launch(s.params.N, s.launch.a, s.launch.v0, s.params.d);
  if (!hard)
    for (double e : o.es)
      for (double k : o.ks) check_contact_time(k, e, s.params.m, s.params.d, s.params.N, s.launch.a, s.launch.v0, engine->fine_clock);
  const std::string stop = given("stop") ? read_name(param("stop"), raw.at("stop"))
                                         : s.setup == CollapseSetup::FreeSpace ? "ends" : "strict";
  if (stop != "ends" && stop != "strict") throw InputError(fmt::format("--stop = '{}'; valid: ends, strict", stop));
  s.rule = stop == "ends" ? StopRule::Ends : StopRule::Strict;
  if (s.rule == StopRule::Ends && s.setup == CollapseSetup::Wall)
    throw InputError("--stop = ends compares the end particles in free space; on a wall use --stop strict");
  s.launch.dv0 = real("dv0", s.launch.dv0);
  s.engine.kind = engine->kind;
  s.engine.dt_factor = real("dt-factor", s.engine.dt_factor);
  s.engine.hard.tc = real("tc", s.engine.hard.tc);
  s.engine.hard.collapse_time = real("collapse-time", s.engine.hard.collapse_time);
  // The TC time acts on collisions within t_c of one another; the collapse watch spans
  // collapse-time: t_c = 0 (off) or t_c >= collapse-time (see the driven column's tc).
  if (!(s.engine.hard.tc == 0 || s.engine.hard.tc >= s.engine.hard.collapse_time))
    throw InputError(fmt::format("--tc = {:g} is out of range; valid range: tc = 0 (off) or tc >= collapse-time = {:g}",
                                 s.engine.hard.tc, s.engine.hard.collapse_time));
  // Every launch's outcome is kept in memory until the table is printed: at most 1e9 launches.
  const double launches = static_cast<double>(o.es.size()) * static_cast<double>(o.ks.size()) * s.realizations;
  if (launches > 1e9)
    throw InputError(fmt::format("--realizations = {}: {} values of e times {} of k times the launches is {:.3g}; valid range: "
                                 "at most 1e9 launches in one command", s.realizations, o.es.size(), o.ks.size(), launches));
  return o;
}

void check_storable(const CollapseSpec& spec) {
  if (!engine_info(spec.engine.kind).hard_spheres) return;
  const HardSphereOptions def;
  const HardSphereOptions& h = spec.engine.hard;
  if (h.collapse_collisions != def.collapse_collisions)
    throw InputError(fmt::format("--collapse-collisions = {}: a results store tells counts apart by their stored parameters, and the "
                                 "collapse watch is not one; valid with a store: {} (the default), or count without one (--no-db)",
                                 h.collapse_collisions, def.collapse_collisions));
  if (h.collapse_time != def.collapse_time)
    throw InputError(fmt::format("--collapse-time = {:g}: a results store tells counts apart by their stored parameters, and the "
                                 "collapse watch is not one; valid with a store: {:g} (the default), or count without one (--no-db)",
                                 h.collapse_time, def.collapse_time));
}

}  // namespace granchain
