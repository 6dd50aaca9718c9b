#include "engines/exact/exact_engine.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace granchain {

ExactEngine::ExactEngine(const ChainParameters& p, const ChainState& initial, FloorDrive* floor, bool audit)
    : audit_(audit),
      n_(p.N),
      d_(p.d),
      g_(p.g),
      floor_(floor),
      tables_(p.N, p.k / p.m, damping_constant(p.k, p.e, p.m)) {
  if (n_ < 1 || static_cast<int>(initial.z.size()) != n_ || static_cast<int>(initial.v.size()) != n_) {
    throw std::invalid_argument("ExactEngine: the initial state must hold N positions and velocities");
  }
  const ContactLaw law = contact_law(p);
  k_over_m_ = law.k_over_m;
  D_ = law.D;
  tau_c_ = law.tau_c;
  const double t = initial.t;
  now_ = last_event_t_ = t;
  for (int i = 0; i < n_; ++i) {
    if (!std::isfinite(initial.z[i]) || !std::isfinite(initial.v[i])) {
      throw UnphysicalStateError(t, i + 1, i + 1, fmt::format("non-finite initial state of particle {}", i + 1));
    }
  }
  hi_.assign(n_, -1);
  lo_of_.assign(n_, 0);
  t0_.assign(n_, t);
  search_from_.assign(n_, 0.0);
  grazing_streak_.assign(n_, 0);
  hold_until_.assign(n_, -kInf);
  V0_.assign(n_, 0.0);
  generation_.assign(n_, 0);
  cache_.y.assign(n_, 0.0);
  cache_.yd.assign(n_, 0.0);
  y0_.assign(n_, 0.0);
  yd0_.assign(n_, 0.0);
  amp0_.assign(n_, 0.0);
  gap_s_.assign(n_, 0.0);
  gap_t_.assign(n_, t);
  gap_ua_.assign(n_, 0.0);
  gap_ub_.assign(n_, 0.0);
  for (auto* s : {&sx_, &sxd_, &sv_, &sv2_}) s->assign(n_, 0.0);
  for (int k = 0; k < 2; ++k) {
    sy2_[k].assign(n_, 0.0);
    sx2_[k].assign(n_, 0.0);
  }
  shq_.assign(2 * n_, 0.0);
  smode_.assign(kTaylorOrder * static_cast<std::size_t>(n_), 0.0);
  samp_.assign(2 * n_, 0.0);

  // Clusters: maximal runs of overlapping neighbours.
  std::vector<double> x(n_, 0.0);
  for (int i = 0; i + 1 < n_; ++i) {
    x[i] = d_ - (initial.z[i + 1] - initial.z[i]);
    if (x[i] >= d_) {
      throw UnphysicalStateError(t, i + 1, i + 2,
                                 fmt::format("initial state: particles {} and {} overlap by {:.6g} d or more",
                                             i + 1, i + 2, x[i] / d_));
    }
  }
  for (int lo = 0; lo < n_;) {
    int hi = lo;
    while (hi + 1 < n_ && x[hi] > 0) ++hi;
    form_cluster(lo, hi, t, &x[lo], &initial.v[lo]);
    lo = hi + 1;
  }
  for (int i = 0; i + 1 < n_; ++i) {
    if (lo_of_[i] != lo_of_[i + 1]) {
      gap_s_[i] = -x[i];
      rebase_gap(i, t);
    }
  }
  floor_s_ = initial.z[0] - 0.5 * d_;
  if (floor_ != nullptr && floor_s_ < -1e-12 * d_) {
    throw UnphysicalStateError(t, 1, 1, "initial state: particle 1 is below the floor");
  }
  rebase_floor(t);

  slots_.assign(2 * n_, Slot{kInf, SlotKind::None, 0});
  queue_.reset(2 * n_);
  for (int lo = 0; lo < n_; lo = hi_[lo] + 1) predict_cluster(lo);
  for (int i = 0; i + 1 < n_; ++i) {
    if (lo_of_[i] != lo_of_[i + 1]) predict_gap(i);
  }
  predict_floor();
}

