#pragma once
// The sequence of collisions of one free-space collapse (paper Summary: does the collision interval
// shrink geometrically toward an inelastic collapse, as for three bodies, Eq. deltat12, or as a
// power of the collision number?). Plain data in, numbers out: the simulation records the
// collisions, this file measures them.
#include <cstddef>
#include <vector>

namespace granchain::analysis {

// One collision: its contact begins and ends (equal for hard spheres); pair i joins particles i
// and i + 1 (1-based), 0 is the wall.
struct Collision {
  double t_begin = 0, t_end = 0;
  int pair = 0;
};

// Free flight between successive collisions of the whole system: g_n = t_begin(n+1) - t_end(n),
// n = 1 .. size-1 (negative where contacts overlap, possible for soft spheres only).
std::vector<double> system_gaps(const std::vector<Collision>& c);
// Free flight between successive collisions of the same pair, over all pairs.
std::vector<double> pair_gaps(const std::vector<Collision>& c);
// The mean over pairs of ln(g_(j+1) / g_j), g_j the successive gaps of one pair among collisions
// first .. last (pairs with at least 3 collisions there): the log of the ratio by which a pair's
// interval shrinks from one of its collisions to the next (ln q of Eq. deltat12 for three bodies).
// NaN when no pair has 3 collisions in the range.
double mean_pair_log_ratio(const std::vector<Collision>& c, std::size_t first, std::size_t last);
// Distinct particles touched by collisions first .. last (inclusive; the wall is not a particle).
int particles_involved(const std::vector<Collision>& c, std::size_t first, std::size_t last);

// A collapse event of soft spheres: a maximal run of collisions whose successive gaps are all
// below max_gap (a few contact durations: the intervals have shrunk to the model's cut-off),
// holding at least min_collisions collisions.
struct CollapseEvent {
  std::size_t first = 0, collisions = 0;
  int particles = 0;
};
std::vector<CollapseEvent> collapse_events(const std::vector<Collision>& c, double max_gap, std::size_t min_collisions);

// Collapse events that set each other off. A soft collapse leaves a compressed cluster whose
// relative speeds are a small fraction of its approach speed; the cluster collapses again some
// tens of tau_c later. A cascade is a maximal run of events (in time order), each beginning less
// than max_wait after the end of the one before: the index of its first event and its length.
struct EventSpan {
  double begin = 0, end = 0;
};
struct Cascade {
  std::size_t first = 0, events = 0;
};
std::vector<Cascade> cascades(const std::vector<EventSpan>& events, double max_wait);

// Hard spheres toward a collapse at t_star: the remaining time tau_n = t_star - t_n of collision n
// (1-based). For each tau of `taus`, the number of collisions with tau_n >= tau (before the
// sequence first comes within tau of the collapse); the count a cut-off at that tau leaves.
std::vector<double> collisions_before_remaining(const std::vector<Collision>& c, double t_star, const std::vector<double>& taus);

// How tau_n falls with n over the collisions with tau_lo <= tau_n <= tau_hi, by two unweighted
// straight-line fits:
//   geometric:  ln tau_n = a + n ln q        (intervals shrink by a constant ratio q per collision)
//   power:      ln tau_n = a - (beta - 1) ln n  (intervals shrink as n^-beta, tau_n ~ n^(1-beta))
// and the rms residual of ln tau_n of each; the smaller says which straight line the data follow.
struct ShrinkFit {
  int points = 0;
  std::size_t first = 0, last = 0;  // the collisions fitted (0-based, inclusive; tau_n falls with n)
  double ln_q = 0, ln_q_error = 0, rms_geometric = 0;
  double beta = 0, beta_error = 0, rms_power = 0;
};
// Needs at least 4 collisions in the range; otherwise points < 4 and the rest NaN.
ShrinkFit fit_remaining_time(const std::vector<Collision>& c, double t_star, double tau_lo, double tau_hi);

}  // namespace granchain::analysis
