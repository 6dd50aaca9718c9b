#include "config/run_options.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <type_traits>

#include "config/drive_options.hpp"
#include "config/input_error.hpp"
#include "config/run_definition.hpp"
#include "engines/engine_registry.hpp"

namespace granchain {

namespace {

using run_table::Definition;
using run_table::integer;
using run_table::real;

// The driven column's parameters (Sec. II of the paper; units m = d = g = 1 unless set). An entry
// with a store column is part of a run's identity: its point key and its row in the store follow
// from the entry (config/run_key.hpp, store/store_schema.cpp).
const std::vector<Definition>& definitions() {
  static const std::vector<Definition> defs = [] {
    // The defaults are those of RunOptions (model/chain_parameters.hpp, simulation/driven_run.hpp,
    // engines/engine_registry.hpp), shown in the help as they are.
    const RunOptions def;
    const HardSphereOptions& hard = def.spec.engine.hard;
    const auto shown = [](double x) { return fmt::format("{:g}", x); };
    using I = RunIdentity;
    std::vector<Definition> d;
    d.push_back(integer({"N", {}, "", "number of particles", "integer 1 <= N <= 100000", shown(def.spec.params.N), kUseDriven | kUseTrace, EngineScope::Any, true, "N",
                         [](double x) { return x >= 1 && x <= 100000; }},
                        I::Physics, [](auto& s) -> auto& { return s.params.N; }));
    d.push_back(real({"e", {}, "", "restitution coefficient of a binary collision", "0 < e <= 1", shown(def.spec.params.e), kUseDriven | kUseTrace, EngineScope::Any, true,
                      "e", [](double x) { return x > 0 && x <= 1; }},
                     I::Physics, [](auto& s) -> auto& { return s.params.e; }));
    d.push_back(real({"k", {}, "m g / d", "elastic constant of the spring (hard-sphere limit: k -> infinity at fixed e)", "k > 0",
                      shown(def.spec.params.k), kUseDriven | kUseTrace, EngineScope::Soft, true, "k", [](double x) { return x > 0; },
                      "the hard-sphere engine has k = infinity"},
                     I::Physics, [](auto& s) -> auto& { return s.params.k; }));
    d.push_back(real({"T0", {}, "m g d", "temperature of the thermal floor, k_B T0 (and of the initial velocities)", "T0 > 0", shown(def.spec.params.kT0), kUseDriven | kUseTrace, EngineScope::Any, true,
                      "T0", [](double x) { return x > 0; }},
                     I::Physics, [](auto& s) -> auto& { return s.params.kT0; }));
    run_table::add_drive_definitions(d);
    // T and transient: their defaults depend on N (resolve_run_options).
    d.push_back(real({"T", {}, "sqrt(d / g)", "measuring time (window after the transient)", "T > 0",
                      "1e4 for N < 50, 1e3 for N >= 50 (the paper's)", kUseDriven, EngineScope::Any, true, "T",
                      [](double x) { return x > 0; }},
                     I::Window, [](auto& s) -> auto& { return s.T; }));
    d.push_back(real({"transient", {}, "sqrt(d / g)", "discarded time before the measuring window", "transient >= 0", "T/10",
                      kUseDriven, EngineScope::Any, false, "transient", [](double x) { return x >= 0; }},
                     I::Window, [](auto& s) -> auto& { return s.transient; }));
    d.push_back(integer({"seed", {}, "", "random seed (initial state and floor)", "integer 0 <= seed <= 9223372036854775807",
                         shown(static_cast<double>(def.spec.seed)), kUseDriven | kUseTrace, EngineScope::Any, false, "seed",
                         [](double x) { return x >= 0; }},
                        I::Seed, [](auto& s) -> auto& { return s.seed; }));
    {
      const std::string names = engine_name_list();
      Parameter p{"engine", ParameterType::Name, "", "time integrator (reference = the paper's 2nd-order Runge-Kutta with dt = tau_c/dt-factor)",
                  "one of: " + names, std::string(engines().front().name), kUseDriven | kUseTrace, EngineScope::Any, true, "engine", {}};
      p.identity = I::Engine;
      const auto set = [names](RunSpec& s, const TypedValue& v) {
        const std::string& name = std::get<std::string>(v);
        const EngineInfo* e = find_engine(name);
        if (!e) throw InputError(fmt::format("'{}' is not an engine; valid: {}", name, names));
        s.engine.kind = e->kind;
      };
      d.push_back({std::move(p), false,
                   [](const RunSpec& s) -> TypedValue { return std::string(engine_name(s.engine.kind)); }, set,
                   [names](RunOptions& o, const Parameter& q, const RawValue& v) {
                     const std::string name = read_name(q, v);
                     if (const EngineInfo* e = find_engine(name)) {
                       o.spec.engine.kind = e->kind;
                       return;
                     }
                     throw InputError(fmt::format("--engine = '{}'{} is not an engine; valid: {}", v.text(), from_where(v), names));
                   }});
    }
    d.push_back(real({"dt-factor", {}, "", "reference engine step dt = tau_c / dt-factor (the paper: 100)", "10 <= dt-factor <= 1e6",
                      shown(def.spec.engine.dt_factor),
                      kUseDriven | kUseTrace, EngineScope::TimeStepped, false, "dt_factor", [](double x) { return x >= 10 && x <= 1e6; }},
                     I::EngineOption, [](auto& s) -> auto& { return s.engine.dt_factor; }));
    // The hard engine declares an inelastic collapse when collapse_collisions (1000) collisions
    // fall within collapse_time (1e-9). A TC time shorter than that span leaves collisions inside
    // it inelastic, and the watch can fire although the TC model is on (N = 100, e = 0.05 collapses
    // at tc = 1e-10, runs at 1e-9); from tc = collapse_time on, every further collision of a
    // particle inside the span is elastic.
    {
      Definition tc = real({"tc", {}, "sqrt(d / g)",
                            "hard engine: TC model time t_c, a collision within t_c of a particle's previous one is elastic (0: off)",
                            fmt::format("tc = 0 (off) or tc >= {:g} (the hard engine counts {} collisions within {:g} as a collapse; "
                                        "a shorter t_c leaves them inelastic)",
                                        hard.collapse_time, hard.collapse_collisions, hard.collapse_time),
                            shown(hard.tc), kUseDriven, EngineScope::Hard, false, "tc",
                            [min = hard.collapse_time](double x) { return x == 0 || x >= min; }, "the TC model"},
                           I::EngineOption, [](auto& s) -> auto& { return s.engine.hard.tc; });
      tc.nullable = true;  // NULL for the soft engines
      d.push_back(std::move(tc));
    }
    // Does the hard column collapse from its stationary state, or only in the first fall from the
    // initial state? The transient at a large k brings the soft column there; the window is hard.
    {
      Definition start = real({"start-k", {}, "m g / d",
                               "hard engine: the exact engine at this k runs the transient and the hard spheres start from its "
                               "column (overlaps closed); 0: the hard engine runs from the initial state",
                               "start-k = 0 (off) or start-k > 0 with transient > 0", shown(def.spec.engine.start_k), kUseDriven,
                               EngineScope::Hard, false, "start_k", [](double x) { return x >= 0; }, "the hard-sphere engine's start"},
                              I::EngineOption, [](auto& s) -> auto& { return s.engine.start_k; });
      start.nullable = true;  // NULL where the hard engine runs from the initial state, and for the soft engines
      start.acts_in = [](const RunSpec& s) { return s.engine.start_k > 0; };
      d.push_back(std::move(start));
    }
    d.push_back(real({"m", {}, "", "particle mass (unit of mass)", "m > 0", shown(def.spec.params.m), kUseDriven | kUseTrace, EngineScope::Any, false, "m",
                      [](double x) { return x > 0; }},
                     I::Physics, [](auto& s) -> auto& { return s.params.m; }));
    d.push_back(real({"d", {}, "", "particle diameter (unit of length)", "d > 0", shown(def.spec.params.d), kUseDriven | kUseTrace, EngineScope::Any, false, "d",
                      [](double x) { return x > 0; }},
                     I::Physics, [](auto& s) -> auto& { return s.params.d; }));
    d.push_back(real({"g", {}, "", "gravitational acceleration", "g > 0", shown(def.spec.params.g), kUseDriven | kUseTrace, EngineScope::Any, false, "g",
                      [](double x) { return x > 0; }},
                     I::Physics, [](auto& s) -> auto& { return s.params.g; }));
    d.push_back(real({"sample-interval", {}, "sqrt(d / g)",
                      "time between profile samples (rounded to whole engine steps); 16 to 1e10 samples in T, at least 1e6 clock resolutions",
                      "sample-interval > 0", shown(def.spec.sample_interval), kUseDriven, EngineScope::Any, false, "sample_interval", [](double x) { return x > 0; }},
                     I::Window, [](auto& s) -> auto& { return s.sample_interval; }));
    {
      Definition bins = integer({"bins", {}, "", "time bins for the blocking error analysis", "power of two, 16 <= bins <= 65536", shown(def.spec.bins),
                                 kUseDriven, EngineScope::Any, false, "bins",
                                 [](double x) {
                                   const auto b = static_cast<long long>(x);
                                   return b >= 16 && b <= 65536 && (b & (b - 1)) == 0;
                                 }},
                                I::Window, [](auto& s) -> auto& { return s.bins; });
      bins.nullable = true;  // runs of the first store version have none
      d.push_back(std::move(bins));
    }
    d.push_back({{"db", ParameterType::Path, "", "results store (SQLite file), created if missing", "a file name",
                  def.db_path + " in the working folder", kUseRun | kUseSweep | kUsePython, EngineScope::Any, false, "", {}},
                 false, {}, {},
                 [](RunOptions& o, const Parameter& q, const RawValue& v) {
                   const std::string path = read_name(q, v);
                   if (path.empty()) throw InputError("--db: the path is empty; give a file name");
                   o.db_path = std::get<std::string>(v.value);
                 }});
    d.push_back({{"checkpoint", ParameterType::Path, "",
                  "keep the run's state in this file as it goes (every checkpoint-every seconds, and when SIGINT or SIGTERM "
                  "stops it) and resume from it where it exists; removed once the run is stored or written (engines: " +
                      resumable_engine_list() + ")",
                  "a file name", "none", kUseRun | kUsePython, EngineScope::Any, false, "", {}},
                 false, {}, {},
                 [](RunOptions& o, const Parameter& q, const RawValue& v) {
                   const std::string path = read_name(q, v);
                   if (path.empty()) throw InputError("--checkpoint: the path is empty; give a file name");
                   o.checkpoint_path = path;
                 }});
    d.push_back({{"checkpoint-every", ParameterType::Real, "",
                  "wall-clock seconds between two saves of a run's state (run --checkpoint, sweep --checkpoint-dir)",
                  "1 <= checkpoint-every <= 1e7", shown(def.checkpoint_every), kUseRun | kUseSweep | kUsePython, EngineScope::Any, false, "",
                  [](double x) { return x >= 1 && x <= 1e7; }},
                 false, {}, {},
                 [](RunOptions& o, const Parameter& q, const RawValue& v) { o.checkpoint_every = read_real(q, v); }});
    return d;
  }();
  return defs;
}

// Reads a raw value as the entry's type and sets it (the entries without their own apply).
void apply(const Definition& d, RunOptions& o, const RawValue& v) {
  if (d.apply) return d.apply(o, d.info, v);
  switch (d.info.type) {
    case ParameterType::Integer: return d.set(o.spec, read_integer(d.info, v));
    case ParameterType::Real: return d.set(o.spec, read_real(d.info, v));
    default: return d.set(o.spec, read_name(d.info, v));
  }
}

// ---------------------------------------------------------------------------------------------
// What the engines resolve in double precision. Each parameter alone has a wide valid range, but
// together they set two scales that must stay resolvable; a run outside them prints numbers that
// mean nothing (k = 1e300: tau_c = 2e-150, every contact begins and ends at one clock value) or
// an exploded column (m = 1e-300: speeds of 1e150, heights of 1e149 after t = 1).

// Resolution steps a scale must span (kResolutionSteps): the exact engine steps over what it
// cannot resolve in intervals of 1e-6 tau_c (ExactEngine::kResolutionSkip), the reference engine's
// finest step is tau_c / 1e6 (dt-factor <= 1e6), and heights are asked to resolve d to the same 1e-6.

double ulp(double t) { return std::nextafter(t, std::numeric_limits<double>::infinity()) - t; }

// The flag a message names: the first of `names` that was given and fails with every other
// parameter at its default (fails(name) says so), else the first that was given.
std::string culprit(const std::vector<std::string>& names, const std::map<std::string, RawValue>& raw,
                    const std::function<bool(const std::string&)>& fails) {
  for (const auto& n : names)
    if (raw.count(n) && fails(n)) return n;
  for (const auto& n : names)
    if (raw.count(n)) return n;
  return names.front();
}

// The raw value of a flag, or its value in effect when it was not given.
RawValue given_or(const std::map<std::string, RawValue>& raw, const std::string& name, double value) {
  const auto it = raw.find(name);
  return it != raw.end() ? it->second : RawValue{fmt::format("{}", value), ""};
}

// Time (soft engines). A contact lasts tau_c, with tau_c^2 = m (pi^2 + ln^2 e) / 2k (Eqs. Dd,
// tauc), and the clock's resolution at the run's last instant t = transient + T is ulp(t) (about
// 2^-52 t) for a double clock, 2^-53 ulp(t) for the exact engine's FineTime: tau_c >= 1e6 times
// that, i.e. k <= m (pi^2 + ln^2 e) / (2 tau_min^2). At the paper's T = 1e4 that is k <= 1.49e12
// for m = 1 on a double clock (the reference engines) and k <= 1.2e44 for the exact engine.
void check_contact_time(const RunOptions& o, const std::map<std::string, RawValue>& raw) {
  const EngineInfo& engine = engine_info(o.spec.engine.kind);
  if (engine.hard_spheres) return;
  const ChainParameters& p = o.spec.params;
  const double t_end = o.spec.transient + o.spec.T;
  const auto tau = [](double k, double m, double e) { return contact_time(k, damping_constant(k, e, m), m); };
  const bool fine = engine.fine_clock;
  const auto resolved = [&](double k, double m, double e, double t) { return tau(k, m, e) >= shortest_resolved_time(t, fine); };
  if (resolved(p.k, p.m, p.e, t_end)) return;
  const ChainParameters def;
  const double t_def = default_measuring_time(p.N) * 1.1;
  const std::string name = culprit({"k", "m", "T", "transient"}, raw, [&](const std::string& n) {
    if (n == "k") return !resolved(p.k, def.m, def.e, t_def);
    if (n == "m") return !resolved(def.k, p.m, def.e, t_def);
    return !resolved(def.k, def.m, def.e, t_end);
  });
  const double tau_min = shortest_resolved_time(t_end, fine);
  const double l2 = std::log(p.e) * std::log(p.e);
  const double pi2 = std::numbers::pi * std::numbers::pi;
  std::string range;
  if (name == "k") {
    range = fmt::format("0 < k <= {} at m = {}, e = {} and transient + T = {}", rounded_bound(p.m * (pi2 + l2) / (2 * tau_min * tau_min), true),
                        p.m, p.e, t_end);
  } else if (name == "m") {
    range = fmt::format("m >= {} at k = {}, e = {} and transient + T = {}", rounded_bound(2 * p.k * tau_min * tau_min / (pi2 + l2), false),
                        p.k, p.e, t_end);
  } else {  // the largest t_end whose ulp, 2^(ilogb(t) - 52), is at most tau_c / 1e6 (times 2^53: fine)
    const double t_max = std::ldexp(1.0, 53 + std::ilogb(tau(p.k, p.m, p.e) / kResolutionSteps) + (fine ? 53 : 0));
    range = fmt::format("transient + T < {} at k = {}, m = {} and e = {}", rounded_bound(t_max, true), p.k, p.m, p.e);
  }
  value_out_of_range(name, given_or(raw, name, name == "k" ? p.k : name == "m" ? p.m : o.spec.T),
               fmt::format("{}: a contact (tau_c = {:.3g} here) must last at least 1e6 times the {} engine's clock resolution "
                           "at t = transient + T ({:.3g})", range, tau(p.k, p.m, p.e), engine.name,
                           shortest_resolved_time(t_end, fine) / kResolutionSteps));
}

// Heights (all engines). The floor throws particles to heights of order k_B T0 / (m g) above a
// stack of N d. Profiles are sampled as absolute heights (and the reference engine integrates
// them), resolved to 2^-52 of the column's height scale; for that to resolve d to 1e-6,
// N d + T0/(m g) <= R d with R = 2^52 / 1e6 = 4.5e9.
void check_height_scale(const RunOptions& o, const std::map<std::string, RawValue>& raw) {
  const ChainParameters& p = o.spec.params;
  const double R = std::ldexp(1.0, 52) / kResolutionSteps;
  // Written as quotients, so that T0 / m overflowing to infinity fails the check.
  const auto resolved = [&](double kT0, double m, double g, double d) { return kT0 / m / g / d + p.N <= R; };
  if (resolved(p.kT0, p.m, p.g, p.d)) return;
  const ChainParameters def;
  const std::string name = culprit({"m", "T0", "g", "d"}, raw, [&](const std::string& n) {
    if (n == "m") return !resolved(def.kT0, p.m, def.g, def.d);
    if (n == "T0") return !resolved(p.kT0, def.m, def.g, def.d);
    if (n == "g") return !resolved(def.kT0, def.m, p.g, def.d);
    return !resolved(def.kT0, def.m, def.g, p.d);
  });
  const double room = R - p.N;  // T0 / (m g d) may be at most this
  std::string range;
  if (name == "m") range = fmt::format("m >= {} at T0 = {}, g = {}, d = {}", rounded_bound(p.kT0 / p.g / p.d / room, false), p.kT0, p.g, p.d);
  else if (name == "T0") range = fmt::format("0 < T0 <= {} at m = {}, g = {}, d = {}", rounded_bound(p.m * p.g * p.d * room, true), p.m, p.g, p.d);
  else if (name == "g") range = fmt::format("g >= {} at T0 = {}, m = {}, d = {}", rounded_bound(p.kT0 / p.m / p.d / room, false), p.kT0, p.m, p.d);
  else range = fmt::format("d >= {} at T0 = {}, m = {}, g = {}", rounded_bound(p.kT0 / p.m / p.g / room, false), p.kT0, p.m, p.g);
  value_out_of_range(name, given_or(raw, name, name == "m" ? p.m : name == "T0" ? p.kT0 : name == "g" ? p.g : p.d),
               fmt::format("{} and N = {}: the column's height scale N d + T0 / (m g) must stay below {:.2g} d, where heights "
                           "resolve d to 1e-6", range, p.N, R));
}

// The soft start of the hard engine (--start-k): the exact engine runs the transient at start-k,
// so the transient must exist, its contacts must be resolved by the exact engine's clock until the
// transient ends, and a plate's period must last 10 of them (as resolve_drive asks of soft runs).
void check_start_k(const RunOptions& o, const std::map<std::string, RawValue>& raw) {
  const double k = o.spec.engine.start_k;
  if (!(k > 0)) return;
  const RawValue& given = raw.at("start-k");
  if (!(o.spec.transient > 0))
    throw InputError(fmt::format("--start-k = {}{}: the exact engine runs the transient, and transient = 0; valid: --start-k with "
                                 "--transient > 0",
                                 given.text(), from_where(given)));
  const ChainParameters& p = o.spec.params;
  const double tau_c = contact_time(k, damping_constant(k, p.e, p.m), p.m);
  if (!(tau_c >= shortest_resolved_time(o.spec.transient, true)))
    value_out_of_range("start-k", given,
                       fmt::format("0 < start-k <= {} at m = {}, e = {} and transient = {} (a contact must last 1e6 times the exact "
                                   "engine's clock resolution at the transient's end)",
                                   rounded_bound(largest_resolved_k(p.m, p.e, o.spec.transient, true), true), p.m, p.e,
                                   o.spec.transient));
  // tau_c falls as k^-1/2: the plate's period bounds start-k from below.
  const double omega_max = 2.0 * std::numbers::pi / (10.0 * tau_c);
  if (o.spec.drive.plate() && !(o.spec.drive.omega <= omega_max))
    value_out_of_range("start-k", given,
                       fmt::format("start-k >= {} at omega = {}, e = {}, m = {} (the plate's period must last at least 10 contact "
                                   "times of the soft start)",
                                   rounded_bound(k * std::pow(o.spec.drive.omega / omega_max, 2), false), o.spec.drive.omega, p.e, p.m));
}

// A checkpoint needs an engine that can save its state (EngineInfo::resumable); its interval acts
// only with it.
void check_checkpoint(const RunOptions& o, const std::map<std::string, RawValue>& raw) {
  if (o.checkpoint_path.empty()) {
    if (raw.count("checkpoint-every")) {
      const RawValue& given = raw.at("checkpoint-every");
      throw InputError(fmt::format("--checkpoint-every = {}{}: it acts only with --checkpoint FILE", given.text(), from_where(given)));
    }
    return;
  }
  const EngineInfo& engine = engine_info(o.spec.engine.kind);
  if (!can_resume(o.spec)) {
    const RawValue& given = raw.at("checkpoint");
    throw InputError(fmt::format("--checkpoint = {}{}: the {} engine{} cannot save its state; valid: --engine {}", given.text(),
                                 from_where(given), engine.name, o.spec.engine.start_k > 0 ? " with its soft start" : "",
                                 resumable_engine_list()));
  }
}

}  // namespace

double default_measuring_time(int N) { return N < 50 ? 1e4 : 1e3; }

void request_audit(RunOptions& o) {
  if (!engine_info(o.spec.engine.kind).has_audit)
    throw InputError(fmt::format("--audit checks the exact engine; --engine = '{}' has no audit", engine_name(o.spec.engine.kind)));
  if (o.spec.drive.plate())
    throw InputError(fmt::format("--audit: the exact engine's audit does not cover a vibrating plate (--drive = '{}'); valid: --audit "
                                 "with --drive thermal", drive_name(o.spec.drive.kind)));
  o.spec.engine.audit = true;
}

double shortest_resolved_time(double t, bool fine) { return kResolutionSteps * (fine ? std::ldexp(ulp(t), -53) : ulp(t)); }

double largest_resolved_k(double m, double e, double t, bool fine) {
  const double tau_min = shortest_resolved_time(t, fine);
  const double l2 = std::log(e) * std::log(e);
  return m * (std::numbers::pi * std::numbers::pi + l2) / (2 * tau_min * tau_min);
}

const std::vector<Parameter>& run_parameters() {
  static const std::vector<Parameter> infos = [] {
    std::vector<Parameter> v;
    for (const auto& d : definitions()) v.push_back(d.info);
    return v;
  }();
  return infos;
}

RunOptions resolve_run_options(const std::map<std::string, RawValue>& raw) {
  RunOptions o;
  for (const auto& [key, value] : raw) {
    bool known = false;
    for (const auto& d : definitions()) {
      if (d.info.name == key) {
        apply(d, o, value);
        known = true;
        break;
      }
    }
    if (!known)
      throw InputError(fmt::format("unknown parameter '{}'{}; known: {}", key, from_where(value), parameter_names(run_parameters())));
  }
  check_engine_scope(run_parameters(), raw, engine_info(o.spec.engine.kind));
  if (engine_info(o.spec.engine.kind).hard_spheres) o.spec.params.k = std::numeric_limits<double>::infinity();
  if (!raw.count("T")) o.spec.T = default_measuring_time(o.spec.params.N);
  if (!raw.count("transient")) o.spec.transient = o.spec.T / 10.0;
  check_contact_time(o, raw);
  check_height_scale(o, raw);
  run_table::resolve_drive(o, raw);
  check_start_k(o, raw);
  check_checkpoint(o, raw);
  // The clock runs from 0 to transient + T: beyond 1e15 a step of order 1 stops advancing it.
  if (!(o.spec.transient + o.spec.T <= 1e15))
    value_out_of_range(raw.count("transient") ? "transient" : "T", given_or(raw, raw.count("transient") ? "transient" : "T",
                                                                      raw.count("transient") ? o.spec.transient : o.spec.T),
                 "transient + T <= 1e15 (the clock must still advance by steps of order 1)");
  // The profile histograms hold (1 + 3N) bins doubles: at most 1 GiB.
  if (static_cast<double>(1 + 3 * o.spec.params.N) * o.spec.bins * 8.0 > 1073741824.0) {
    const bool bins_given = raw.count("bins") > 0;
    const long long n_max = (1073741824LL / (8LL * o.spec.bins) - 1) / 3;
    value_out_of_range(bins_given ? "bins" : "N", given_or(raw, bins_given ? "bins" : "N", bins_given ? o.spec.bins : o.spec.params.N),
                 bins_given ? fmt::format("bins <= {} at N = {} (the profile histograms, (1 + 3N) x bins doubles, take at most 1 GiB)",
                                          1073741824LL / (8LL * (1 + 3LL * o.spec.params.N)), o.spec.params.N)
                            : fmt::format("N <= {} at bins = {} (the profile histograms, (1 + 3N) x bins doubles, take at most 1 GiB)",
                                          n_max, o.spec.bins));
  }
  // Profiles are sampled every sample-interval over the window T: blocking needs at least 16
  // samples (the least --bins), more than 1e10 would take longer to sample than any run is meant to, and the sample
  // times must be told apart by the clock (1e6 resolutions at transient + T, as contacts are).
  {
    const double samples = o.spec.T / o.spec.sample_interval, t_end = o.spec.transient + o.spec.T;
    const bool interval_given = raw.count("sample-interval") > 0;
    const std::string name = interval_given || !raw.count("T") ? "sample-interval" : "T";
    const RawValue& given = given_or(raw, name, name == "T" ? o.spec.T : o.spec.sample_interval);
    if (!(samples >= 16 && samples <= 1e10))
      value_out_of_range(name, given,
                   name == "T" ? fmt::format("16 sample-intervals <= T <= 1e10 sample-intervals, i.e. {} <= T <= {} at "
                                             "sample-interval = {} (a window of 16 to 1e10 profile samples)",
                                             rounded_bound(16 * o.spec.sample_interval, false), rounded_bound(1e10 * o.spec.sample_interval, true),
                                             o.spec.sample_interval)
                               : fmt::format("T / 1e10 <= sample-interval <= T / 16, i.e. {} <= sample-interval <= {} at T = {} "
                                             "(a window of 16 to 1e10 profile samples)",
                                             rounded_bound(o.spec.T / 1e10, false), rounded_bound(o.spec.T / 16, true), o.spec.T));
    if (o.spec.sample_interval < shortest_resolved_time(t_end))
      value_out_of_range("sample-interval", given_or(raw, "sample-interval", o.spec.sample_interval),
                   fmt::format("sample-interval >= {} at transient + T = {} (1e6 times the clock's resolution there)",
                               rounded_bound(shortest_resolved_time(t_end), false), t_end));
  }
  return o;
}

namespace {

// The entries with a store column, in the order of a run's identity (then of the table).
const std::vector<const Definition*>& stored_definitions() {
  static const std::vector<const Definition*> stored = [] {
    std::vector<const Definition*> v;
    for (const auto& d : definitions())
      if (!d.info.store_column.empty()) v.push_back(&d);
    std::stable_sort(v.begin(), v.end(), [](const Definition* a, const Definition* b) { return a->info.identity < b->info.identity; });
    return v;
  }();
  return stored;
}

bool acts(const Parameter& p, const EngineInfo& engine) {
  if (p.engines == EngineScope::Hard) return engine.hard_spheres;
  if (p.engines == EngineScope::TimeStepped) return engine.time_stepped;
  return true;  // k too: the hard-sphere engine runs at k = infinity
}

}  // namespace

const std::vector<StoredParameter>& stored_run_parameters() {
  static const std::vector<StoredParameter> out = [] {
    std::vector<StoredParameter> v;
    for (const Definition* d : stored_definitions()) v.push_back({&d->info, d->nullable});
    return v;
  }();
  return out;
}


std::vector<StoredValue> stored_values(const RunSpec& spec) {
  const EngineInfo& engine = engine_info(spec.engine.kind);
  std::vector<StoredValue> v;
  for (const Definition* d : stored_definitions())
    v.push_back({d->get(spec), acts(d->info, engine) && (!d->acts_in || d->acts_in(spec))});
  return v;
}

void set_stored_value(RunSpec& spec, std::size_t i, const TypedValue& value) { stored_definitions().at(i)->set(spec, value); }

}  // namespace granchain
