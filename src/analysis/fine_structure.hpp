#pragma once
// The fine structure of n_coll(e) in small columns (paper Sec. III.B, Fig. cfe): at a fixed k the
// curve n_coll(e) of N = 3 ... 6 has sharp peaks at the free-space critical values e_c(n),
// 3 <= n <= N - 1 (the one at e_c(3) highest), a dip at or slightly above e_c(N) (for N = 3 at
// e_c(4)), a broad peak near e_c(N + 1), and "irregular-looking" structure elsewhere that the
// paper finds reproducible under a change of random numbers. The functions here find those
// features in a sampled curve with their significance, so that each statement can be tested.
#include <vector>

#include "analysis/collapse_regimes.hpp"

namespace granchain::analysis {

enum class ExtremumKind { Peak, Dip };
const char* extremum_kind_name(ExtremumKind k);  // "peak", "dip"

// A significant local extremum of a sampled curve: the point lies above (peak) or below (dip) both
// of its neighbours by more than z standard errors of the difference. `z` is the smaller of the
// two differences in units of their standard errors, `prominence` the smaller difference itself.
struct Extremum {
  ExtremumKind kind = ExtremumKind::Peak;
  double x = 0, y = 0, error = 0;
  double z = 0, prominence = 0;
};

// Every significant local extremum of a curve sampled at strictly increasing x (interior points
// only: an end point has one neighbour). Points with a non-positive error are not compared.
std::vector<Extremum> significant_extrema(const std::vector<DataPoint>& curve, double z = 3.0);

// A broad peak around `centre`: the largest y among the samples with |x - centre| <= half_width
// lies above the curve, linearly interpolated between the samples, at both window edges
// (centre -+ half_width) by more than z standard errors. Without samples beyond an edge the
// nearest sample inside stands for it.
struct BroadPeak {
  bool found = false;
  double x = 0, y = 0;
  double z = 0;                // the smaller excess over the two edges, in standard errors
};
BroadPeak broad_peak(const std::vector<DataPoint>& curve, double centre, double half_width, double z = 3.0);

// The features of one n_coll(e) curve of an N-particle column at one k, sorted by the free-space
// critical values e_c(n) = tan^2(pi/4 (1 - 2/n)) (theory::ec_free) they sit at.
struct CriticalFeatures {
  int n = 0;
  double e_c = 0;
  std::vector<Extremum> extrema;  // significant extrema with |e - e_c(n)| <= window
};
struct FineStructure {
  int N = 0;
  std::vector<CriticalFeatures> at_critical;  // n = 3 ... N + 1
  BroadPeak near_next;                        // broad peak within e_c(N + 1) -+ broad_half_width
  std::vector<Extremum> elsewhere;            // significant extrema outside every window
};
// window: half width of the region "at e_c(n)" (the refined grid's +-0.01, plus rounding);
// broad_half_width: half width of the broad-peak window around e_c(N + 1).
FineStructure find_fine_structure(int N, const std::vector<DataPoint>& n_coll_of_e, double window = 0.0105,
                                  double broad_half_width = 0.05, double z = 3.0);

// Whether two independent replicas (different random numbers) show the same curve: the chi^2 of
// their differences at the common x over `dof` points, and its Wilson-Hilferty normal deviate
// (about N(0, 1) when the replicas agree within their errors); and how many of the significant
// extrema of `a` recur in `b` as extrema of the same kind at the same or an adjacent sample with
// more than z_recur standard errors.
struct ReplicaAgreement {
  double chi2 = 0;
  int dof = 0;
  double chi2_z = 0;
  int extrema_a = 0, recurring_in_b = 0;
};
ReplicaAgreement compare_replicas(const std::vector<DataPoint>& a, const std::vector<DataPoint>& b, double z = 3.0,
                                  double z_recur = 2.0);

// The growth of a quantity y(k) with k, decade by decade: the increments y(k2) - y(k1) between
// successive sampled k (errors combined in quadrature). Growth "faster than log k" shows as
// increments that rise: `rising_z` is (last increment - first increment) / its standard error.
struct Increment {
  double k1 = 0, k2 = 0, dy = 0, error = 0;
};
struct GrowthPerDecade {
  std::vector<Increment> increments;
  double rising_z = 0;
};
GrowthPerDecade growth_per_decade(const std::vector<DataPoint>& y_of_k);

}  // namespace granchain::analysis
