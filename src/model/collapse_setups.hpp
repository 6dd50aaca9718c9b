#pragma once
// Set-ups for counting the collisions of one inelastic collapse (no drive): the free-space launch
// of the paper's Sec. III.D and Bernu and Mazighi's spheres thrown against a wall (Sec. II.C).
#include <cstdint>

#include "model/chain_parameters.hpp"
#include "model/chain_state.hpp"

namespace granchain {

struct LaunchParameters {
  double a = 1.0;    // free space between neighbours at t = 0
  double v0 = 1.0;   // inward (free space) or wall-ward speed
  double dv0 = 0.1;  // amplitude of the random part of the velocities
};

// Sec. III.D: x_i = (i - (N+1)/2)(d + a), v_i = -v0 sgn(x_i) + dv0 xi_i with xi_i uniform in
// [-1, 1), i = 1..N (the middle particle of an odd N has x = 0 and sgn 0). Random numbers from
// the InitialState stream of `seed`.
ChainState free_space_launch_state(const ChainParameters& p, const LaunchParameters& launch, std::uint64_t seed);

// N spheres thrown against a wall at z = 0 whose surface touches particle 1's lower edge when
// z_1 = d/2: particle 1 starts a gap a above it, neighbours a gaps a apart, all moving down at v0
// (plus dv0 xi_i, xi_i uniform in [-1, 1)). a = 0: a touching column, Bernu and Mazighi's case.
ChainState wall_throw_state(const ChainParameters& p, const LaunchParameters& launch, std::uint64_t seed);

}  // namespace granchain
