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
  // A checkpoint (store/run_checkpoint.hpp): the run's state saved to this file every
  // checkpoint_every wall seconds and when it is interrupted, and resumed from it; "" none.
  std::string checkpoint_path;
  double checkpoint_every = 600.0;
};

// Every parameter that may come from a flag or a config file (config/parameter.hpp).
const std::vector<Parameter>& run_parameters();

// A parameter that a driven-column run keeps in the store's runs table (its store_column): the
// entry, and whether the column may be NULL (tc, which only the hard engine takes; bins, which runs
// of the first store version lack). A column added to the table later is NULL in older runs.
struct StoredParameter {
  const Parameter* parameter;
  bool nullable;
};
// The stored parameters in the order of a run's identity (RunIdentity, then table order): the
// order of the point key and of the store's parameter columns.
const std::vector<StoredParameter>& stored_run_parameters();
// The value of each stored parameter in a run (aligned with stored_run_parameters()) and whether
// it acts there: by its engine scope (a Hard one, tc, only for the hard-sphere engine, a TimeStepped
// one, dt_factor, only for the time-stepped engines, any other always: k too, infinite for hard
// spheres) and, where its entry says so, by the run's other
// parameters (a drive's amplitude only with that drive). The store keeps NULL for a nullable one
// that does not act (tc of a soft engine).
struct StoredValue {
  TypedValue value;
  bool acts;
};
std::vector<StoredValue> stored_values(const RunSpec& spec);
// The seed is a 64-bit unsigned number (a sweep derives seeds over the whole range), held as the
// signed integer of the same bits as SQLite keeps it; the edges (key, JSON, Python) show it unsigned.
inline bool unsigned_integer(const Parameter& p) { return p.identity == RunIdentity::Seed; }
// Sets the i-th stored parameter of a spec from a stored value, without the range checks (the
// store keeps what passed them). Throws InputError for a name nothing takes (an unknown engine).
void set_stored_value(RunSpec& spec, std::size_t i, const TypedValue& value);

// Parses and validates raw values (unknown keys, bad numbers, out-of-range values all throw
// InputError with one line naming the parameter and its valid range) and fills in defaults:
// T = 1e4 for N < 50 and 1e3 for N >= 50 (the paper's choice), transient = T / 10.
RunOptions resolve_run_options(const std::map<std::string, RawValue>& raw);

// Turns on the engine's audit (EngineChoice::audit) for `run --audit` and Python's audit=True:
// InputError for an engine without one, or above a vibrating plate, which it does not cover.
void request_audit(RunOptions& o);

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
