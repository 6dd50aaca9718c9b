#pragma once
// The identity of a driven-column run: every parameter that can change its result, numbers in
// their shortest exact decimal form. Two runs with one key (seed included) give identical results,
// whichever thread, rank or machine ran them; the results store and sweeps use it to find a point.
// The key is read off the parameter table (config/run_options.cpp): each entry with a store
// column enters as `column=value`, in the order of its part of the identity (RunIdentity: engine,
// physics, window, engine options, seed), where it acts.
#include <string>
#include <vector>

#include "config/parameter.hpp"
#include "simulation/collapse_run.hpp"
#include "simulation/driven_run.hpp"

namespace granchain {

// The shortest decimal text that reads back as exactly x ("0.88", "100000000").
std::string exact_decimal(double x);

// "driven_column engine=exact N=25 e=0.88 k=100000000 T0=1 ... seed=7". Engine options enter
// only where they act: dt_factor for the time-stepped engines, tc for the hard engine.
std::string point_key(const RunSpec& spec);
// The trajectory a run follows: the physics, the engine (with the options that act) and the seed,
// without the window (T, transient) and the sampling. Runs with one trajectory key share their
// start, so they are one sample of the dynamics, never independent replicas.
std::string trajectory_key(const RunSpec& spec);
// The same without the seed: what a sweep point's seed is derived from.
std::string point_key_without_seed(const RunSpec& spec);

// The identity of a collapse count, read off its stored parameters (config/collapse_options.hpp)
// in their order: "collapse N=100 e=0.5 k=1e+17 engine=exact setup=free_space ... seed=1 dt_factor=100 tc=0". Two
// counts with one key are the same launches and give identical results.
std::string collapse_key(const CollapseSpec& spec);
// The same from the values of the stored parameters, in their order (a row of collapse_runs).
std::string collapse_key(const std::vector<TypedValue>& stored_values);

}  // namespace granchain
