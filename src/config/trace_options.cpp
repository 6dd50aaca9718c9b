#include "config/trace_options.hpp"

#include <fmt/format.h>

#include "config/input_error.hpp"
#include "config/run_options.hpp"
#include "engines/engine_registry.hpp"

namespace granchain {

const std::vector<Parameter>& trace_window_parameters() {
  static const std::vector<Parameter> table = [] {
    const unsigned t = kUseTrace | kUsePython;
    using T = ParameterType;
    std::vector<Parameter> p;
    p.push_back({"setup", T::Name, "", "driven column (the trajectory of `granchain run` with the same seed) or free space (launch "
                 "`realization` of `granchain collapse`)", "driven or free", "driven", t, EngineScope::Any, false, "", {}});
    p.push_back({"from", T::Real, "sqrt(d / g)", "start of the window", "0 <= from < 1e15", "0", t, EngineScope::Any, false, "",
                 [](double x) { return x >= 0 && x < 1e15; }});
    p.push_back({"to", T::Real, "sqrt(d / g)", "end of the window", "from < to <= 1e15", "1", t, EngineScope::Any, false, "",
                 [](double x) { return x <= 1e15; }});
    p.push_back({"dt", T::Real, "sqrt(d / g)", "sampling interval (at most 1e7 samples, 1e8 heights)", "dt > 0", "1e-3", t,
                 EngineScope::Any, false, "", [](double x) { return x > 0; }});
    p.push_back({"a", T::Real, "d", "free space: initial space between neighbours", "a >= 0", "1", t, EngineScope::Any, false, "",
                 [](double x) { return x >= 0; }});
    p.push_back({"v0", T::Real, "", "free space: launch speed", "v0 > 0", "1", t, EngineScope::Any, false, "",
                 [](double x) { return x > 0; }});
    p.push_back({"dv0", T::Real, "v0", "free space: amplitude of the random velocity part", "dv0 >= 0", "0.1", t, EngineScope::Any,
                 false, "", [](double x) { return x >= 0; }});
    p.push_back({"realization", T::Integer, "", "free space: launch number (seed derive_seed(seed, realization))",
                 "integer 0 <= realization <= 1000000000", "0", t, EngineScope::Any, false, "",
                 [](double x) { return x >= 0 && x <= 1e9; }});
    return p;
  }();
  return table;
}

TraceSpec resolve_trace_spec(const std::map<std::string, RawValue>& raw) {
  std::map<std::string, RawValue> run_raw;
  std::map<std::string, RawValue> own;
  for (const auto& [name, value] : raw) (find_parameter(trace_window_parameters(), name) ? own : run_raw)[name] = value;
  const auto& table = trace_window_parameters();
  // The trace's own value of `name` as given, or its default, read as its type.
  const auto value = [&](const char* name, auto read) {
    const Parameter& p = *find_parameter(table, name);
    return read(p, own.count(name) ? own.at(name) : RawValue(p.fallback));
  };
  const auto real = [&](const char* name) { return value(name, read_real); };
  const std::string setup = value("setup", read_name);
  if (setup != "driven" && setup != "free") throw InputError(fmt::format("--setup = '{}' is not a set-up; valid: driven, free", setup));

  const EngineInfo* named = run_raw.count("engine") ? find_engine(run_raw.at("engine").text()) : nullptr;
  if (named != nullptr && named->hard_spheres)
    throw InputError("--engine: trace needs a soft engine (exact or reference); hard spheres have no overlaps to draw");
  for (const auto& [name, value] : run_raw) {
    const Parameter* p = find_parameter(run_parameters(), name);
    if (p == nullptr || !(p->uses & kUseTrace))
      throw InputError(fmt::format("--{}: trace takes no such parameter; valid: {}, {}", name, parameter_names(run_parameters(), kUseTrace),
                                   parameter_names(table)));
  }
  TraceSpec spec;
  spec.run = resolve_run_options(run_raw).spec;
  spec.free_space = setup == "free";
  if (spec.free_space && spec.run.drive.plate())
    throw InputError(fmt::format("--drive = '{}': free space has no floor to vibrate; valid: --setup driven with a plate, or --drive "
                                 "thermal (left out) in free space",
                                 run_raw.at("drive").text()));
  spec.launch = {real("a"), real("v0"), real("dv0")};
  spec.realization = static_cast<int>(value("realization", read_integer));
  const double from = real("from"), to = real("to"), dt = real("dt");
  spec.t_from = from;
  spec.t_to = to;
  spec.dt = dt;
  if (!(to > from)) throw InputError(fmt::format("--to = {} is out of range; valid range: from = {} < to <= 1e15", to, from));
  // Samples and contacts must be resolved by the clock at `to`, as a run's are at transient + T.
  if (!(dt >= shortest_resolved_time(to)))
    throw InputError(fmt::format("--dt = {} is out of range; valid range: dt >= {:.3g} at to = {} (1e6 times the clock's "
                                 "resolution there)", dt, shortest_resolved_time(to), to));
  const bool fine = engine_info(spec.run.engine.kind).fine_clock;
  if (!(spec.run.params.k <= largest_resolved_k(spec.run.params.m, spec.run.params.e, to, fine)))
    throw InputError(fmt::format("--to = {} is out of range at k = {:g}: a contact must last at least 1e6 times the engine's "
                                 "clock resolution at to; valid range: k <= {:.3g} there", to, spec.run.params.k,
                                 largest_resolved_k(spec.run.params.m, spec.run.params.e, to, fine)));
  if ((to - from) / dt > 1e7)
    throw InputError(fmt::format("--dt = {} is out of range; valid range: dt > 0 with (to - from)/dt <= 1e7", dt));
  // The trace holds every height in memory: at most 1e8 values.
  if (spec.run.params.N * ((to - from) / dt + 1) > 1e8)
    throw InputError(fmt::format("--dt = {} is out of range; valid range: dt >= N (to - from) / 1e8 = {:.3g} (at most 1e8 heights "
                                 "in the trace)", dt, spec.run.params.N * (to - from) / 1e8));
  return spec;
}

}  // namespace granchain