// ----------------------------------------------------------------------------------------------
// Clusters

void ExactEngine::form_cluster(int lo, int hi, double t, const double* x, const double* v) {
  const int n = hi - lo + 1;
  hi_[lo] = hi;
  double vsum = 0.0;
  for (int p = 0; p < n; ++p) {
    lo_of_[lo + p] = lo;
    vsum += v[p];
  }
  t0_[lo] = t;
  search_from_[lo] = 0.0;
  V0_[lo] = vsum / n;
  generation_[lo] = ++formations_;
  if (n >= 2) {
    const ClusterModeTable& tab = tables_[n];
    double* xd = sv2_.data();
    for (int i = 0; i + 1 < n; ++i) xd[i] = v[i] - v[i + 1];  // x_i' = v_i - v_{i+1}
    tab.to_modes(x, &y0_[lo]);
    tab.to_modes(xd, &yd0_[lo]);
    // sqrt(E_j) / omega0_j >= |y_j| at all later times (the energy never grows).
    for (int j = 0; j < tab.M; ++j) {
      const ModeConstants& mc = tab.modes[j];
      const double y = y0_[lo + j], yd = yd0_[lo + j];
      const double s = yd * yd + mc.omega0_sq * y * y;  // underflows for a cluster at rest within round-off
      amp0_[lo + j] = s >= ModeConstants::kNoUnderflow ? std::sqrt(s / mc.omega0_sq) : std::hypot(yd / std::sqrt(mc.omega0_sq), y);
    }
  }
}

void ExactEngine::modes_at(int lo, double tau, double* y, double* yd) const {
  const ClusterModeTable& tab = tables_[cluster_size(lo)];
  if (tau == 0.0) {
    std::copy_n(&y0_[lo], tab.M, y);
    std::copy_n(&yd0_[lo], tab.M, yd);
    return;
  }
  for (int j = 0; j < tab.M; ++j) tab.modes[j].evolve(y0_[lo + j], yd0_[lo + j], tau, y[j], yd[j]);
}

void ExactEngine::cached_modes(int lo, double t, const double*& y, const double*& yd) const {
  if (cache_.lo != lo || cache_.generation != generation_[lo] || cache_.t != t) {
    modes_at(lo, t - t0_[lo], cache_.y.data(), cache_.yd.data());
    cache_.lo = lo;
    cache_.generation = generation_[lo];
    cache_.t = t;
  }
  y = cache_.y.data();
  yd = cache_.yd.data();
}

void ExactEngine::cluster_state(int lo, double t, double* x, double* xd, double* v) const {
  const double *y = nullptr, *yd = nullptr;
  if (cluster_size(lo) >= 2) cached_modes(lo, t, y, yd);
  cluster_state_local(lo, t - t0_[lo], y, yd, x, xd, v);
}

void ExactEngine::cluster_state_local(int lo, double tau, const double* y, const double* yd, double* x,
                                      double* xd, double* v) const {
  const int n = cluster_size(lo);
  const double vcom = V0_[lo] - g_ * tau;
  if (n == 1) {
    v[0] = vcom;
    return;
  }
  const ClusterModeTable& tab = tables_[n];
  tab.to_overlaps(y, x);
  tab.to_overlaps(yd, xd);
  // v_{i+1} = v_i - x_i', shifted so that the mean is the centre-of-mass velocity.
  double vr = 0.0, sum = 0.0;
  for (int p = 0; p < n; ++p) {
    if (p > 0) vr -= xd[p - 1];
    v[p] = vr;
    sum += vr;
  }
  const double shift = vcom - sum / n;
  for (int p = 0; p < n; ++p) v[p] += shift;
}

