#include "theory/collapse_theory.hpp"

#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <stdexcept>

namespace granchain::theory {

namespace {

void require(bool ok, const char* what) {
  if (!ok) throw std::domain_error(what);
}

void require_three_body(double e) {
  // Below 1e-150, e^2 and m'* ~ -1/(2e) leave the range of a double.
  if (!(e >= 1e-150 && e <= ec3())) {
    throw std::domain_error(fmt::format("e = {} outside the three-body collapse range 1e-150 <= e <= e_c(3) = 7 - 4 sqrt 3", e));
  }
}

// b^2 - 4e, clipped at zero: it vanishes at e_c(3) and only round-off makes it negative there.
double discriminant(double e) {
  const double b = 0.5 * (1.0 + e);
  return std::max(0.0, b * b - 4.0 * e);
}

}  // namespace

double ec_wall_icw(int N) {
  require(N >= 1, "ec_wall_icw: N >= 1");
  const double t = std::tan(0.25 * std::numbers::pi * (1.0 - 1.0 / N));
  return t * t;
}

double ec_wall_icw_asymptotic(int N) {
  require(N >= 1, "ec_wall_icw_asymptotic: N >= 1");
  return 1.0 - std::numbers::pi / N;
}

double cushion_Nc_wall(double e) {
  require(e >= 0 && e < 1, "cushion_Nc_wall: 0 <= e < 1");
  return std::log(4.0 / (1.0 - e)) / (1.0 - e);
}

double ec_wall_cushion(double N) {
  require(N >= 2, "ec_wall_cushion: N >= 2");
  // N_c^wall increases from ln 4 at e = 0 to infinity at e = 1: bisection in u = 1 - e.
  double lo = 0.0, hi = 1.0;  // e
  for (int it = 0; it < 200 && hi - lo > 4e-16; ++it) {
    const double mid = 0.5 * (lo + hi);
    (cushion_Nc_wall(mid) < N ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double ec_wall_cushion_asymptotic(double N) {
  require(N >= 1, "ec_wall_cushion_asymptotic: N >= 1");
  const double L = std::log(4.0 * N);
  return 1.0 - L / N * (1.0 - std::log(L) / L);
}

double ec3() { return 7.0 - 4.0 * std::sqrt(3.0); }

double ec_free(int N) {
  require(N >= 3, "ec_free: N >= 3");
  const double t = std::tan(0.25 * std::numbers::pi * (1.0 - 2.0 / N));
  return t * t;
}

double m_star(double e) {
  require_three_body(e);
  const double b = 0.5 * (1.0 + e);
  // The root of m^2 + b m + e = 0 nearer zero, as e over the other (no cancellation at small e).
  return 2.0 * e / (-b - std::sqrt(discriminant(e)));
}

double m_prime_star(double e) {
  require_three_body(e);
  const double b = 0.5 * (1.0 + e);
  return (-b - std::sqrt(discriminant(e))) / (2.0 * e);
}

namespace {

// ln q of Eq. (def_q), q = (a - r)/(a + r) with a = 1 - 6e + e^2, r = (1 + e) sqrt(1 - 14e + e^2)
// (1 - 14e + e^2 = 16 (b^2 - 4e) >= 0 on the range). Since a^2 - r^2 = 64 e^2 exactly,
// q = 64 e^2 / (a + r)^2: no cancellation of a - r at small e, and its logarithm is finite where
// q itself is below the least double.
double log_q(double e) {
  const double a = 1.0 - 6.0 * e + e * e;
  const double r = (1.0 + e) * std::sqrt(std::max(0.0, 1.0 - 14.0 * e + e * e));
  return std::log(64.0) + 2.0 * std::log(e) - 2.0 * std::log(a + r);
}

}  // namespace

double q_ratio(double e) {
  require_three_body(e);
  return std::exp(log_q(e));
}

double f_shift(double e) {
  const double ms = m_star(e), mps = m_prime_star(e);
  return -ms * (1.0 / ((e * mps) * (e * mps)) - 1.0);
}

double ntot_slope_per_ln_k(double e) {
  require(e > 0 && e < ec3(), "ntot_slope_per_ln_k: 0 < e < e_c(3) = 7 - 4 sqrt 3");
  return -1.0 / (2.0 * log_q(e));
}

double collisions_slope_per_ln_k(double e) { return 2.0 * ntot_slope_per_ln_k(e); }

}  // namespace granchain::theory
