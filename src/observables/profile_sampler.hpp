#pragma once
// Per-particle profiles (paper Fig. partial_cond): time averages, over equally spaced samples of
// the state in the measuring window, of the height z_i, its standard deviation sigma_i and the
// kinetic energy K_i = m v_i^2 / 2, each with a blocked standard error.
#include <cstdint>
#include <vector>

#include "analysis/blocking.hpp"
#include "model/chain_state.hpp"

namespace granchain {

struct ParticleProfile {
  Estimate z_mean;  // <z_i>
  Estimate z_std;   // sigma_i = sqrt(<z_i^2> - <z_i>^2)
  Estimate kinetic; // K_i = <m v_i^2 / 2>
};

class ProfileSampler {
 public:
  // expected_samples fixes the binning: sample j goes to bin j * bins / expected_samples.
  ProfileSampler(int N, double m, std::int64_t expected_samples, int bins);
  void sample(const ChainState& s);
  std::int64_t samples() const { return taken_; }
  std::vector<ParticleProfile> profiles() const;
  // Halves check (analysis/blocking.hpp) of the column's mean height, the average of z_i over
  // the particles: a column still settling or drifting changes it between the window's halves.
  StationarityCheck height_stationarity() const;
  // The blocking curve of that mean height (analysis/blocking.hpp): how its standard error grows with
  // the block length, which shows the column's slow states (a condensed layer's) where they outlast a block.
  std::vector<BlockingLevel> height_blocking() const;
  // The samples' sums so far, for a run's checkpoint (model/state_archive.hpp).
  void save(StateArchive& out) const;
  void restore(const StateArchive& in);

 private:
  // components per bin: sample count, then per particle: sum dz, sum dz^2, sum v^2,
  // with dz = z - z_ref (z_ref = first sample) to keep sigma_i precise when it is tiny.
  Estimator mean_height() const;  // the average of z_i over the particles, of summed bins
  int n_;
  double m_;
  std::int64_t expected_;
  std::int64_t taken_ = 0;
  std::vector<double> z_ref_;
  BinnedSums sums_;
};

}  // namespace granchain
