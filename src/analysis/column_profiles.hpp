#pragma once
// The classical observables of a vibrated column (Luding et al., PRE 49, 1634; Bernu et al., PRE 50,
// 4551), from the states of a trajectory sampled at equal times:
//   - the number density n(z) = <sum_i delta(z - z_i)> (particles per unit height; its integral is N)
//     and the granular temperature T(z) = m <(v - u(z))^2> of the particles found at height z, with
//     u(z) = <v> there (k_B = 1, as T0);
//   - the centre of mass z_cm = (1/N) sum_i z_i and its velocity against the plate's phase
//     theta in [0, 2 pi), beside the plate's own height and velocity: how the column follows the
//     plate through a cycle.
// Errors are batch means: the samples are cut into `blocks` consecutive blocks, each block's
// value computed alone, and the error is the standard deviation of the block values over
// sqrt(blocks). A block is long compared with the column's correlation time only if the window
// is; the caller chooses the window.
#include <vector>

namespace granchain::analysis {

struct BinnedValue {
  double value = 0, error = 0;
  bool measured = false;  // every block had samples in the bin (two for a temperature)
};

// The mean of a series of samples with its batch-means error over `blocks` blocks.
BinnedValue batch_mean(const std::vector<double>& x, int blocks);

// The first harmonic of a function of the phase sampled at the bin centres theta_b of [0, 2 pi):
// f(theta) ~ f0 + a cos theta + b sin theta, its amplitude sqrt(a^2 + b^2) and the phase of its
// maximum atan2(b, a) in (-pi, pi], with errors propagated from the bins' (taken as independent).
struct Harmonic {
  double amplitude = 0, amplitude_error = 0, phase = 0, phase_error = 0;
  bool measured = false;  // every bin measured
};
Harmonic first_harmonic(const std::vector<double>& theta, const std::vector<BinnedValue>& f);

struct HeightProfiles {
  double z_min = 0, width = 0;         // bin b covers [z_min + b width, z_min + (b + 1) width)
  std::vector<double> z;               // bin centres
  std::vector<BinnedValue> density;    // n(z), particles per unit height
  std::vector<BinnedValue> temperature;
  double outside = 0;                  // fraction of particle samples outside the bins
};

// z[s][i], v[s][i]: the samples; m the particle mass. Throws std::invalid_argument for fewer
// samples than blocks, blocks < 2, bins < 1 or width <= 0.
HeightProfiles height_profiles(const std::vector<std::vector<double>>& z, const std::vector<std::vector<double>>& v, double m,
                               double z_min, double width, int bins, int blocks);

struct PhaseProfiles {
  std::vector<double> theta;           // bin centres in [0, 2 pi)
  std::vector<BinnedValue> z_cm, v_cm; // the column's centre of mass and its velocity
  std::vector<BinnedValue> z_plate, v_plate;  // the plate's surface, averaged the same way
};

// phase[s] in [0, 2 pi): the plate's phase at sample s; plate_z, plate_v its surface. Throws
// std::invalid_argument as height_profiles, or when the lengths differ.
PhaseProfiles phase_profiles(const std::vector<std::vector<double>>& z, const std::vector<std::vector<double>>& v,
                             const std::vector<double>& phase, const std::vector<double>& plate_z, const std::vector<double>& plate_v,
                             int bins, int blocks);

}  // namespace granchain::analysis
