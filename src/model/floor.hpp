#pragma once
// The thermal floor at z = 0 (paper Sec. II.A). Its surface touches the lower edge of particle 1,
// i.e. a floor hit happens when the centre z_1 comes down to d/2. The hit is instantaneous: the
// particle leaves upward with a fresh speed drawn from the floor, whatever its incoming speed.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "model/plate_motion.hpp"
#include "model/random.hpp"
#include "model/state_archive_fwd.hpp"

namespace granchain {

// What drives the column from below; engines own none of the randomness. Either a floor at z = 0
// that particle 1 bounces off at once (bounce), or a vibrating plate (plate() not null) that it
// touches with the contact law of plate_motion.hpp.
class FloorDrive {
 public:
  virtual ~FloorDrive() = default;
  // Upward speed of particle 1 leaving the floor, given its downward speed on arrival.
  virtual double bounce(double incoming_speed) = 0;
  // The plate's motion, or nullptr for a floor at rest at z = 0.
  virtual const PlateMotion* plate() const { return nullptr; }
  // What changes as it drives (a random generator, a script's position), for a run's checkpoint
  // (model/state_archive.hpp); nothing for a drive without such state.
  virtual void save(StateArchive&) const {}
  virtual void restore(const StateArchive&) {}
};

// Flux-weighted Maxwell distribution p(v) = (m v / kT0) exp(-m v^2 / (2 kT0)), v > 0
// (the first equation of Sec. II.A), sampled by inverting its CDF 1 - exp(-m v^2 / (2 kT0)).
class ThermalFloor final : public FloorDrive {
 public:
  ThermalFloor(double kT0, double m, std::uint64_t seed);
  double next_speed();
  double bounce(double) override { return next_speed(); }
  void save(StateArchive& out) const override;
  void restore(const StateArchive& in) override;

 private:
  double two_kT_over_m_;
  Rng rng_;
};

// A fixed sequence of speeds, for deterministic comparisons between engines.
class ScriptedFloor final : public FloorDrive {
 public:
  explicit ScriptedFloor(std::vector<double> speeds) : speeds_(std::move(speeds)) {}
  double next_speed();  // throws std::out_of_range when the script is used up
  double bounce(double) override { return next_speed(); }
  std::size_t used() const { return next_; }
  void save(StateArchive& out) const override;
  void restore(const StateArchive& in) override;

 private:
  std::vector<double> speeds_;
  std::size_t next_ = 0;
};

// A hard wall with restitution coefficient r: the particle leaves with r times the speed it
// arrived with. r = 1: an elastic wall. r = e: the wall of Bernu and Mazighi's spheres thrown
// against a wall (paper Sec. II.C), which acts on particle 1 as its mirror image would, so that
// N spheres on the wall are half of a symmetric 2N-sphere chain in free space (Eq. symmetry).
class Wall final : public FloorDrive {
 public:
  explicit Wall(double restitution = 1.0) : r_(restitution) {}
  double bounce(double incoming_speed) override { return r_ * incoming_speed; }

 private:
  double r_;
};

// A vibrating plate (plate_motion.hpp). bounce() is the hard-sphere limit of its contact: speeds
// relative to the plate, the outgoing one e times the incoming one.
class VibratingPlate final : public FloorDrive {
 public:
  VibratingPlate(const PlateMotion& motion, double restitution) : motion_(motion), e_(restitution) {}
  double bounce(double incoming_relative_speed) override { return e_ * incoming_relative_speed; }
  const PlateMotion* plate() const override { return &motion_; }

 private:
  PlateMotion motion_;
  double e_;
};

// CDF of the thermal floor's speed distribution, for tests and analysis.
double thermal_floor_speed_cdf(double v, double kT0, double m);

}  // namespace granchain
