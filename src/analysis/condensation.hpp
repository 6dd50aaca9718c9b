#pragma once
// The partially condensed state (paper Sec. III.C.2, Fig. partial_cond): a cold, dense layer near
// the floor. Above e ~ 0.91 (N = 25) the kinetic energy K_i falls monotonically with height, as the
// floor's energy is dissipated upward; in the partially condensed state K_i has a dip near the
// bottom above which it rises again (an inversion layer), and sigma_i / sigma_0,i dips there too.
#include <cstddef>
#include <vector>

namespace granchain::analysis {

struct ParticleValue {
  double value = 0, error = 0;
};

// Which condensed state a column with a K_i inversion is in (paper Sec. III.C.2): partially
// condensed, a cold dense layer near the floor under a hotter fluid layer (0.84 <~ e <~ 0.90 at
// N = 25), or condensed as a whole, cold throughout with only its free surface warmer.
enum class CondensedState { None, Whole, Partial };
const char* condensed_state_name(CondensedState s);  // "none", "whole", "partial"

// How many standard errors a rise (or drop) of K_i must reach when the test compares `pairs` pairs
// of particles: the z whose Bonferroni bound on a chance flag, pairs * Q(z) with Q the normal upper
// tail, equals that of z = 3 over the 234 pairs the inversion test compares at N = 25 (the paper's
// Fig. partial_cond) — never below 3. The largest chance rise grows with the number of pairs (at a
// fixed z = 3 a flat N = 1000 profile is flagged nearly always), so the test's false-alarm rate
// is held at N = 25's whatever N: z = 3.40 at N = 50, 3.76 at 100, 4.10 at 200, 4.50 at 500,
// 4.79 at 1000.
double pair_test_threshold(std::size_t pairs);
// The pairs (i, j > i, i in the lower half) the inversion test compares in a column of n particles.
std::size_t inversion_pairs(std::size_t n);

struct CondensationCheck {
  bool condensed = false;     // an inversion of K_i above its dip, by more than z standard errors
  // Partial when a particle above the dip and below the free surface (the top max(2, N/10)
  // particles) is warmer than some particle above it by more than z standard errors: an interior
  // hot layer, cooler again towards the top. `hot` and `cooler_above` (1-based) are the pair with
  // the largest such drop, hot_drop = K_hot - K_cooler_above. Whole for any other inversion, where
  // K_i only rises from the dip towards the free surface (the warmest part of a condensed column);
  // None without an inversion.
  CondensedState state = CondensedState::None;
  int hot = 0, cooler_above = 0;
  double hot_drop = 0, hot_drop_error = 0;
  int dip = 0;                // 1-based particle i of the most significant rise K_j - K_i (j > i)
  double rise = 0, rise_error = 0;  // that rise and its standard error
  // The threshold of both searches in standard errors, pair_test_threshold(inversion_pairs(N)):
  // the hot-layer search compares of order N^2 pairs as well, and keeps z = 3 at N = 25.
  double z = 0;
  std::size_t pairs = 0;  // inversion_pairs(N), the pairs the inversion search compares
  int sigma_dip = 0;          // 1-based particle of the lowest sigma_i / sigma_0,i (0 without sigma_0)
  double sigma_ratio_min = 0;
};

// K: K_i for i = 1..N (bottom first). sigma, sigma0 (optional, same length): sigma_i and the
// elastic column's sigma_0,i. Condensed when K_j - K_i > z sqrt(err_j^2 + err_i^2) for a particle
// i in the lower half of the column (i <= ceil(N/2)) and some j above it, z = pair_test_threshold(
// inversion_pairs(N)) for the pairs compared: a dip near the floor with a warmer layer above it, whatever the
// coldest particles at the top do. `dip` is the i, and `rise` the K_j - K_i, of the pair with the
// largest such ratio.
CondensationCheck detect_partial_condensation(const std::vector<ParticleValue>& K,
                                              const std::vector<ParticleValue>& sigma = {},
                                              const std::vector<double>& sigma0 = {});

}  // namespace granchain::analysis
