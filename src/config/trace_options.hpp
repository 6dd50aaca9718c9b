#pragma once
// The options of a space-time trace (`granchain trace`, granchain.trace in Python): the run
// parameters that trace takes (config/run_options.hpp, those marked kUseTrace) and the trace's
// own, written once here: set-up, window, sampling interval, launch, realisation.
#include <map>
#include <string>
#include <vector>

#include "config/parameter.hpp"
#include "simulation/trajectory.hpp"

namespace granchain {

// The trace's own parameters: setup, from, to, dt, a, v0, dv0, realization (Python: t_from, t_to
// for the reserved word from).
const std::vector<Parameter>& trace_window_parameters();

// The trace from its run parameters and its own (raw values by name, either table; absent: the
// default), validated as the command validates them; InputError with one line otherwise: a soft
// engine only, samples and contacts resolved by the clock at `to`, at most 1e7 samples and 1e8
// heights.
TraceSpec resolve_trace_spec(const std::map<std::string, RawValue>& raw);

}  // namespace granchain
