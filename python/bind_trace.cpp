// granchain.trace: the heights z_i(t) of every particle on a regular grid of times and the events
// of the window (simulation/trajectory.hpp), validated by the command's own resolve_trace_spec;
// interruptible, returning the samples recorded so far.
#include <fmt/format.h>
#include <pybind11/numpy.h>

#include "bindings.hpp"
#include "config/input_error.hpp"
#include "config/run_options.hpp"
#include "config/trace_options.hpp"

namespace granchain::python {

namespace {

TraceSpec trace_spec(const py::kwargs& kwargs) {
  std::map<std::string, RawValue> raw;
  try {
    auto args = flag_arguments(kwargs);
    // Python cannot name a keyword `from`: t_from and t_to stand for --from and --to.
    for (const auto& [py_name, flag] : {std::pair<const char*, const char*>{"t-from", "from"}, {"t-to", "to"}})
      if (auto v = take(args, py_name)) args[flag] = *v;
    for (const auto& [name, value] : args) {
      const Parameter* p = find_parameter(trace_window_parameters(), name);
      if (p == nullptr) p = find_parameter(run_parameters(), name);
      raw[name] = keyword_value(value, p);
    }
    return resolve_trace_spec(raw);
  } catch (const InputError& e) {
    // --from and --to, and from and to in a range, are t_from and t_to here.
    std::string m = e.what();
    for (const auto& [flag, keyword] : {std::pair<std::string, std::string>{"--from", "t_from"}, {"--to", "t_to"},
                                        {"from = ", "t_from = "}, {"< to <", "< t_to <"}, {"<= from <", "<= t_from <"},
                                        {"at to =", "at t_to ="}, {"(to - from)", "(t_to - t_from)"}})
      for (std::size_t at = m.find(flag); at != std::string::npos; at = m.find(flag, at + keyword.size())) m.replace(at, flag.size(), keyword);
    m = keyword_message(keyword_message(m, run_parameters()), trace_window_parameters());
    throw InputError(m);
  }
}

py::dict trace(const py::kwargs& kwargs) {
  const TraceSpec spec = trace_spec(kwargs);
  Trajectory tr;
  std::atomic<bool> cancel{false};
  std::optional<py::error_already_set> stop = run_interruptible(cancel, [&] { tr = record_trajectory(spec, &cancel); });
  const auto S = static_cast<py::ssize_t>(tr.t.size());
  const auto N = static_cast<py::ssize_t>(spec.run.params.N);
  py::array_t<double> t(S), z({S, N}), v({S, N});
  auto tw = t.mutable_unchecked<1>();
  auto zw = z.mutable_unchecked<2>();
  auto vw = v.mutable_unchecked<2>();
  for (py::ssize_t s = 0; s < S; ++s) {
    const auto su = static_cast<std::size_t>(s);
    tw(s) = tr.t[su];
    for (py::ssize_t i = 0; i < N; ++i) {
      zw(s, i) = tr.z[su][static_cast<std::size_t>(i)];
      vw(s, i) = tr.v[su][static_cast<std::size_t>(i)];
    }
  }
  const auto E = static_cast<py::ssize_t>(tr.events.size());
  py::array_t<double> et(E), speed(E);
  py::array_t<std::int32_t> ei(E), ej(E);
  py::list kind;
  for (py::ssize_t k = 0; k < E; ++k) {
    const Event& e = tr.events[static_cast<std::size_t>(k)];
    et.mutable_at(k) = e.t;
    speed.mutable_at(k) = e.speed;
    const bool floor = e.kind == EventKind::FloorHit || e.kind == EventKind::FloorContact;
    ei.mutable_at(k) = floor ? 0 : e.i + 1;  // particles from 1 at the bottom, the floor as 0
    ej.mutable_at(k) = floor ? 1 : e.i + 2;
    kind.append(event_kind_name(e.kind));
  }
  py::dict events;
  events["t"] = et;
  events["kind"] = py::array(kind);
  events["i"] = ei;
  events["j"] = ej;
  events["speed"] = speed;
  py::dict params;
  params["setup"] = spec.free_space ? "free" : "driven";
  params["N"] = spec.run.params.N;
  params["e"] = spec.run.params.e;
  params["k"] = spec.run.params.k;
  params["T0"] = spec.run.params.kT0;
  if (!spec.free_space && spec.run.drive.plate()) {
    params["drive"] = std::string(drive_name(spec.run.drive.kind));
    params["plate_A"] = spec.run.drive.A;
    params["plate_omega"] = spec.run.drive.omega;
  }
  params["engine"] = std::string(engine_name(spec.run.engine.kind));
  params["seed"] = spec.run.seed;
  params["t_from"] = spec.t_from;
  params["t_to"] = spec.t_to;
  params["dt"] = spec.dt;
  if (spec.free_space) params["realization"] = spec.realization;
  py::dict d;
  d["parameters"] = params;
  d["t"] = t;
  d["z"] = z;
  d["v"] = v;
  if (!tr.plate.empty()) {  // the plate's surface at each sample
    py::array_t<double> plate(S);
    for (py::ssize_t s = 0; s < S; ++s) plate.mutable_at(s) = tr.plate[static_cast<std::size_t>(s)];
    d["plate"] = plate;
  } else {
    d["plate"] = py::none();
  }
  d["events"] = events;
  d["interrupted"] = stop.has_value() || tr.interrupted;
  if (stop && !stop->matches(PyExc_KeyboardInterrupt)) throw std::move(*stop);
  return d;
}

}  // namespace

void bind_trace(py::module_& m) {
  m.def("trace", &trace,
        "Record the heights z_i(t) of every particle on a grid of times (granchain trace): the run parameters that trace "
        "takes, setup ('driven' or 'free'), t_from, t_to, dt, and for free space a, v0, dv0, realization. Returns a dict: "
        "t (S), z and v (S x N), plate (S: the surface of a vibrating plate, or None), events (t, kind, i, j, speed), parameters, "
        "interrupted.");
  m.def("trace_parameters", [] {
    py::list l = parameter_list(trace_window_parameters());
    for (const Parameter& p : run_parameters())
      if (p.uses & kUseTrace) l.append(parameter_list({p})[0]);
    return l;
  }, "The parameters of trace(): its own (setup, from as t_from, to as t_to, dt, a, v0, dv0, realization) and the run "
     "parameters it takes.");
}

}  // namespace granchain::python
