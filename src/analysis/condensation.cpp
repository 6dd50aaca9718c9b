#include "analysis/condensation.hpp"

#include <cmath>
#include <stdexcept>

namespace granchain::analysis {

CondensationCheck detect_partial_condensation(const std::vector<ParticleValue>& K, const std::vector<ParticleValue>& sigma,
                                              const std::vector<double>& sigma0, double z) {
  if (K.size() < 3) throw std::invalid_argument("partial condensation: needs at least 3 particles");
  CondensationCheck c;
  std::size_t dip = 0;
  for (std::size_t i = 1; i < K.size(); ++i)
    if (K[i].value < K[dip].value) dip = i;
  c.dip = static_cast<int>(dip) + 1;
  for (std::size_t j = dip + 1; j < K.size(); ++j) {
    const double rise = K[j].value - K[dip].value;
    if (rise > c.rise) {
      c.rise = rise;
      c.rise_error = std::hypot(K[j].error, K[dip].error);
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
