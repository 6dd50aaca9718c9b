#include "engines/exact/exact_engine.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace granchain {

ExactEngine::ExactEngine(const ChainParameters& p, const ChainState& initial, FloorDrive* floor, ExactOptions options)
    : shortcuts_(options.pair_shortcuts),
      audit_(options.audit),
      n_(p.N),
      d_(p.d),
      g_(p.g),
      floor_(floor),
      // Above a plate, a grounded cluster of n particles uses the mirror cluster's table of 2n.
      tables_(floor != nullptr && floor->plate() != nullptr ? 2 * p.N : p.N, p.k / p.m, damping_constant(p.k, p.e, p.m)) {
  if (n_ < 1 || static_cast<int>(initial.z.size()) != n_ || static_cast<int>(initial.v.size()) != n_) {
    throw std::invalid_argument("ExactEngine: the initial state must hold N positions and velocities");
  }
  const ContactLaw law = contact_law(p);
  k_over_m_ = law.k_over_m;
  D_ = law.D;
  tau_c_ = law.tau_c;
  if (n_ >= 2) pair_table_ = &tables_[2];
  if (n_ >= 2 && tables_[2].modes[0].kind == ModeKind::Under) {
    const ModeConstants& mc = tables_[2].modes[0];
    pair_.tau = std::numbers::pi / mc.w;
    pair_.restitution = std::exp(-mc.beta * pair_.tau);
  }
  const double t = initial.t;
  now_ = t;
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
  gaps_.reset(n_, t);
  gap_ma_.assign(n_, 0.0);
  gap_mb_.assign(n_, 0.0);
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
  std::vector<double> xd(n_, 0.0);
  for (int i = 0; i + 1 < n_; ++i) xd[i] = initial.v[i] - initial.v[i + 1];  // x_i' = v_i - v_{i+1}
  for (int lo = 0; lo < n_;) {
    int hi = lo;
    double vsum = initial.v[lo];
    while (hi + 1 < n_ && x[hi] > 0) vsum += initial.v[++hi];
    form_cluster(lo, hi, t, &x[lo], &xd[lo], vsum / (hi - lo + 1));
    lo = hi + 1;
  }
  for (int i = 0; i + 1 < n_; ++i) {
    if (lo_of_[i] != lo_of_[i + 1]) {
      gaps_.s[i] = -x[i];
      gaps_.c[i] = V0_[i + 1] - V0_[lo_of_[i]];
      rebase_gap(i, t);
    }
  }
  floor_s_ = initial.z[0] - 0.5 * d_;
  plate_ = floor_ != nullptr ? floor_->plate() : nullptr;
  if (plate_ != nullptr) {
    if (audit_) throw std::invalid_argument("ExactEngine: the audit does not cover a vibrating plate");
    sine_ = plate_->kind() == DriveKind::Sine;
    start_piece(now_);
    for (auto* v : {&gy0_, &gyd0_, &gamp0_, &gx_, &gxd_, &gy_, &gyd_, &gc_re_, &gc_im_, &gP_re_, &gP_im_, &gP_abs_, &gf_, &gfd_})
      v->assign(2 * static_cast<std::size_t>(n_), 0.0);
    // The searches' scratch for a mirror cluster of up to 2N particles (2N - 1 modes).
    smode_.assign(kTaylorOrder * 2 * static_cast<std::size_t>(n_), 0.0);
    samp_.assign(4 * static_cast<std::size_t>(n_), 0.0);
    for (auto* v : {&gxr_, &gxdr_, &gv_}) v->assign(static_cast<std::size_t>(n_) + 1, 0.0);
  }
  const double surface = plate_ != nullptr ? plate_z(now_) : 0.0;
  if (floor_ != nullptr && floor_s_ < surface - 1e-12 * d_) {
    throw UnphysicalStateError(t, 1, 1, plate_ ? "initial state: particle 1 is below the plate" : "initial state: particle 1 is below the floor");
  }
  rebase_floor(t);

  schedule_.reset(n_, true);
  for (int lo = 0; lo < n_; lo = hi_[lo] + 1) predict_cluster(lo);
  for (int i = 0; i + 1 < n_; ++i) {
    if (lo_of_[i] != lo_of_[i + 1]) predict_gap(i);
  }
  predict_floor();
}

// ----------------------------------------------------------------------------------------------
// Clusters

void ExactEngine::form_cluster(int lo, int hi, Time t, const double* x, const double* xd, double V) {
  const int n = hi - lo + 1;
  hi_[lo] = hi;
  for (int p = 0; p < n; ++p) lo_of_[lo + p] = lo;
  t0_[lo] = t;
  search_from_[lo] = 0.0;
  V0_[lo] = V;
  generation_[lo] = ++formations_;
  if (n >= 2) {
    const ClusterModeTable& tab = tables_[n];
    tab.to_modes(x, &y0_[lo]);
    tab.to_modes(xd, &yd0_[lo]);
    // sqrt(E_j) / omega0_j >= |y_j| at all later times (the energy never grows).
    for (int j = 0; j < tab.M; ++j) amp0_[lo + j] = tab.modes[j].energy_amplitude(y0_[lo + j], yd0_[lo + j]);
  }
}

