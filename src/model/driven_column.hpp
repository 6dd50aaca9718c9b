#pragma once
// Set-up of the driven column (paper Sec. II.A, III.A): particles stacked above the thermal floor
// or a vibrating plate (plate_motion.hpp).
#include <cstdint>
#include <memory>

#include "model/chain_parameters.hpp"
#include "model/chain_state.hpp"
#include "model/floor.hpp"
#include "model/plate_motion.hpp"

namespace granchain {

// Height of particle 1's centre when its lower edge touches the floor at z = 0.
inline double floor_contact_height(const ChainParameters& p) { return 0.5 * p.d; }

// Initial state of Sec. III.A: no overlaps, random velocities. The lowest particle starts
// above the floor, every gap (floor to particle 1, then between neighbours) is uniform in
// [0, d), and each velocity is Maxwellian at the floor temperature, N(0, kT0/m). Above a plate
// the stack starts from the top of the plate's stroke (z = A) instead of z = 0.
ChainState driven_column_initial_state(const ChainParameters& p, std::uint64_t seed, const DriveSpec& drive = {});

// What drives the column of a run: the thermal floor at k_B T0 (its own random stream of the
// seed), or the plate of `drive` with its phase drawn uniformly in [0, 2 pi) from the seed and
// the restitution e of the particles (the hard-sphere limit of its contact).
std::unique_ptr<FloorDrive> column_drive(const ChainParameters& p, const DriveSpec& drive, std::uint64_t seed);

}  // namespace granchain
