#pragma once
// Exact equilibrium of the elastic (e = 1, D = 0) driven column, against which the engines are
// tested. With e = 1 the thermal floor is a heat bath and the column samples the Gibbs measure
// exp(-U / kT0) with U = sum_i m g z_i + sum_pairs (k/2) x^2 theta(x) and the hard floor z_1 >= d/2.
// In the gap variables s_1 = z_1 - d/2, s_j = z_j - z_{j-1} - d the measure factorises: gap j
// carries the weight W_j = m g (N - j + 1) of the particles above it, with density
//   p_j(s) ~ exp(-(W_j s + (k/2) s^2 theta(-s)) / kT0),   s >= 0 only for j = 1,
// and velocities are independent Maxwellians. Hence exactly:
//   <z_i> = d/2 + (i-1) d + sum_{j<=i} <s_j>,   sigma_i^2 = sum_{j<=i} var(s_j),   K_i = kT0/2,
// and, by Rice's formula, the rate at which gap j crosses zero upward (a contact ends) is
//   p_j(0) <u^+> with u = v_j - v_{j-1} ~ N(0, 2 kT0/m):  p_j(0) sqrt(kT0 / (pi m)),
// while the floor is hit at the rate p_1(0) sqrt(kT0 / (2 pi m)) with p_1(0) = W_1 / kT0.
#include <vector>

#include "model/chain_parameters.hpp"

namespace granchain {

struct ElasticColumnEquilibrium {
  std::vector<double> z_mean;          // <z_i>, i = 1..N
  std::vector<double> z_std;           // sigma_i
  double kinetic = 0.0;                // K_i = kT0 / 2 for every particle
  double floor_rate = 0.0;             // floor hits per unit time
  std::vector<double> contact_end_rate;// per pair (i, i+1), i = 1..N-1
  double n_coll = 0.0;                 // (floor + all pairs) / N
};

// Requires g > 0 (a bounded column). Throws std::domain_error where the soft-overlap integrals
// would overflow (columns so soft that the weight W_j^2 / (2 k kT0) exceeds ~600).
ElasticColumnEquilibrium elastic_column_equilibrium(const ChainParameters& p);

}  // namespace granchain
