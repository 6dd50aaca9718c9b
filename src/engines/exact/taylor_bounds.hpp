#pragma once
// Proofs that a watched function has no root over a step, and the bracketing of its first root
// (the exact engine's event searches). A function is described near the current search time by
// its exact derivatives and bounds on its mode part's higher derivatives (ModeConstants::bound).
#include <algorithm>
#include <cmath>
#include <limits>

#include "engines/exact/cluster_modes.hpp"
#include "engines/free_flight.hpp"

namespace granchain::taylor {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

// The quadratic lower bound's first root (free_flight.hpp).
using free_flight::quadratic_step;

inline constexpr int P = kTaylorOrder;

// 1/n! and the Bernstein weights C(k, i) / C(P, i), i <= k <= P.
struct TaylorTables {
  double inv_fact[P + 1];
  double bernstein[P + 1][P + 1];
  TaylorTables() {
    inv_fact[0] = 1.0;
    for (int n = 1; n <= P; ++n) inv_fact[n] = inv_fact[n - 1] / n;
    auto binom = [](int n, int k) {
      double c = 1.0;
      for (int i = 1; i <= k; ++i) c = c * (n - k + i) / i;
      return c;
    };
    for (int k = 0; k <= P; ++k) {
      for (int i = 0; i <= P; ++i) bernstein[k][i] = i <= k ? binom(k, i) / binom(P, i) : 0.0;
    }
  }
};
inline const TaylorTables kTaylor;

// The watched function f near the current search time s, for steps h >= 0:
//   f(s + h) >= f + f' h + (p2 - m2) h^2 / 2                                    (quadratic bound)
//   f(s + h) >= sum_{n < P} f^(n) h^n / n! - mP h^P / P!                        (order-P bound)
// with f^(n) the exact derivatives at s, p2 the exact second derivative of its polynomial part
// (the modes' third and higher derivatives are its only ones), and m2 >= |W''|, mP >= |W^(P)|
// bounds on its mode part W over all later times (ModeConstants::bound times the mode amplitudes).
struct Jet {
  double d[P];  // f, f', ..., f^(P-1) at s
  double p2 = 0, m2 = 0, mP = 0;
  // The order-P lower bound and its slope.
  double lower(double h) const {
    double v = -mP * kTaylor.inv_fact[P];
    for (int n = P - 1; n >= 0; --n) v = v * h + d[n] * kTaylor.inv_fact[n];
    return v;
  }
  double lower_slope(double h) const {
    double v = -mP * kTaylor.inv_fact[P - 1];
    for (int n = P - 1; n >= 1; --n) v = v * h + d[n] * kTaylor.inv_fact[n - 1];
    return v;
  }
  // Upper end of the interval that must hold f's first root when f > 0 up to the safe step h:
  // f(s + h) <= f + f' h + (p2 + m2) h^2 / 2, so f has a root by the first root of that parabola
  // (+inf if it has none).
  double root_upper() const {
    const double a = 0.5 * (p2 + m2), f0 = std::max(d[0], 0.0);
    if (!(d[1] < 0)) return kInf;
    const double disc = d[1] * d[1] - 4.0 * a * f0;
    return disc < 0 ? kInf : 2.0 * f0 / (std::sqrt(disc) - d[1]);
  }
  // Is the order-P bound positive on [0, H]? Sufficient test: every Bernstein coefficient of it
  // on [0, H] is positive (the polynomial is a convex combination of them there).
  bool lower_positive(double H) const {
    double a[P + 1];
    double Hn = 1.0;
    for (int n = 0; n < P; ++n, Hn *= H) a[n] = d[n] * kTaylor.inv_fact[n] * Hn;
    a[P] = -mP * kTaylor.inv_fact[P] * Hn;
    if (!(a[0] > 0)) return false;
    for (int k = 1; k <= P; ++k) {
      double b = 0.0;
      for (int i = 0; i <= k; ++i) b += kTaylor.bernstein[k][i] * a[i];
      if (!(b > 0)) return false;
    }
    return true;
  }
};

// A step h <= cap over which f is proven positive (f > 0 at the start). The quadratic bound
// gives a first safe step; Newton's method on the order-P bound then looks for that bound's
// first root, and the step is extended to just short of it when the Bernstein test proves the
// bound positive up there. Near a simple root of f the bound's root differs from f's by
// O(mP h^P / (P! |f'|)), so the search closes in on an event with few steps. Returns cap when
// the whole interval is safe.
inline double safe_step(const Jet& j, double cap) {
  const double h = quadratic_step(j.d[0], j.d[1], 0.5 * (j.p2 - j.m2));
  if (h >= cap) return cap;
  if (!(j.d[0] > 0)) return h;
  double r = h;
  for (int k = 0; k < 8; ++k) {
    const double p = j.lower(r), dp = j.lower_slope(r);
    double next = dp < 0 ? r - p / dp : 2.0 * r + h;
    if (!(next > 0)) break;
    if (next >= cap) {
      r = cap;
      break;
    }
    const bool converged = std::abs(next - r) <= 1e-8 * (next - h);
    r = next;
    if (converged) break;
  }
  if (!(r > h)) return h;
  // Just short of the bound's root, where it is still clearly positive.
  double H = r >= cap ? cap : h + (r - h) * (1.0 - 1e-6);
  for (int tries = 0; tries < 2; ++tries, H = h + 0.5 * (H - h)) {
    if (j.lower_positive(H)) return H;
  }
  return h;
}

// Is a watched function at (or, by round-off, just past) zero and moving down? The first
// non-zero derivative decides; a function whose value and first three derivatives all vanish is
// taken as at its root.
inline bool at_root(double f, double f1, double f2, double f3) {
  return f <= 0 && (f1 < 0 || (f1 == 0 && (f2 < 0 || (f2 == 0 && f3 <= 0))));
}

}  // namespace granchain::taylor
