#include "model/floor.hpp"

#include <cmath>
#include <stdexcept>

namespace granchain {

ThermalFloor::ThermalFloor(double kT0, double m, std::uint64_t seed)
    : two_kT_over_m_(2.0 * kT0 / m), rng_(seed) {}

double ThermalFloor::next_speed() {
  const double u = rng_.uniform01();  // [0, 1): 1 - u in (0, 1], log finite
  return std::sqrt(-two_kT_over_m_ * std::log1p(-u));
}

double ScriptedFloor::next_speed() {
  if (next_ >= speeds_.size()) throw std::out_of_range("scripted floor: no speeds left");
  return speeds_[next_++];
}

double thermal_floor_speed_cdf(double v, double kT0, double m) {
  if (v <= 0) return 0.0;
  return -std::expm1(-m * v * v / (2.0 * kT0));
}

}  // namespace granchain
