#pragma once
// JSON form of a collapse count (granchain collapse --json, and the store's provenance column).
#include <nlohmann/json.hpp>

#include "simulation/collapse_run.hpp"

namespace granchain {

// A finite number, or null for infinity and NaN (JSON has neither).
nlohmann::json number_or_null(double x);

// Parameters, derived constants, n_tot with its standard error, the collapsed fraction and the
// cost. k = infinity (hard spheres) and undefined values (no realisation finished) are null.
nlohmann::json collapse_result_to_json(const CollapseResult& r);

}  // namespace granchain
