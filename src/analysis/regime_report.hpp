#pragma once
// The whole analysis of a set of stored driven-column runs: n_coll(k) for every (engine, N, kT0, e),
// its regime, and per (engine, N, kT0) the critical restitutions and the power-law exponents; then
// across N, the fits (1 - e_c) = A/N and alpha(N). What `granchain analyze` prints.
#include <map>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "analysis/blocking.hpp"
#include "engines/engine_registry.hpp"
#include "model/plate_motion.hpp"
#include "analysis/alpha_across_n.hpp"
#include "analysis/collapse_regimes.hpp"
#include "analysis/critical_restitution.hpp"

namespace granchain::analysis {

// One run of a point as combine_replicas takes it: its n_coll, blocking error and measuring window.
struct PointRun {
  double n_coll = 0, error = 0;
  double T = 0;  // the window; <= 0 (unknown) in any run of a point weights all its runs equally
};

// Independent runs (replicas, or windows of several T) of one point: the pooled rate
// n = sum_i T_i n_i / sum_i T_i, the collisions of all windows over their total time, with the
// blocking errors propagated, sqrt(sum_i T_i^2 err_i^2) / sum_i T_i, and from kReplicasForScatter
// runs on the error of that mean from the runs' own scatter, sqrt(m / (m - 1) sum_i T_i^2 (n_i -
// n)^2) / sum_i T_i, where it is the larger (never scaled down). Weights by window, not by 1/err^2:
// where collisions come in bursts (the near-solid columns of docs/columns.md) a window's blocking
// error grows with its count, and inverse-variance weights would pull the mean toward the quiet
// windows. With equal windows and errors the error is the Birge-scaled one. Fewer runs keep the
// blocking error: with 1 or 2 degrees of freedom the scatter is uncertain by 50 % or more, and
// taking it only where it exceeds the blocking error would widen right errors on average.
inline constexpr std::size_t kReplicasForScatter = 4;
std::pair<double, double> combine_replicas(const std::vector<PointRun>& runs);

// One stored run's result (several runs of one point are combined by combine_replicas).
struct NcollRun {
  EngineKind engine = EngineKind::Exact;
  int N = 0;
  double kT0 = 1, e = 0, k = 0;
  double n_coll = 0, n_coll_err = 0;
  bool stationary = true;  // the run's window passed its halves check (or the run predates it)
  std::int64_t run_id = 0;  // the store's id, to name a run that is left out
  // The trajectory: the physics, the engine and the seed ("" if unknown). Runs with one trajectory
  // share their start (whatever their window or sampling), so they are one sample, not replicas.
  std::string trajectory;
  double T = 0;  // the measuring window: of one trajectory, the longest run is kept
  DriveSpec drive;  // the thermal floor or a plate: each drive its own families
  // The time discarded before the window. Where a point has a stationary run after a longer
  // transient, the runs after a shorter transient that some of them fail the check are left out,
  // all of them (they started from the same unsettled column, the passing ones too); any other
  // non-stationary run stays in its point, marked (a settled column fails the check now and then,
  // and dropping those runs alone would favour quiet windows).
  double transient = 0;
};

// A run the analysis could not use, and why.
struct ExcludedRun {
  std::int64_t run_id = 0;
  EngineKind engine = EngineKind::Exact;
  int N = 0;
  double kT0 = 1, e = 0, k = 0;
  std::string reason;
  DriveSpec drive;
};

struct CurveAnalysis {  // one (engine, N, kT0, e)
  double e = 0;
  std::vector<DataPoint> n_coll_of_k;  // combined over runs, k ascending
  std::vector<double> non_stationary_k;  // k of runs whose window failed the halves check
  bool classified = false;             // enough values of k in the asymptotic range
  Classification c;
};

struct FamilyAnalysis {  // one (engine, drive, N, kT0)
  EngineKind engine = EngineKind::Exact;
  DriveSpec drive;
  int N = 0;
  double kT0 = 1;
  std::vector<CurveAnalysis> curves;  // e ascending
  CriticalValue e_c1, e_c2;  // e_c1: estimate.e_c1 (its error includes the systematic part)
  CriticalValue e_c2_sign;   // e_c2 where the curvature changes sign (the paper's reading)
  E_c1Estimate e_c1_estimate;
  // Table 1: alpha at e = 0.1, 0.2, 0.3, 0.4 (those measured) and their mean.
  std::vector<DataPoint> alphas;  // x = e
  bool has_alpha_bar = false;
  Mean alpha_bar;
  // The local exponent per interval of k, averaged over the same e as alpha_bar (all k, not only
  // the asymptotic range): how the slope behind alpha_bar drifts with k.
  std::vector<LocalExponent> local_alpha_bar;
  std::map<double, std::vector<LocalExponent>> local_alpha_by_e;  // the same e, each curve's own
  // The blocking errors checked against independent replicas of one (e, k), where the store holds
  // two or more (analysis/blocking.hpp); the worst point's e and k.
  ReplicaScatter replicas;
  double replicas_worst_e = 0, replicas_worst_k = 0;
};

// The line alpha = p log10 N + q (Eq. alphafit) through the local exponents of one interval of k
// (FamilyAnalysis::local_alpha_bar) at every N that has it: how the slope depends on where in k the
// exponent is read. Only intervals measured at three N or more.
struct LocalAlphaLine {
  double k1 = 0, k2 = 0;
  std::vector<int> Ns;  // ascending
  LineFit fit;
  // At the same e on both sides (analysis/alpha_across_n.hpp): the slope between neighbouring
  // columns, and the largest column against the line through the others.
  std::vector<NeighbourSlope> neighbour_slopes;
  bool has_excess = false;
  LineExcess excess;
};

struct AcrossN {  // one (engine, drive, kT0), over N
  EngineKind engine = EngineKind::Exact;
  DriveSpec drive;
  double kT0 = 1;
  bool has_A1 = false, has_A2 = false, has_alpha_fit = false;
  InverseNFit A1, A2;  // e_c1 (b -> 0), e_c2 (convex by 2 errors / not: the bracket)
  // The same fits of the classification boundary (its midpoint, with the bracket's half-width /
  // sqrt 3, the standard deviation of a uniform position within it) and of e_c2 where the
  // curvature changes sign (the paper's reading). The fits of brackets (A2, A1_boundary) have an
  // error of at least the fit-weighted mean bracket width in c = N (1 - e) over sqrt 12: on a grid
  // in c the rounding to the grid is shared by every N.
  bool has_A1_boundary = false, has_A2_sign = false;
  InverseNFit A1_boundary, A2_sign;
  LineFit alpha_fit;   // alpha bar against log10 N
  std::vector<LocalAlphaLine> local_alpha_lines;  // k1 ascending
};

struct RegimeReport {
  double k_min = 0;
  std::vector<FamilyAnalysis> families;
  std::vector<AcrossN> across;
  std::vector<ExcludedRun> excluded;  // every run left out, with its reason, in the input's order
};

// Groups the runs and analyses every group (see docs/analysis.md). Left out, and listed in
// `excluded` with the reason: runs with a non-finite k (hard spheres) or n_coll, runs without a
// positive error (no blocking estimate: too few collisions in the window), and every run of a
// trajectory but one (the longest window; then the first given).
RegimeReport analyze_runs(const std::vector<NcollRun>& runs, double k_min = 0.0);

}  // namespace granchain::analysis
