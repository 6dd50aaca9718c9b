#pragma once
// e_c1 as the paper finds it, from the approach of the log slope b to zero (Eq. b_e_N: near e_c1,
// b ~ ((1 - e) - A/N)^2, so sqrt(b) is linear in e and vanishes at e_c1), with an error that
// includes the choices the estimate depends on:
//   - the asymptotic range: b is fitted over k >= k_min and over k >= 10 k_min;
//   - the fit window below the last positive slope: 0.5/N, 1/N and 2/N wide (the critical region's
//     width scales as 1/N, Eq. e-fit); the square law holds only near e_c1, so a wide window
//     biases the root, a narrow one has few points;
//   - the finite-k residual: where n_coll converges, n(k) = n_inf - c k^(-1/2) still rises over a
//     finite range of k, so the fitted b is small but positive on the uncollapsing side too, and
//     sqrt(b) reaches zero only beyond e_c1. The residual is measured as the weighted mean b of the
//     curves classified uncollapsing at least 1/N above the last collapsing e (closer ones may
//     collapse with slopes too small to resolve) and subtracted; the variants without the
//     subtraction enter the spread too.
// The central value is the variant (k_min, 1/N, subtracted); the systematic error is half the range
// of all variants found, added in quadrature to the central variant's statistical error. Beside it
// comes the classification boundary (at k >= k_min): scanning down from the largest e, the first
// collapsing e (logarithmic or power-law) that is not isolated between two uncollapsing ones, and
// the next e of the grid. Isolated collapsing e above it (chance: 2 errors) are listed and enter
// the fit as b = 0.
#include <vector>

#include "analysis/collapse_regimes.hpp"

namespace granchain::analysis {

struct Curve {  // n_coll against k at one e, k ascending
  double e = 0;
  std::vector<DataPoint> n_coll_of_k;
};

struct E_c1Estimate {
  CriticalValue e_c1;  // central value; error = hypot(statistical, systematic)
  double statistical = 0, systematic = 0;
  int variants = 0, variants_found = 0;
  double residual_b = 0, residual_b_error = 0;  // finite-k slope of the uncollapsing side (k >= k_min)
  bool has_boundary = false;
  double last_collapsing_e = 0, first_uncollapsing_e = 0;
  std::vector<double> isolated_collapsing_e;  // collapsing e above the boundary (taken as b = 0)
};

E_c1Estimate estimate_e_c1(const std::vector<Curve>& curves, int N, double k_min, double z = 2.0);

// The classification boundary as a bracket (low: the last collapsing e, high: the first
// uncollapsing one), its midpoint the value and the standard deviation of a position uniform
// within it the error; not found without a boundary.
CriticalValue classification_boundary(const E_c1Estimate& x);

}  // namespace granchain::analysis