void ExactEngine::modes_at(int lo, double tau, double* y, double* yd) const {
  const int n = cluster_size(lo);
  // A binary contact begun at zero overlap, at its end tau = pi / w: the overlap is zero and its
  // rate -e times the initial one (Eqs. tauc, Dd), with e = exp(-beta pi / w) of this mode.
  if (n == 2 && y0_[lo] == 0.0 && tau == pair_.tau) {
    y[0] = 0.0;
    yd[0] = -pair_.restitution * yd0_[lo];
    return;
  }
  const ClusterModeTable& tab = tables_[n];
  if (tau == 0.0) {
    std::copy_n(&y0_[lo], tab.M, y);
    std::copy_n(&yd0_[lo], tab.M, yd);
    return;
  }
  for (int j = 0; j < tab.M; ++j) tab.modes[j].evolve(y0_[lo + j], yd0_[lo + j], tau, y[j], yd[j]);
}

void ExactEngine::seed_cache(int lo, Time t, const double* y, const double* yd) const {
  if (cache_.lo == lo && cache_.generation == generation_[lo] && cache_.t == t) return;
  const int M = cluster_size(lo) - 1;
  std::copy_n(y, M, cache_.y.data());
  std::copy_n(yd, M, cache_.yd.data());
  cache_.lo = lo;
  cache_.generation = generation_[lo];
  cache_.t = t;
}

void ExactEngine::cached_modes(int lo, Time t, const double*& y, const double*& yd) const {
  if (cache_.lo != lo || cache_.generation != generation_[lo] || cache_.t != t) {
    modes_at(lo, t - t0_[lo], cache_.y.data(), cache_.yd.data());
    cache_.lo = lo;
    cache_.generation = generation_[lo];
    cache_.t = t;
  }
  y = cache_.y.data();
  yd = cache_.yd.data();
}

void ExactEngine::cluster_state(int lo, Time t, double* x, double* xd, double* v) const {
  const double *y = nullptr, *yd = nullptr;
  if (cluster_size(lo) >= 2) cached_modes(lo, t, y, yd);
  cluster_relative(lo, y, yd, x, xd, v);
  const double V = com_velocity(lo, t);
  for (int p = 0; p < cluster_size(lo); ++p) v[p] += V;
}

void ExactEngine::cluster_relative(int lo, const double* y, const double* yd, double* x, double* xd, double* u) const {
  const int n = cluster_size(lo);
  if (n == 1) {
    u[0] = 0.0;
    return;
  }
  const ClusterModeTable& tab = tables_[n];
  tab.to_overlaps(y, x);
  tab.to_overlaps(yd, xd);
  // v_{i+1} = v_i - x_i', shifted so that the mean is zero.
  double vr = 0.0, sum = 0.0;
  for (int p = 0; p < n; ++p) {
    if (p > 0) vr -= xd[p - 1];
    u[p] = vr;
    sum += vr;
  }
  const double shift = sum / n;
  for (int p = 0; p < n; ++p) u[p] -= shift;
}

double ExactEngine::cluster_edge_mode(int lo, bool top, Time t) const {
  const ClusterModeTable& tab = tables_[cluster_size(lo)];
  const double* c = top ? tab.top.data() : tab.bottom.data();
  const double *y, *yd;
  cached_modes(lo, t, y, yd);
  double u = 0.0;
  for (int j = 0; j < tab.M; ++j) u += c[j] * y[j];
  return u;
}

// u = z_com(t) - z_com(t0) + sum_j c_j y_j(t - t0): particle 1's height up to a constant.
double ExactEngine::bottom_u_mode(Time t, double mode) const {
  const double tau = t - t0_[0];
  return tau * (V0_[0] - 0.5 * g_ * tau) + mode;
}

ExactEngine::EdgeTerm ExactEngine::edge_term(int lo, bool top, double sign, Time t) const {
  const ClusterModeTable& tab = tables_[cluster_size(lo)];
  return EdgeTerm{&tab, &y0_[lo], &yd0_[lo], &amp0_[lo], top ? tab.top.data() : tab.bottom.data(), sign, t - t0_[lo]};
}

// ----------------------------------------------------------------------------------------------
// Gaps and the floor height

double ExactEngine::gap_at(int i, Time t) const {
  return gap_from_edges(i, t, edge_mode(lo_of_[i], true, t), edge_mode(i + 1, false, t));
}

void ExactEngine::sync_gap(int i, Time t) { sync_gap_edges(i, t, edge_mode(lo_of_[i], true, t), edge_mode(i + 1, false, t)); }

void ExactEngine::sync_gap_edges(int i, Time t, double ma, double mb) {
  if (i == ground_gap()) {  // above the grounded cluster: the line bends with -g and the plate's Z (gap_line)
    const Time t_ref = gaps_.t[i];
    const double tau = t - t_ref;
    gaps_.s[i] += tau * (gaps_.c[i] - 0.5 * g_ * tau) - ground_zdev(t_ref, t) + (mb - gap_mb_[i]) - (ma - gap_ma_[i]);
    gaps_.c[i] += -g_ * tau - (ground_zdot(t) - ground_zdot(t_ref));
    gaps_.t[i] = t;
    gap_ma_[i] = ma;
    gap_mb_[i] = mb;
    return;
  }
  gaps_.s[i] += gaps_.c[i] * (t - gaps_.t[i]) + (mb - gap_mb_[i]) - (ma - gap_ma_[i]);
  gaps_.t[i] = t;
  gap_ma_[i] = ma;
  gap_mb_[i] = mb;
}

