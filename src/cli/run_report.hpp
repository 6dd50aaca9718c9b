#pragma once
// Human-readable output of a run for the terminal.
#include <cstdint>
#include <optional>
#include <string>

#include "analysis/estimate_format.hpp"
#include "simulation/driven_run.hpp"

namespace granchain {

// Summary of a run; `stored` names where it was written ("" if it was not).
std::string run_summary(const RunResult& r, const std::string& stored);

}  // namespace granchain
