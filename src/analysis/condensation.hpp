#pragma once
// The partially condensed state (paper Sec. III.C.2, Fig. partial_cond): a cold, dense layer near
// the floor. Above e ~ 0.91 (N = 25) the kinetic energy K_i falls monotonically with height, as the
// floor's energy is dissipated upward; in the partially condensed state K_i has a dip near the
// bottom above which it rises again (an inversion layer), and sigma_i / sigma_0,i dips there too.
#include <vector>

namespace granchain::analysis {

struct ParticleValue {
  double value = 0, error = 0;
};

struct CondensationCheck {
  bool condensed = false;     // an inversion of K_i above its dip, by more than z standard errors
  int dip = 0;                // 1-based particle of the lowest K_i
  double rise = 0, rise_error = 0;  // largest K_j - K_dip above the dip, and its standard error
  int sigma_dip = 0;          // 1-based particle of the lowest sigma_i / sigma_0,i (0 without sigma_0)
  double sigma_ratio_min = 0;
};

// K: K_i for i = 1..N (bottom first). sigma, sigma0 (optional, same length): sigma_i and the
// elastic column's sigma_0,i. Condensed when K_j - K_dip > z sqrt(err_j^2 + err_dip^2) for some j
// above the dip particle `dip` = argmin K_i.
CondensationCheck detect_partial_condensation(const std::vector<ParticleValue>& K,
                                              const std::vector<ParticleValue>& sigma = {},
                                              const std::vector<double>& sigma0 = {}, double z = 3.0);

}  // namespace granchain::analysis
