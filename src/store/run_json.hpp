#pragma once
// JSON form of a run: what `granchain run --json` prints and what the store keeps as provenance.
#include <nlohmann/json.hpp>

#include "simulation/driven_run.hpp"

namespace granchain {

nlohmann::json to_json(const Estimate& e);
nlohmann::json run_spec_to_json(const RunSpec& spec);
// Everything about a finished run: parameters, derived constants, observables with errors,
// per-particle profiles, cost. Wall time and code version are included; the physics is not
// affected by them.
nlohmann::json run_result_to_json(const RunResult& r);
// The inverse, for what the store and the MPI sweep need: every number round-trips exactly
// (nlohmann writes doubles with 17 significant digits). Per-particle profile estimates keep value
// and error only (their block counts are not in the JSON).
RunResult run_result_from_json(const nlohmann::json& j);
// One blocking curve (the array under "blocking"."n_coll" or "mean_height"); null numbers read as NaN.
std::vector<BlockingLevel> blocking_curve_from_json(const nlohmann::json& levels);

}  // namespace granchain
