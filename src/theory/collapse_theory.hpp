#pragma once
// Closed forms of the paper for inelastic collapse (Sec. II.C, II.D, III.B and Appendices A, B).
// Every function throws std::domain_error outside the range where its formula holds.
namespace granchain::theory {

// --- N hard spheres thrown against an elastic wall (Bernu & Mazighi, Sec. II.C) ---

// ICW model, Eq. (icw): e_c^wall(N) = tan^2(pi/4 (1 - 1/N)); exact for N = 2. N >= 1.
double ec_wall_icw(int N);
// Its large-N form, Eq. (ec_icw_wall): 1 - pi/N. N >= 1.
double ec_wall_icw_asymptotic(int N);
// Cushion model (McNamara & Young): the least N that collapses at e, N_c^wall(e) =
// ln(4/(1-e)) / (1-e). 0 <= e < 1.
double cushion_Nc_wall(double e);
// The cushion model's critical e for N particles: the e in [0, 1) where N_c^wall(e) = N (the
// inverse of cushion_Nc_wall, which increases with e). N >= 2 (N_c^wall(0) = ln 4 > 1).
double ec_wall_cushion(double N);
// Its large-N form, Eq. (ec_cushion): 1 - ln(4N)/N (1 - ln ln 4N / ln 4N). N >= 1.
double ec_wall_cushion_asymptotic(double N);

// --- free space (Sec. II.C and III.B) ---

// e_c(3) = 7 - 4 sqrt(3) (McNamara & Young): below it the three-body map has real fixed points.
double ec3();
// The paper's estimate for N free particles, Sec. III.B, from the ICW model and the symmetry
// e_c(2N) = e_c^wall(N): e_c(N) = tan^2(pi/4 (1 - 2/N)). N >= 3 (equals ec3() at N = 3).
double ec_free(int N);

// --- three-body collapse, Appendices A and B (0 < e <= e_c(3)) ---

// b = (1 + e)/2 and the stable fixed points of the velocity-ratio map, Eqs. (mmdash), (mdashm):
// m* = (-b + sqrt(b^2 - 4e))/2, m'* = (-b - sqrt(b^2 - 4e))/(2e).
double m_star(double e);
double m_prime_star(double e);
// q = (m*/(e m'*))^2, Eq. (def_q): the ratio of successive intervals between collisions of the
// same pair, t12^(n) ~ q t12^(n-1), Eq. (deltat12). 0 <= q < 1.
double q_ratio(double e);
// f = -m* (1/(e m'*)^2 - 1) > 0, Appendix B: the soft-sphere shift t12^(n) = q t12^(n-1) - f tau_c,
// Eq. (deltat12ss).
double f_shift(double e);
// Slope of n_tot against ln k, Eq. (ntot-log): -1 / (2 ln q); against log10 k it is ln 10 times
// this. 0 < e < e_c(3).
double ntot_slope_per_ln_k(double e);
// Slope against ln k of the number of all collisions of the three-body sequence: -1 / ln q, twice
// Eq. (ntot-log). The index n of Eq. (deltat12) counts intervals between collisions of one pair
// (1, 2); each such interval holds one collision of (2, 3) too, so the total is 2n + const.
double collisions_slope_per_ln_k(double e);

}  // namespace granchain::theory
