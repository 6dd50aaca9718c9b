#include "model/floor.hpp"

#include <cmath>
#include <stdexcept>

#include "model/state_archive.hpp"

namespace granchain {

ThermalFloor::ThermalFloor(double kT0, double m, std::uint64_t seed)
    : two_kT_over_m_(2.0 * kT0 / m), rng_(seed) {}

double ThermalFloor::next_speed() {
  const double u = rng_.uniform01();  // [0, 1): 1 - u in (0, 1], log finite
  return std::sqrt(-two_kT_over_m_ * std::log1p(-u));
}

void ThermalFloor::save(StateArchive& out) const { rng_.save(out["rng"]); }
void ThermalFloor::restore(const StateArchive& in) {
  if (!in.contains("rng")) throw StateArchiveError("saved state: the thermal floor has no random generator");
  rng_.restore(in.at("rng"));
}

void ScriptedFloor::save(StateArchive& out) const { out["used"] = next_; }
void ScriptedFloor::restore(const StateArchive& in) {
  const auto used = saved_value<std::size_t>(in, "used");
  if (used > speeds_.size()) throw StateArchiveError("saved state: the scripted floor used more speeds than it has");
  next_ = used;
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
