#include "model/driven_column.hpp"

#include <cmath>
#include <numbers>

#include "model/random.hpp"

namespace granchain {

ChainState driven_column_initial_state(const ChainParameters& p, std::uint64_t seed, const DriveSpec& drive) {
  Rng rng(derive_seed(seed, static_cast<std::uint64_t>(RandomStream::InitialState)));
  ChainState s;
  s.z.resize(p.N);
  s.v.resize(p.N);
  double z = floor_contact_height(p) + (drive.plate() ? drive.A : 0.0);
  const double v_thermal = std::sqrt(p.kT0 / p.m);
  for (int i = 0; i < p.N; ++i) {
    z += (i == 0 ? 0.0 : p.d) + p.d * rng.uniform01();
    s.z[i] = z;
  }
  for (int i = 0; i < p.N; ++i) s.v[i] = v_thermal * rng.normal();
  return s;
}

std::unique_ptr<FloorDrive> column_drive(const ChainParameters& p, const DriveSpec& drive, std::uint64_t seed) {
  if (!drive.plate())
    return std::make_unique<ThermalFloor>(p.kT0, p.m, derive_seed(seed, static_cast<std::uint64_t>(RandomStream::Floor)));
  Rng rng(derive_seed(seed, static_cast<std::uint64_t>(RandomStream::PlatePhase)));
  const double phase = 2.0 * std::numbers::pi * rng.uniform01();
  return std::make_unique<VibratingPlate>(PlateMotion(drive.kind, drive.A, drive.omega, phase), p.e);
}

}  // namespace granchain
