#include "analysis/condensation.hpp"

#include <cmath>
#include <stdexcept>

namespace granchain::analysis {

CondensationCheck detect_partial_condensation(const std::vector<ParticleValue>& K, const std::vector<ParticleValue>& sigma,
                                              const std::vector<double>& sigma0, double z) {
  if (K.size() < 3) throw std::invalid_argument("partial condensation: needs at least 3 particles");
  CondensationCheck c;
  // A dip near the floor: the particle i in the lower half of the column (i <= ceil(N/2)) above
  // which some K_j (j > i) is warmer by the most standard errors. The top particles of a
  // dissipative column are its coldest, which is no inversion, so i is not looked for there.
  double best = -INFINITY;
  c.dip = 1;
  for (std::size_t i = 0; i < (K.size() + 1) / 2; ++i)
    for (std::size_t j = i + 1; j < K.size(); ++j) {
      const double rise = K[j].value - K[i].value, error = std::hypot(K[j].error, K[i].error);
      const double pull = error > 0 ? rise / error : (rise > 0 ? INFINITY : 0.0);
      if (pull > best) {
        best = pull;
        c.dip = static_cast<int>(i) + 1;
        c.rise = rise;
        c.rise_error = error;
      }
    }
  c.condensed = c.rise > z * c.rise_error && c.rise > 0;
  if (!sigma.empty() && sigma.size() == K.size() && sigma0.size() == K.size()) {
    c.sigma_ratio_min = sigma[0].value / sigma0[0];
    c.sigma_dip = 1;
    for (std::size_t i = 1; i < sigma.size(); ++i) {
      const double r = sigma[i].value / sigma0[i];
      if (r < c.sigma_ratio_min) {
        c.sigma_ratio_min = r;
        c.sigma_dip = static_cast<int>(i) + 1;
      }
    }
  }
  return c;
}

}  // namespace granchain::analysis
