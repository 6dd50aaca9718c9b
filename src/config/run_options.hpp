#pragma once
// The parameters of `granchain run`: one table that defines the flags, the config-file keys,
// their help texts, defaults and valid ranges, so that all three always agree.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "config/parameter.hpp"
#include "simulation/driven_run.hpp"

namespace granchain {

struct RunOptions {
  RunSpec spec;
  std::string db_path = "granchain.db";
  bool use_db = true;
};

// Every parameter that may come from a flag or a config file (config/parameter.hpp).
const std::vector<Parameter>& run_parameters();

// Parses and validates raw values (unknown keys, bad numbers, out-of-range values all throw
// InputError with one line naming the parameter and its valid range) and fills in defaults:
// T = 1e4 for N < 50 and 1e3 for N >= 50 (the paper's choice), transient = T / 10.
RunOptions resolve_run_options(const std::map<std::string, RawValue>& raw);

// The paper's measuring time, the default of T: 1e4 for N < 50, 1e3 for N >= 50.
double default_measuring_time(int N);

// The shortest interval a clock resolves at time t: 1e6 times its resolution there, the span a
// contact, a profile sample or a trace step must at least have. A double clock (profile samples,
// trace steps, the time-stepped and hard engines) resolves ulp(t); the exact engine's FineTime
// clock (fine = true) resolves 2^-53 ulp(t).
double shortest_resolved_time(double t, bool fine = false);

// The clock's resolution limit of a soft contact: a contact (tau_c, Eqs. Dd, tauc) must last at
// least 1e6 resolutions of the engine's clock at the latest time t it can happen, i.e.
// k <= m (pi^2 + ln^2 e) / (2 shortest_resolved_time(t, fine)^2). The largest such k.
double largest_resolved_k(double m, double e, double t, bool fine = false);

// The number of clock resolutions that a resolved interval spans (shortest_resolved_time).
constexpr double kResolutionSteps = 1e6;

}  // namespace granchain