// u = z_com(t) - z_com(t0) + sum_j c_j y_j(t - t0): the particle's height up to a constant.
double ExactEngine::edge_u(int lo, bool top, double t) const {
  const double tau = t - t0_[lo];
  double u = tau * (V0_[lo] - 0.5 * g_ * tau);
  const int n = cluster_size(lo);
  if (n >= 2) {
    const ClusterModeTable& tab = tables_[n];
    const double* c = top ? tab.top.data() : tab.bottom.data();
    const double *y, *yd;
    cached_modes(lo, t, y, yd);
    for (int j = 0; j < tab.M; ++j) u += c[j] * y[j];
  }
  return u;
}

ExactEngine::EdgeTerm ExactEngine::edge_term(int lo, bool top, double sign, double t) const {
  const ClusterModeTable& tab = tables_[cluster_size(lo)];
  return EdgeTerm{&tab, &y0_[lo], &yd0_[lo], &amp0_[lo], top ? tab.top.data() : tab.bottom.data(), sign, t - t0_[lo]};
}

// ----------------------------------------------------------------------------------------------
// Gaps and the floor height

double ExactEngine::gap_at(int i, double t) const {
  return gap_s_[i] + (edge_u(i + 1, false, t) - gap_ub_[i]) - (edge_u(lo_of_[i], true, t) - gap_ua_[i]);
}

void ExactEngine::sync_gap(int i, double t) {
  const double ua = edge_u(lo_of_[i], true, t), ub = edge_u(i + 1, false, t);
  gap_s_[i] += (ub - gap_ub_[i]) - (ua - gap_ua_[i]);
  gap_t_[i] = t;
  gap_ua_[i] = ua;
  gap_ub_[i] = ub;
}

// A neighbour that did not re-form keeps the displacement origin sync_gap gave it at t.
void ExactEngine::rebase_gap(int i, double t) {
  const int a = lo_of_[i], b = i + 1;
  if (gap_t_[i] != t || t0_[a] == t) gap_ua_[i] = edge_u(a, true, t);
  if (gap_t_[i] != t || t0_[b] == t) gap_ub_[i] = edge_u(b, false, t);
  gap_t_[i] = t;
}

void ExactEngine::sync_floor(double t) {
  const double u = edge_u(0, false, t);
  floor_s_ += u - floor_u_;
  floor_t_ = t;
  floor_u_ = u;
}

void ExactEngine::rebase_floor(double t) {
  floor_t_ = t;
  floor_u_ = edge_u(0, false, t);
}

// ----------------------------------------------------------------------------------------------
// Events

void ExactEngine::split(int lo, int pair, double t, double tau, EventSink& sink) {
  const int hi = hi_[lo];
  if (lo > 0) sync_gap(lo - 1, t);
  if (hi + 1 < n_) sync_gap(hi, t);
  if (lo == 0) sync_floor(t);
  // The cluster is taken at its own root time tau (not t - t0, which rounds): the overlap that
  // ends is zero to round-off and the velocities carry no error of order (dv/dt) ulp(t).
  double* x = sx_.data();
  double* v = sv_.data();
  double* y = sy2_[0].data();
  double* yd = sy2_[1].data();
  modes_at(lo, tau, y, yd);
  cluster_state_local(lo, tau, y, yd, x, sxd_.data(), v);
  const int r = pair - lo;
  const double speed = std::abs(sxd_[r]);
  form_cluster(lo, pair, t, x, v);
  form_cluster(pair + 1, hi, t, x + r + 1, v + r + 1);
  gap_s_[pair] = 0.0;  // the overlap has just returned to zero
  if (lo > 0) rebase_gap(lo - 1, t);
  rebase_gap(pair, t);
  if (hi + 1 < n_) rebase_gap(hi, t);
  if (lo == 0) rebase_floor(t);
  ++counters_.contact_ends;
  sink.on_event({EventKind::ContactEnd, t, pair, speed});
  predict_cluster(lo);
  predict_cluster(pair + 1);
  if (lo > 0) predict_gap(lo - 1);
  predict_gap(pair);
  if (hi + 1 < n_) predict_gap(hi);
  if (lo == 0) predict_floor();
}