// A neighbour that did not re-form keeps the mode-part origin sync_gap gave it at t.
void ExactEngine::rebase_gap(int i, Time t) {
  const int a = lo_of_[i], b = i + 1;
  if (gaps_.t[i] != t || t0_[a] == t) gap_ma_[i] = edge_mode(a, true, t);
  if (gaps_.t[i] != t || t0_[b] == t) gap_mb_[i] = edge_mode(b, false, t);
  gaps_.t[i] = t;
}

void ExactEngine::sync_floor(Time t) { sync_floor_mode(t, edge_mode(0, false, t)); }

void ExactEngine::sync_floor_mode(Time t, double mode) {
  const double u = bottom_u_mode(t, mode);
  floor_s_ += u - floor_u_;
  floor_t_ = t;
  floor_u_ = u;
}

void ExactEngine::rebase_floor(Time t) {
  floor_t_ = t;
  floor_u_ = bottom_u(t);
}

// ----------------------------------------------------------------------------------------------
// The event loop (the events themselves: exact_events.cpp, exact_binary.cpp)

void ExactEngine::handle(int slot, const Time& t, EventSink& sink) {
  const SlotDetail s = schedule_.detail(slot);
  ++counters_.steps;
  const auto [family, index] = schedule_.slot_of(slot);
  switch (family) {
    case EventFamily::Floor:
      if (s.kind == SlotKind::FloorHit) {
        if (plate_ != nullptr) plate_contact(t, sink);
        else floor_hit(t, sink);
      } else if (s.kind == SlotKind::PlateSwitch) {
        plate_switch(t, sink);
      } else {
        sync_floor(t);
        predict_floor();
      }
      return;
    case EventFamily::Interaction: {
      const int i = index;
      if (i == ground_gap() && s.kind == SlotKind::ContactBegin) {
        grounded_merge(i, t, sink);
      } else if (s.kind != SlotKind::ContactBegin) {
        sync_gap(i, t);
        predict_gap(i);
      } else if (shortcuts_ && lo_of_[i] == i && hi_[i + 1] == i + 1 && pair_.tau > 0 && gaps_.c[i] != 0.0) {
        // Two free particles meeting with a resolvable speed (c != 0): the short path.
        ++shortcut_events_;
        merge_free_pair(i, t, sink);
      } else {
        merge(i, t, sink);
      }
      return;
    }
    case EventFamily::Local: {
      const int lo = index;
      if (lo == 0 && grounded_) {
        if (s.kind == SlotKind::ContactEnd && s.pair < 0) {
          plate_release(t, s.tau, sink, true);
        } else if (s.kind == SlotKind::ContactEnd) {
          grounded_split(s.pair, t, s.tau, sink);
        } else if (s.kind == SlotKind::PassThrough) {
          throw UnphysicalStateError(t.value(), s.pair < 0 ? 1 : s.pair + 1, s.pair < 0 ? 1 : s.pair + 2,
                                     s.pair < 0 ? fmt::format("particle 1 passed through the plate at t = {:.10g}", t.value())
                                                : fmt::format("particles {} and {} passed through each other at t = {:.10g} "
                                                              "(overlap reached d)", s.pair + 1, s.pair + 2, t.value()));
        } else {
          reform_grounded(t, false);  // a refresh: no physics
        }
        return;
      }
      if (s.kind == SlotKind::ContactEnd) {
        if (shortcuts_ && is_fresh_pair(lo) && s.tau == pair_.tau) {
          ++shortcut_events_;
          split_fresh_pair(lo, t, sink);
        } else {
          split(lo, s.pair, t, s.tau, sink);
        }
      } else if (s.kind == SlotKind::PassThrough) {
        throw UnphysicalStateError(
            t.value(), s.pair + 1, s.pair + 2,
            fmt::format("particles {} and {} passed through each other at t = {:.10g} (overlap reached d)",
                        s.pair + 1, s.pair + 2, t.value()));
      } else {
        refresh_cluster(lo, t);
      }
      return;
    }
  }
}

void ExactEngine::advance_to(double t_end, EventSink& sink) {
  const Time t = t_end;
  if (!(t >= now_)) throw std::logic_error("ExactEngine::advance_to: time must not go back");
  now_ = run_events(schedule_, t, sink, [&](int slot, const Time& t_event) {
    handle(slot, t_event, sink);
    if (audit_) audit_interval(t_event, std::min(schedule_.next_time(), t));
  });
  state_valid_ = false;
}

void ExactEngine::set_slot(int slot, const Time& t, SlotKind kind, int pair, double tau) {
  schedule_.set(slot, t, SlotDetail{kind, pair, tau});
}

}  // namespace granchain
