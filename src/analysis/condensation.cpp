#include "analysis/condensation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace granchain::analysis {

const char* condensed_state_name(CondensedState s) {
  switch (s) {
    case CondensedState::Whole: return "whole";
    case CondensedState::Partial: return "partial";
    case CondensedState::None: break;
  }
  return "none";
}

namespace {

double normal_upper_tail(double z) { return 0.5 * std::erfc(z / std::numbers::sqrt2); }

}  // namespace

std::size_t inversion_pairs(std::size_t n) {
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < (n + 1) / 2; ++i) pairs += n - 1 - i;
  return pairs;
}

double pair_test_threshold(std::size_t pairs) {
  constexpr double z_reference = 3.0;
  if (pairs <= inversion_pairs(25)) return z_reference;
  const double tail = normal_upper_tail(z_reference) * static_cast<double>(inversion_pairs(25)) / static_cast<double>(pairs);
  double lo = z_reference, hi = 40.0;  // Q falls monotonically: bisect Q(z) = tail
  for (int it = 0; it < 200 && hi - lo > 1e-12; ++it) {
    const double mid = 0.5 * (lo + hi);
    (normal_upper_tail(mid) > tail ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

CondensationCheck detect_partial_condensation(const std::vector<ParticleValue>& K, const std::vector<ParticleValue>& sigma,
                                              const std::vector<double>& sigma0) {
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
  c.pairs = inversion_pairs(K.size());
  c.z = pair_test_threshold(c.pairs);
  c.condensed = c.rise > c.z * c.rise_error && c.rise > 0;
  // The hot layer: a particle j above the dip and below the free surface (the top max(2, N/10))
  // warmer than some particle m above it, the pair with the largest drop in standard errors.
  const std::size_t n = K.size();
  const std::size_t surface = std::max<std::size_t>(2, n / 10);
  double best_drop = -INFINITY;
  for (std::size_t j = static_cast<std::size_t>(c.dip); j + surface < n; ++j)
    for (std::size_t m = j + 1; m < n; ++m) {
      const double drop = K[j].value - K[m].value, error = std::hypot(K[j].error, K[m].error);
      const double pull = error > 0 ? drop / error : (drop > 0 ? INFINITY : 0.0);
      if (pull > best_drop) {
        best_drop = pull;
        c.hot = static_cast<int>(j) + 1;
        c.cooler_above = static_cast<int>(m) + 1;
        c.hot_drop = drop;
        c.hot_drop_error = error;
      }
    }
  if (c.condensed) {
    c.state = c.hot > 0 && c.hot_drop > c.z * c.hot_drop_error ? CondensedState::Partial : CondensedState::Whole;
  }
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