void ExactEngine::merge(int pair, double t, EventSink& sink) {
  const int a = lo_of_[pair], b = pair + 1, hi = hi_[b];
  const int na = pair - a + 1;
  if (a > 0) sync_gap(a - 1, t);
  if (hi + 1 < n_) sync_gap(hi, t);
  if (a == 0) sync_floor(t);
  // Overlaps indexed from a: pairs a..pair-1 from cluster a, pair itself (0: contact begins),
  // pairs b..hi-1 from cluster b; velocities of particles a..hi.
  double* x = sx_.data();
  double* v = sv_.data();
  cluster_state(a, t, x, sxd_.data(), v);
  cluster_state(b, t, x + na, sxd_.data() + na, v + na);
  x[na - 1] = 0.0;
  const double speed = std::abs(v[na - 1] - v[na]);
  form_cluster(a, hi, t, x, v);
  // A grazing contact: the gap closed with no approach speed that double precision can resolve
  // (a cluster's edge pushing a particle that rests against it). The new overlap and its rate are
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
  if (speed <= 1e-13 * (std::abs(v[na - 1]) + std::abs(v[na]))) {
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
  sink.on_event({EventKind::ContactBegin, t, pair, speed});
  predict_cluster(a);
  if (a > 0) predict_gap(a - 1);
  if (hi + 1 < n_) predict_gap(hi);
  if (a == 0) predict_floor();
}

void ExactEngine::floor_hit(double t, EventSink& sink) {
  const int hi = hi_[0];
  if (hi + 1 < n_) sync_gap(hi, t);
  double* v = sv_.data();
  cluster_state(0, t, sx_.data(), sxd_.data(), v);
  const double speed = floor_->bounce(-v[0]);
  if (!std::isfinite(speed) || speed < 0) {
    throw UnphysicalStateError(t, 1, 1, fmt::format("the floor returned speed {} at t = {:.10g}", speed, t));
  }
  v[0] = speed;
  form_cluster(0, hi, t, sx_.data(), v);
  floor_s_ = 0.0;
  rebase_floor(t);
  if (hi + 1 < n_) rebase_gap(hi, t);
  ++counters_.floor_hits;
  sink.on_event({EventKind::FloorHit, t, 0, speed});
  predict_cluster(0);
  if (hi + 1 < n_) predict_gap(hi);
  predict_floor();
}

// No physics happens: the cluster is re-formed from its own state so that its searches restart.
void ExactEngine::refresh_cluster(int lo, double t) {
  const int hi = hi_[lo];
  if (lo > 0) sync_gap(lo - 1, t);
  if (hi + 1 < n_) sync_gap(hi, t);
  if (lo == 0) sync_floor(t);
  cluster_state(lo, t, sx_.data(), sxd_.data(), sv_.data());
  form_cluster(lo, hi, t, sx_.data(), sv_.data());
  if (lo > 0) rebase_gap(lo - 1, t);
  if (hi + 1 < n_) rebase_gap(hi, t);
  if (lo == 0) rebase_floor(t);
  predict_cluster(lo);
  if (lo > 0) predict_gap(lo - 1);
  if (hi + 1 < n_) predict_gap(hi);
  if (lo == 0) predict_floor();
}

void ExactEngine::handle(int slot, EventSink& sink) {
  const Slot s = slots_[slot];
  const double t = s.t;
  if (t == last_event_t_) {
    if (++same_time_events_ > kMaxSameTimeEvents) {
      throw UnphysicalStateError(t, s.pair + 1, s.pair + 2,
                                 fmt::format("events pile up at t = {:.17g} without time advancing", t));
    }
  } else {
    same_time_events_ = 0;
    last_event_t_ = t;
  }
  ++counters_.steps;
  if (slot == floor_slot()) {
    if (s.kind == SlotKind::FloorHit) {
      floor_hit(t, sink);
    } else {
      sync_floor(t);
      predict_floor();
    }
  } else if (slot >= n_) {
    const int i = slot - n_;
    if (s.kind == SlotKind::ContactBegin) {
      merge(i, t, sink);
    } else {
      sync_gap(i, t);
      predict_gap(i);
    }
  } else if (s.kind == SlotKind::ContactEnd) {
    split(slot, s.pair, t, s.tau, sink);
  } else if (s.kind == SlotKind::PassThrough) {
    throw UnphysicalStateError(
        t, s.pair + 1, s.pair + 2,
        fmt::format("particles {} and {} passed through each other at t = {:.10g} (overlap reached d)",
                    s.pair + 1, s.pair + 2, t));
  } else {
    refresh_cluster(slot, t);
  }
}

void ExactEngine::advance_to(double t, EventSink& sink) {
  if (!(t >= now_)) throw std::logic_error("ExactEngine::advance_to: time must not go back");
  while (queue_.next_time() <= t) {
    const double t_event = queue_.next_time();
    handle(next_slot(), sink);
    if (audit_) audit_interval(t_event, std::min(queue_.next_time(), t));
    if (sink.stop_requested()) {
      now_ = t_event;
      state_valid_ = false;
      return;
    }
  }
  now_ = t;
  state_valid_ = false;
}

void ExactEngine::set_slot(int slot, double t, SlotKind kind, int pair, double tau) {
  slots_[slot] = Slot{t, kind, pair, tau};
  queue_.set(slot, t);
}

// ----------------------------------------------------------------------------------------------
// Observables

const ChainState& ExactEngine::state() const {
  if (state_valid_) return state_;
  state_.t = now_;
  state_.z.resize(n_);
  state_.v.resize(n_);
  double* x = sx_.data();
  double* u_top = sxd_.data();  // edge displacement u of each cluster's top particle, at lo
  for (int lo = 0; lo < n_; lo = hi_[lo] + 1) {
    double ub;
    if (hi_[lo] == lo) {  // a free particle: a parabola (the common case, written out)
      const double tau = now_ - t0_[lo];
      state_.v[lo] = V0_[lo] - g_ * tau;
      ub = tau * (V0_[lo] - 0.5 * g_ * tau);
      u_top[lo] = ub;
    } else {
      cluster_state(lo, now_, x + lo, sv2_.data(), &state_.v[lo]);
      ub = edge_u(lo, false, now_);  // modes come from the cache
      u_top[lo] = edge_u(lo, true, now_);
    }
    if (lo == 0) {
      state_.z[0] = 0.5 * d_ + floor_s_ + ub - floor_u_;
    } else {
      const int i = lo - 1;  // open pair below this cluster
      x[i] = -(gap_s_[i] + (ub - gap_ub_[i]) - (u_top[lo_of_[i]] - gap_ua_[i]));
    }
  }
  for (int i = 0; i + 1 < n_; ++i) state_.z[i + 1] = state_.z[i] + d_ - x[i];
  state_valid_ = true;
  return state_;
}

std::vector<double> ExactEngine::overlaps() const {
  std::vector<double> x(n_, 0.0), xd(n_, 0.0), v(n_, 0.0);
  for (int lo = 0; lo < n_; lo = hi_[lo] + 1) cluster_state(lo, now_, &x[lo], &xd[lo], &v[lo]);
  for (int i = 0; i + 1 < n_; ++i) {
    if (lo_of_[i] != lo_of_[i + 1]) x[i] = -gap_at(i, now_);
  }
  x.pop_back();
  return x;
}

double ExactEngine::mechanical_energy_per_mass() const {
  const ChainState& s = state();
  const std::vector<double> x = overlaps();
  double e = 0.0;
  for (int i = 0; i < n_; ++i) e += 0.5 * s.v[i] * s.v[i] + g_ * (s.z[i] - 0.5 * d_);
  for (double xi : x) {
    if (xi > 0) e += 0.5 * k_over_m_ * xi * xi;
  }
  return e;
}

}  // namespace granchain
