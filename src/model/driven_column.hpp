#pragma once
// Set-up of the driven column (paper Sec. II.A, III.A): particles stacked above the thermal floor.
#include <cstdint>

#include "model/chain_parameters.hpp"
#include "model/chain_state.hpp"

namespace granchain {

// Height of particle 1's centre when its lower edge touches the floor at z = 0.
inline double floor_contact_height(const ChainParameters& p) { return 0.5 * p.d; }

// Initial state of Sec. III.A: no overlaps, random velocities. The lowest particle starts
// above the floor, every gap (floor to particle 1, then between neighbours) is uniform in
// [0, d), and each velocity is Maxwellian at the floor temperature, N(0, kT0/m).
ChainState driven_column_initial_state(const ChainParameters& p, std::uint64_t seed);

}  // namespace granchain
