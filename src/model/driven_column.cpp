#include "model/driven_column.hpp"

#include <cmath>

#include "model/random.hpp"

namespace granchain {

ChainState driven_column_initial_state(const ChainParameters& p, std::uint64_t seed) {
  Rng rng(derive_seed(seed, static_cast<std::uint64_t>(RandomStream::InitialState)));
  ChainState s;
  s.z.resize(p.N);
  s.v.resize(p.N);
  double z = floor_contact_height(p);
  const double v_thermal = std::sqrt(p.kT0 / p.m);
  for (int i = 0; i < p.N; ++i) {
    z += (i == 0 ? 0.0 : p.d) + p.d * rng.uniform01();
    s.z[i] = z;
  }
  for (int i = 0; i < p.N; ++i) s.v[i] = v_thermal * rng.normal();
  return s;
}

}  // namespace granchain
