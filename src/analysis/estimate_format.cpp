#include "analysis/estimate_format.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace granchain {

std::string format_with_error(double value, double error) {
  if (!std::isfinite(error) || error <= 0) return fmt::format("{:.6g}", value);
  const int exponent = static_cast<int>(std::floor(std::log10(error)));
  const int decimals = std::max(0, 1 - exponent);
  if (decimals > 12 || std::abs(value) >= 1e7 || (value != 0 && std::abs(value) < 1e-4))
    return fmt::format("{:.6g} ± {:.2g}", value, error);
  return fmt::format("{:.{}f} ± {:.{}f}", value, decimals, error, decimals);
}

std::string format_estimate(const Estimate& e) { return format_with_error(e.value, e.error); }

}  // namespace granchain
