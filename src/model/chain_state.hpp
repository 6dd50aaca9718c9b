#pragma once
#include <vector>

namespace granchain {

// Positions z_i (centres) and velocities v_i of the N particles at time t, index 0 = bottom.
struct ChainState {
  double t = 0.0;
  std::vector<double> z;
  std::vector<double> v;
};

}  // namespace granchain
