// The exact engine's events: a cluster splitting where an overlap returns to zero, two clusters
// merging where a gap closes, particle 1 hitting the floor, and a refresh that re-forms a cluster
// (no physics) so its search starts again. Each re-forms the clusters it touches, moves the
// neighbouring gaps and the floor height to the event's time, and re-predicts them.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "engines/exact/exact_engine.hpp"

namespace granchain {

void ExactEngine::split(int lo, int pair, Time t, double tau, EventSink& sink) {
  const int hi = hi_[lo];
  // The cluster is taken at its own root time tau (not t - t0, which rounds): the overlap that
  // ends is zero to round-off and the velocities carry no error of order (dv/dt) ulp(t). The
  // gaps and the floor height are synchronised with these same modes (through the cache).
  double* y = sy2_[0].data();
  double* yd = sy2_[1].data();
  modes_at(lo, tau, y, yd);
  if (lo > 0) {
    seed_cache(lo, t, y, yd);
    sync_gap(lo - 1, t);
  }
  if (hi + 1 < n_) {
    seed_cache(lo, t, y, yd);
    sync_gap(hi, t);
  }
  if (lo == 0) {
    seed_cache(lo, t, y, yd);
    sync_floor(t);
  }
  double* x = sx_.data();
  double* xd = sxd_.data();
  double* u = sv_.data();
  cluster_relative(lo, y, yd, x, xd, u);
  const int r = pair - lo;
  const double speed = std::abs(xd[r]);
  // Centre-of-mass velocities of the two parts relative to the old one (u has mean zero).
  const int n_lower = r + 1, n_upper = hi - pair;
  double u_lower = 0.0, u_upper = 0.0;
  for (int p = 0; p < n_lower; ++p) u_lower += u[p];
  for (int p = n_lower; p < n_lower + n_upper; ++p) u_upper += u[p];
  u_lower /= n_lower;
  u_upper /= n_upper;
  part(lo, pair, hi, t, x, xd, V0_[lo] - g_ * tau, u_lower, u_upper, speed, sink);
}

void ExactEngine::part(int lo, int pair, int hi, Time t, const double* x, const double* xd, double V, double u_lower,
                       double u_upper, double speed, EventSink& sink) {
  const int r = pair - lo;
  form_cluster(lo, pair, t, x, xd, V + u_lower);
  form_cluster(pair + 1, hi, t, x == nullptr ? nullptr : x + r + 1, xd == nullptr ? nullptr : xd + r + 1, V + u_upper);
  gaps_.s[pair] = 0.0;  // the overlap has just returned to zero
  gaps_.c[pair] = u_upper - u_lower;
  if (lo > 0) gaps_.c[lo - 1] += u_lower;
  if (hi + 1 < n_) gaps_.c[hi] -= u_upper;
  if (lo > 0) rebase_gap(lo - 1, t);
  rebase_gap(pair, t);
  if (hi + 1 < n_) rebase_gap(hi, t);
  if (lo == 0) rebase_floor(t);
  ++counters_.contact_ends;
  sink.on_event({EventKind::ContactEnd, t.value(), pair, speed, t.low()});
  predict_cluster(lo);
  predict_cluster(pair + 1);
  if (lo > 0) predict_gap(lo - 1);
  predict_gap(pair);
  if (hi + 1 < n_) predict_gap(hi);
  if (lo == 0) predict_floor();
}

void ExactEngine::merge(int pair, Time t, EventSink& sink) {
  const int a = lo_of_[pair], b = pair + 1, hi = hi_[b];
  const int na = pair - a + 1;
  if (a > 0) sync_gap(a - 1, t);
  if (hi + 1 < n_) sync_gap(hi, t);
  if (a == 0) sync_floor(t);
  // Overlaps indexed from a: pairs a..pair-1 from cluster a, pair itself (0: contact begins,
  // its rate minus the gap's rate), pairs b..hi-1 from cluster b.
  double* x = sx_.data();
  double* xd = sxd_.data();
  double* u = sv_.data();
  const double *y = nullptr, *yd = nullptr;
  if (na >= 2) cached_modes(a, t, y, yd);
  cluster_relative(a, y, yd, x, xd, u);
  if (hi > pair + 1) cached_modes(b, t, y, yd);
  cluster_relative(b, y, yd, x + na, xd + na, u + na);
  // The gap's rate: c = V_b - V_a plus the edges' velocities relative to their centres of mass.
  const double c = gaps_.c[pair];
  const double rate = c + u[na] - u[na - 1];
  const double scale = std::abs(c) + std::abs(u[na]) + std::abs(u[na - 1]);
  x[na - 1] = 0.0;
  xd[na - 1] = -rate;
  const double speed = std::abs(rate);
  // The new centre of mass moves at V_a + (n_b / n) c relative to cluster a's.
  const int n = hi - a + 1, nb = hi - pair;
  const double dVa = c * nb / n, dVb = dVa - c;
  form_cluster(a, hi, t, x, xd, com_velocity(a, t) + dVa);
  if (a > 0) gaps_.c[a - 1] += dVa;
  if (hi + 1 < n_) gaps_.c[hi] -= dVb;
  // A grazing contact: the gap closed with no approach speed that double precision can resolve
  // (below 1e-13 of the terms its rate sums: a cluster's edge pushing a particle that rests
  // against it). The new overlap and its rate are
  // zero up to the round-off of the cluster's modes, which could end the contact at the instant it
  // began, again and again. The contact's end is therefore searched from tau = 1e-6 tau_c on, when
  // the push has made the overlap (omega tau)^2 / 2 ~ 1e-11 of the neighbouring overlaps, far above
  // that round-off; a contact shorter than that, with an overlap below round-off, is not resolved.
  //
  // A pair that keeps grazing (the two ends of resting sub-clusters whose relative motion is below
  // round-off touch, part and touch again every 1e-6 tau_c, each time counted as a collision and
  // with no end in sight) is held in contact for a time that doubles with every consecutive
  // grazing contact of that pair, 2^(s-1) 1e-6 tau_c after the s-th, up to tau_c: the chatter
  // then costs O(log) events instead of one every 1e-6 tau_c. While held, the pair's spring acts
  // on overlaps of round-off size only. Any resolvable contact beginning in the cluster releases
  // every hold in it, since it brings relative motion that double precision resolves again.
  if (speed <= 1e-13 * scale) {
    search_from_[a] = kResolutionSkip * tau_c_;
    ++counters_.grazing_contacts;
    const int streak = ++grazing_streak_[pair];
    if (streak >= 2) {
      ++counters_.held_contacts;
      hold_until_[pair] = t + std::min(1.0, kResolutionSkip * std::ldexp(1.0, std::min(streak - 1, 30))) * tau_c_;
    }
  } else {
    grazing_streak_[pair] = 0;
    for (int i = a; i < hi; ++i) hold_until_[i] = -kInf;
  }
  set_slot(cluster_slot(b), kInf, SlotKind::None, b);
  set_slot(gap_slot(pair), kInf, SlotKind::None, pair);
  if (a > 0) rebase_gap(a - 1, t);
  if (hi + 1 < n_) rebase_gap(hi, t);
  if (a == 0) rebase_floor(t);
  sink.on_event({EventKind::ContactBegin, t.value(), pair, speed, t.low()});
  predict_cluster(a);
  if (a > 0) predict_gap(a - 1);
  if (hi + 1 < n_) predict_gap(hi);
  if (a == 0) predict_floor();
}

void ExactEngine::floor_hit(Time t, EventSink& sink) {
  const int hi = hi_[0];
  if (hi + 1 < n_) sync_gap(hi, t);
  double* x = sx_.data();
  double* xd = sxd_.data();
  double* u = sv_.data();
  const double *y = nullptr, *yd = nullptr;
  if (hi > 0) cached_modes(0, t, y, yd);
  cluster_relative(0, y, yd, x, xd, u);
  const double V = com_velocity(0, t), v1 = V + u[0];
  const double speed = floor_->bounce(-v1);
  if (!std::isfinite(speed) || speed < 0) {
    throw UnphysicalStateError(t.value(), 1, 1, fmt::format("the floor returned speed {} at t = {:.10g}", speed, t.value()));
  }
  // Particle 1's velocity jumps by dv: x_1' by dv, the centre of mass by dv / n.
  const double dv = speed - v1, dV = dv / (hi + 1);
  if (hi > 0) xd[0] += dv;
  form_cluster(0, hi, t, x, xd, V + dV);
  if (hi + 1 < n_) gaps_.c[hi] -= dV;
  floor_s_ = 0.0;
  rebase_floor(t);
  if (hi + 1 < n_) rebase_gap(hi, t);
  ++counters_.floor_hits;
  sink.on_event({EventKind::FloorHit, t.value(), 0, speed, t.low()});
  predict_cluster(0);
  if (hi + 1 < n_) predict_gap(hi);
  predict_floor();
}

// No physics happens: the cluster is re-formed from its own state so that its searches restart.
void ExactEngine::refresh_cluster(int lo, Time t) {
  const int hi = hi_[lo];
  if (lo > 0) sync_gap(lo - 1, t);
  if (hi + 1 < n_) sync_gap(hi, t);
  if (lo == 0) sync_floor(t);
  const double *y = nullptr, *yd = nullptr;
  if (hi > lo) cached_modes(lo, t, y, yd);
  cluster_relative(lo, y, yd, sx_.data(), sxd_.data(), sv_.data());
  form_cluster(lo, hi, t, sx_.data(), sxd_.data(), com_velocity(lo, t));
  if (lo > 0) rebase_gap(lo - 1, t);
  if (hi + 1 < n_) rebase_gap(hi, t);
  if (lo == 0) rebase_floor(t);
  predict_cluster(lo);
  if (lo > 0) predict_gap(lo - 1);
  if (hi + 1 < n_) predict_gap(hi);
  if (lo == 0) predict_floor();
}

}  // namespace granchain
