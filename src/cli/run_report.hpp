#pragma once
// Human-readable output of a run for the terminal.
#include <cstdint>
#include <optional>
#include <string>

#include "analysis/blocking.hpp"
#include "simulation/driven_run.hpp"

namespace granchain {

// "12.345 ± 0.012": the error to two significant digits, the value to the same decimal place.
std::string format_with_error(double value, double error);
std::string format_estimate(const Estimate& e);

// Summary of a run; `stored` names where it was written ("" if it was not).
std::string run_summary(const RunResult& r, const std::string& stored);

}  // namespace granchain
