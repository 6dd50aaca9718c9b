#include "model/collapse_setups.hpp"

#include "model/random.hpp"

namespace granchain {

namespace {
// xi uniform in [-1, 1), one per particle, from the InitialState stream.
std::vector<double> launch_noise(int N, std::uint64_t seed) {
  Rng rng(derive_seed(seed, static_cast<std::uint64_t>(RandomStream::InitialState)));
  std::vector<double> xi(N);
  for (double& x : xi) x = 2.0 * rng.uniform01() - 1.0;
  return xi;
}
}  // namespace

ChainState free_space_launch_state(const ChainParameters& p, const LaunchParameters& launch, std::uint64_t seed) {
  const std::vector<double> xi = launch_noise(p.N, seed);
  ChainState s;
  s.z.resize(p.N);
  s.v.resize(p.N);
  for (int i = 1; i <= p.N; ++i) {
    // (i - (N+1)/2) written as (2i - N - 1)/2 so that the middle particle sits at exactly 0.
    const double x = 0.5 * (2 * i - p.N - 1) * (p.d + launch.a);
    const double sgn = (x > 0) - (x < 0);
    s.z[i - 1] = x;
    s.v[i - 1] = -launch.v0 * sgn + launch.dv0 * xi[i - 1];
  }
  return s;
}

ChainState wall_throw_state(const ChainParameters& p, const LaunchParameters& launch, std::uint64_t seed) {
  const std::vector<double> xi = launch_noise(p.N, seed);
  ChainState s;
  s.z.resize(p.N);
  s.v.resize(p.N);
  for (int i = 0; i < p.N; ++i) {
    s.z[i] = 0.5 * p.d + launch.a + i * (p.d + launch.a);
    s.v[i] = -launch.v0 + launch.dv0 * xi[i];
  }
  return s;
}

}  // namespace granchain
