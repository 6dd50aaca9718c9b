// Binary contacts of two free particles, the commonest event of a dilute column: two single
// particles meet at zero overlap, form a pair whose one mode (lambda = 2) starts at y = 0 with
// rate y' = x'(0) > 0, and part at tau = pi / w = tau_c (Eq. tauc) with y = 0 and y' = -e y'(0)
// (Eq. Dd); the centre of mass flies on in free fall throughout. merge and split handle these with
// the cluster machinery (mode projections, relative velocities, edge mode parts); here the same
// quantities are written out for n = 2, where S = (1), the bottom edge's mode part is y/2 and the
// top one's -y/2, and every one of them is zero at both ends of the contact. Each step below is
// the same floating-point operation as in merge and split, so the trajectory is the same bit for
// bit (ExactOptions::pair_shortcuts, and the test that compares the two).
#include <cmath>

#include "engines/exact/exact_engine.hpp"

namespace granchain {

// The gap between the single particles a = pair and b = pair + 1 closes with rate c = gap_c < 0.
void ExactEngine::merge_free_pair(int pair, Time t, EventSink& sink) {
  const int a = pair, b = pair + 1;
  if (a > 0) sync_gap(a - 1, t);
  if (b + 1 < n_) sync_gap(b, t);
  if (a == 0) sync_floor(t);
  // merge: the overlap's rate is -(c + u_b - u_a), u = 0 for single particles; the pair's centre
  // of mass moves at V_a + c / 2.
  const double c = gaps_.c[pair];
  const double speed = std::abs(c);
  const double dVa = c * 1 / 2, dVb = dVa - c;
  const double V = com_velocity(a, t) + dVa;
  hi_[a] = b;
  lo_of_[b] = a;
  t0_[a] = t;
  search_from_[a] = 0.0;
  V0_[a] = V;
  generation_[a] = ++formations_;
  y0_[a] = 0.0 + pair_table_->S[0] * 0.0;  // y = S^T x (to_modes)
  yd0_[a] = 0.0 + pair_table_->S[0] * -c;
  amp0_[a] = pair_table_->modes[0].energy_amplitude(y0_[a], yd0_[a]);
  if (a > 0) gaps_.c[a - 1] += dVa;
  if (b + 1 < n_) gaps_.c[b] -= dVb;
  grazing_streak_[pair] = 0;  // a resolvable contact: merge's non-grazing branch
  hold_until_[pair] = -kInf;
  set_slot(cluster_slot(b), kInf, SlotKind::None, b);
  set_slot(gap_slot(pair), kInf, SlotKind::None, pair);
  // rebase_gap and rebase_floor: the pair's edge mode parts are zero at its formation.
  if (a > 0) {
    if (t0_[lo_of_[a - 1]] == t) gap_ma_[a - 1] = edge_mode(lo_of_[a - 1], true, t);
    gap_mb_[a - 1] = 0.0;
  }
  if (b + 1 < n_) {
    gap_ma_[b] = 0.0;
    if (t0_[b + 1] == t) gap_mb_[b] = edge_mode(b + 1, false, t);
  }
  if (a == 0) {
    floor_t_ = t;
    floor_u_ = bottom_u_mode(t, 0.0);
  }
  sink.on_event({EventKind::ContactBegin, t.value(), pair, speed, t.low()});
  // predict_cluster: the pair's end in closed form (pair_contact_end: y0 = 0, y' > 0) unless an
  // overlap could reach d.
  if (pair_table_->s_max * (0.0 + amp0_[a]) < d_ && yd0_[a] > 0) {
    ++counters_.closed_form_predictions;
    set_slot(cluster_slot(a), t + pair_.tau, SlotKind::ContactEnd, a, pair_.tau);
  } else {
    predict_cluster(a);
  }
  // predict_gap next to the pair and a single particle: no holds on either side, and the pair's
  // edge reaches |1/2| amp0 (edge_reach) in either direction.
  const Time horizon = slot_time(cluster_slot(a));  // the single particle's slot is never earlier
  const double reach = 0.0 + 0.5 * amp0_[a];
  auto predict_outer = [&](int i, bool single_beyond) {
    if (single_beyond &&
        bound_excludes(bound_clear(gaps_.s[i] - gap_mb_[i] + gap_ma_[i], gaps_.c[i], 0.0, reach, true), horizon - t)) {
      clear_slot_before(gap_slot(i), horizon, i);
    } else {
      predict_gap(i);
    }
  };
  if (a > 0) predict_outer(a - 1, lo_of_[a - 1] == a - 1);
  if (b + 1 < n_) predict_outer(b, hi_[b + 1] == b + 1);
  if (a == 0) predict_floor();
}

// The pair lo, lo + 1, begun at zero overlap, parts at its own time pi / w.
void ExactEngine::split_fresh_pair(int lo, Time t, EventSink& sink) {
  const int hi = lo + 1;
  // modes_at and cluster_relative: y = 0, y' = -e y'(0); x' = S y'; u = (x'/2, -x'/2).
  const double xd = 0.0 + pair_table_->S[0] * (-pair_.restitution * yd0_[lo]);
  if (lo > 0) sync_gap_edges(lo - 1, t, edge_mode(lo_of_[lo - 1], true, t), 0.0);
  if (hi + 1 < n_) sync_gap_edges(hi, t, 0.0, edge_mode(hi + 1, false, t));
  if (lo == 0) sync_floor_mode(t, 0.0);
  const double speed = std::abs(xd);
  const double u_lower = xd / 2, u_upper = -xd / 2;
  part(lo, lo, hi, t, nullptr, nullptr, V0_[lo] - g_ * pair_.tau, u_lower, u_upper, speed, sink);
}

}  // namespace granchain
