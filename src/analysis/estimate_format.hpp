#pragma once
// A measured value with its error as text, for reports and warnings.
#include <string>

#include "analysis/blocking.hpp"

namespace granchain {

// "12.345 ± 0.012": the error to two significant digits, the value to the same decimal place.
std::string format_with_error(double value, double error);
std::string format_estimate(const Estimate& e);

}  // namespace granchain
