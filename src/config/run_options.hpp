#pragma once
// The parameters of `granchain run`: one table that defines the flags, the config-file keys,
// their help texts, defaults and valid ranges, so that all three always agree.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "simulation/driven_run.hpp"

namespace granchain {

struct RunOptions {
  RunSpec spec;
  std::string db_path = "granchain.db";
  bool use_db = true;
};

struct ParameterInfo {
  std::string name;          // flag without "--", also the config-file key
  std::string help;          // meaning, valid range and default
  std::string type;          // INT, REAL, NAME or PATH, for --help
};

// Every parameter that may come from a flag or a config file.
const std::vector<ParameterInfo>& run_parameters();

// A raw value and where it came from (for error messages).
struct RawValue {
  std::string text;
  std::string source;  // "" for the command line, else "config file 'x'"
};

// Parses and validates raw values (unknown keys, bad numbers, out-of-range values all throw
// InputError with one line naming the parameter and its valid range) and fills in defaults:
// T = 1e4 for N < 50 and 1e3 for N >= 50 (the paper's choice), transient = T / 10.
RunOptions resolve_run_options(const std::map<std::string, RawValue>& raw);

// The shortest interval a clock resolves at time t: 1e6 times its resolution there, the span a
// contact, a profile sample or a trace step must at least have. A double clock (profile samples,
// trace steps, the time-stepped and hard engines) resolves ulp(t); the exact engine's FineTime
// clock (fine = true) resolves 2^-53 ulp(t).
double shortest_resolved_time(double t, bool fine = false);

// The clock's resolution limit of a soft contact: a contact (tau_c, Eqs. Dd, tauc) must last at
// least 1e6 resolutions of the engine's clock at the latest time t it can happen, i.e.
// k <= m (pi^2 + ln^2 e) / (2 shortest_resolved_time(t, fine)^2). The largest such k.
double largest_resolved_k(double m, double e, double t, bool fine = false);

// A free-space or wall collapse (granchain collapse) has no measuring time: its clock runs over
// the launch, t ~ 2 (N + 1)(a + d) / v0 (the outer particles reach the middle, or the wall, by
// (N - 1)(a + d) / 2v0 and (N a + (N - 1) d) / v0, with a factor 2 for the spread of speeds and the
// rebounds). Throws InputError "--k: ... is out of range" when k exceeds largest_resolved_k there
// for the engine's clock (fine: the exact engine's).
void check_collapse_contact_time(double k, double e, double m, double d, int N, double a, double v0, bool fine);
// The launch must play out well inside the count's clock limit (a launch is given up at t = 1e7,
// simulation/collapse_run.hpp): 2 (N + 1)(a + d) / v0 <= 1e6. Throws InputError naming --a or --v0.
void check_collapse_launch(int N, double a, double v0, double d);
// The hard engine's TC time acts on collisions within t_c of one another; the collapse watch
// spans --collapse-time: t_c = 0 (off) or t_c >= collapse-time. Throws InputError naming --tc.
void check_collapse_tc(double tc, double collapse_time);

}  // namespace granchain
