#pragma once
// Counts collisions inside the measuring window [t_begin, t_end), binned in time for errors.
// Paper Sec. III.A: N_coll counts every separation of two touching particles and every floor hit;
// n_coll = N_coll / (N T).
#include <cstdint>

#include "analysis/blocking.hpp"
#include "engines/events.hpp"

namespace granchain {

class CollisionCounter final : public EventSink {
 public:
  CollisionCounter(double t_begin, double t_end, int bins);
  void on_event(const Event& event) override;

  std::uint64_t particle_collisions() const { return pp_; }
  std::uint64_t floor_hits() const { return floor_; }

  // n_coll = (pp + floor) / (N T) with its blocked standard error.
  Estimate collision_rate_per_particle(int N) const;
  // Halves check (analysis/blocking.hpp) of n_coll over the window.
  StationarityCheck collision_rate_stationarity(int N) const;
  // The blocking curve behind n_coll's error: the standard error at every level (analysis/blocking.hpp).
  std::vector<BlockingLevel> collision_rate_blocking(int N) const;
  // Floor hits per unit time.
  Estimate floor_hit_rate() const;
  // Particle-particle collisions per unit time (all pairs together).
  Estimate particle_collision_rate() const;
  // The counts and bins so far, for a run's checkpoint (model/state_archive.hpp).
  void save(StateArchive& out) const;
  void restore(const StateArchive& in);

 private:
  // components per bin: particle-particle collisions, floor hits, bin duration
  enum : int { kPP = 0, kFloor = 1, kTime = 2, kComponents = 3 };
  static Estimator n_coll(int N);  // (pp + floor) / (N time) of summed bins
  double t_begin_, t_end_, bin_width_;
  BinnedSums sums_;
  std::uint64_t pp_ = 0, floor_ = 0;
};

}  // namespace granchain
