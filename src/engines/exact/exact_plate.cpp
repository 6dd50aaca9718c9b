// The exact engine above a vibrating plate with a piecewise drive (exact_engine.hpp): the grounded
// cluster (particle 1 touching the plate) as the symmetric half of a mirror cluster, its events
// (the plate's contact beginning and ending, a pair of it parting, a gap above it closing, the end of
// a piece of the plate's motion) and its searches.
//
// The mirror cluster has V = 2n particles and M = 2n - 1 overlaps: virtual overlap n - 1 is X =
// 2 x_w (particle 1 and its image), virtual overlap n + r is real pair r and n - 2 - r its image.
// In overlap coordinates (cluster_modes.hpp) x'' = -(k/m) L x - D L x' + F e_mid with F = 2 (g + a_p)
// (the plate's frame accelerates at a_p), so on a piece of the motion
//   x = x_p + S y,   x_p,i = (g + a_p) / (k/m) min(i + 1, M - i)   (L^-1 of the middle column),
// and y holds the free modes of tables_[2n]; those odd in the middle (0-based j odd) stay zero.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "engines/exact/exact_engine.hpp"
#include "engines/exact/taylor_bounds.hpp"
#include "engines/plate_flight.hpp"

namespace granchain {

using taylor::Jet;
using taylor::at_root;
using taylor::quadratic_step;
using taylor::safe_step;
using taylor::P;

void ExactEngine::start_piece(Time t) {
  const plate_flight::PieceState p = plate_flight::piece_state(*plate_, t.value());
  piece_.t0 = t;
  piece_.z = p.z;
  piece_.v = p.v;
  piece_.a = p.a;
  piece_.end = Time(plate_->next_switch(t.value()));
  piece_.drop = plate_->kind() == DriveKind::Sawtooth;
  gp2_ = -(g_ + piece_.a);
  if (sine_) {  // one piece for ever; the sinusoid's own functions (plate_z, ground_zdev) serve
    piece_.a = 0.0;
    gp2_ = -g_;
  }
}

double ExactEngine::ground_zdot(Time t) const {
  if (!sine_) return plate_v(t);
  const double th = plate_phase(t);
  return plate_->omega() * (gW_re_ * std::cos(th) - gW_im_ * std::sin(th));  // omega Re(W e^{i theta})
}

double ExactEngine::ground_zdev(Time t_ref, Time t) const {
  const double tau = t - t_ref;
  if (!sine_) return 0.5 * piece_.a * tau * tau;
  const double a = plate_phase(t_ref), b = plate_phase(t);
  const double z_ref = gW_re_ * std::sin(a) + gW_im_ * std::cos(a), z = gW_re_ * std::sin(b) + gW_im_ * std::cos(b);
  return z - z_ref - tau * plate_->omega() * (gW_re_ * std::cos(a) - gW_im_ * std::sin(a));
}

double ExactEngine::grounded_offset(int i) const {
  const int M = 2 * gn_ - 1;
  return (g_ + piece_.a) / k_over_m_ * std::min(i + 1, M - i);  // piece_.a = 0 for the sine (its a_p is in c_j)
}

void ExactEngine::form_grounded(int n, Time t, const double* xr, const double* xdr) {
  const int V = 2 * n, M = V - 1;
  const ClusterModeTable& tab = tables_[V];
  hi_[0] = n - 1;
  for (int p = 0; p < n; ++p) lo_of_[p] = 0;
  grounded_ = true;
  gn_ = n;
  gt0_ = t;
  t0_[0] = t;
  g_search_from_ = 0.0;
  generation_[0] = ++formations_;
  double* xv = gx_.data();
  double* xdv = gxd_.data();
  xv[n - 1] = xr[0] - grounded_offset(n - 1);
  xdv[n - 1] = xdr[0];
  for (int q = 1; q < n; ++q) {
    xv[n - 1 + q] = xv[n - 1 - q] = xr[q] - grounded_offset(n - 1 + q);
    xdv[n - 1 + q] = xdv[n - 1 - q] = xdr[q];
  }
  tab.to_modes(xv, gy0_.data());
  tab.to_modes(xdv, gyd0_.data());
  if (sine_) {
    // The sine's particular solution: F(t) = Im(F e^{i theta}) on the middle overlap with
    // F = -2 A omega^2, so mode j answers with c_j = S_mid,j F / (omega0_j^2 - omega^2 + 2 i beta_j omega).
    const double w = plate_->omega(), F = -2.0 * plate_->amplitude() * w * w;
    gW_re_ = plate_->amplitude();
    gW_im_ = 0.0;
    for (int j = 0; j < M; ++j) {
      const ModeConstants& mc = tab.modes[j];
      const double re = mc.omega0_sq - w * w, im = 2.0 * mc.beta * w, den = re * re + im * im;
      const double f = tab.S[static_cast<std::size_t>(n - 1) * M + j] * F;
      if (j % 2 == 1 || f == 0.0) {
        gc_re_[j] = gc_im_[j] = 0.0;
        continue;
      }
      if (!(den > 0)) throw UnphysicalStateError(t.value(), 1, n, "the plate drives a mode of the resting column at its resonance");
      gc_re_[j] = f * re / den;
      gc_im_[j] = -f * im / den;
      gW_re_ += tab.top[j] * gc_re_[j];
      gW_im_ += tab.top[j] * gc_im_[j];
    }
    tab.to_overlaps(gc_re_.data(), gP_re_.data());
    tab.to_overlaps(gc_im_.data(), gP_im_.data());
    // The free modes start from the state less the particular solution at t.
    const double th = plate_phase(t), sn = std::sin(th), cs = std::cos(th);
    for (int j = 0; j < M; ++j) {
      gy0_[j] -= gc_re_[j] * sn + gc_im_[j] * cs;
      gyd0_[j] -= w * (gc_re_[j] * cs - gc_im_[j] * sn);
    }
  }
  for (int j = 0; j < M; ++j) {
    if (j % 2 == 1) gy0_[j] = gyd0_[j] = 0.0;  // antisymmetric about the middle: absent by symmetry
    gamp0_[j] = tab.modes[j].energy_amplitude(gy0_[j], gyd0_[j]);
  }
}

void ExactEngine::grounded_modes(double tau, double* y, double* yd) const {
  const ClusterModeTable& tab = tables_[2 * gn_];
  for (int j = 0; j < tab.M; ++j) {
    if (j % 2 == 1) {
      y[j] = yd[j] = 0.0;
    } else {
      tab.modes[j].evolve(gy0_[j], gyd0_[j], tau, y[j], yd[j]);
    }
  }
}

void ExactEngine::grounded_state(double tau, Time t, double* xr, double* xdr, double* v) const {
  const int n = gn_;
  const ClusterModeTable& tab = tables_[2 * n];
  double* y = gy_.data();
  double* yd = gyd_.data();
  grounded_modes(tau, y, yd);
  if (sine_) {  // plus the particular solution, Im(c e^{i theta}) and its rate
    const double w = plate_->omega(), th = plate_phase(t), sn = std::sin(th), cs = std::cos(th);
    for (int j = 0; j < tab.M; j += 2) {
      y[j] += gc_re_[j] * sn + gc_im_[j] * cs;
      yd[j] += w * (gc_re_[j] * cs - gc_im_[j] * sn);
    }
  }
  double* xv = gx_.data();
  double* xdv = gxd_.data();
  tab.to_overlaps(y, xv);
  tab.to_overlaps(yd, xdv);
  for (int q = 0; q < n; ++q) {
    xr[q] = xv[n - 1 + q] + grounded_offset(n - 1 + q);
    xdr[q] = xdv[n - 1 + q];
  }
  if (v == nullptr) return;
  // Particle 1 moves at v_p - X'/2; up the cluster v_{q} = v_{q-1} - x'_{q-1} (x' = v_i - v_{i+1}).
  v[0] = plate_v(t) - 0.5 * xdr[0];
  for (int q = 1; q < n; ++q) v[q] = v[q - 1] - xdr[q];
}

double ExactEngine::grounded_edge_top(Time t) const {
  const ClusterModeTable& tab = tables_[2 * gn_];
  double* y = gy_.data();
  double* yd = gyd_.data();
  grounded_modes(t - gt0_, y, yd);
  double u = 0.0;
  for (int j = 0; j < tab.M; ++j) u += tab.top[j] * y[j];
  return u;
}

double ExactEngine::grounded_reach_top(double acc) const {
  const ClusterModeTable& tab = tables_[2 * gn_];
  for (int j = 0; j < tab.M; ++j) acc += std::abs(tab.top[j]) * gamp0_[j];
  return acc;
}

// As first_internal_root, over the mirror modes with the particular solution added, watching the
// real overlaps only: function k < n is real overlap k (0: the plate's X, r + 1: pair r), k >= n
// (when watched) its distance to passing through (2d - X for the plate, d - x for a pair).
ExactEngine::Root ExactEngine::first_grounded_root(bool watch_pass_through) const {
  const int n = gn_;
  const ClusterModeTable& tab = tables_[2 * n];
  const int M = tab.M;
  std::vector<double> yn(static_cast<std::size_t>(P) * M), amp2(M), ampP(M);
  double* x = gx_.data();
  double* xd = gxd_.data();
  double tau = g_search_from_;
  const int functions = watch_pass_through ? 2 * n : n;
  const auto virtual_index = [n](int k) { return n - 1 + (k < n ? k : k - n); };
  double offset_max = 0.0;
  for (int q = 0; q < n; ++q) offset_max = std::max(offset_max, std::abs(grounded_offset(n - 1 + q)));
  for (int it = 0; it < kMaxIterations; ++it) {
    ++counters_.search_steps;
    double sum2 = 0.0, sum_amp = 0.0;
    for (int j = 0; j < M; ++j) {
      const ModeConstants& mc = tab.modes[j];
      double y = 0.0, yd = 0.0;
      if (j % 2 == 0) mc.evolve(gy0_[j], gyd0_[j], tau, y, yd);
      yn[j] = y;
      yn[M + j] = yd;
      double ym = y, yc = yd;
      for (int q = 2; q < P; ++q) {
        const double next = mc.acceleration(ym, yc);
        yn[q * M + j] = next;
        ym = yc;
        yc = next;
      }
      const double amp = mc.amplitude(y, yd);
      amp2[j] = mc.bound[2] * amp;
      ampP[j] = mc.bound[P] * amp;
      sum2 += amp2[j];
      sum_amp += amp;
    }
    double m2 = tab.s_max * sum2;
    tab.to_overlaps(yn.data(), x);
    tab.to_overlaps(yn.data() + M, xd);
    // The sine's particular solution of overlap i: Im(P_i e^{i theta}), derivative q Im(P_i (i w)^q e^{i theta}).
    const double w = sine_ ? plate_->omega() : 0.0;
    const double th = sine_ ? plate_phase(gt0_) + w * tau : 0.0, sn = std::sin(th), cs = std::cos(th);
    const auto particular = [&](int i, int q) {  // q-th derivative
      if (!sine_) return 0.0;
      const double re = gP_re_[i] * cs - gP_im_[i] * sn, im = gP_re_[i] * sn + gP_im_[i] * cs;  // P e^{i theta}
      const double wq = std::pow(w, q);
      switch (q % 4) {  // Im(i^q P e^{i theta})
        case 0: return wq * im;
        case 1: return wq * re;
        case 2: return -wq * im;
        default: return -wq * re;
      }
    };
    const auto particular_amp = [&](int i) { return sine_ ? std::hypot(gP_re_[i], gP_im_[i]) : 0.0; };
    if (sine_) {
      double pmax = 0.0;
      for (int q = 0; q < n; ++q) pmax = std::max(pmax, particular_amp(n - 1 + q));
      m2 += pmax * w * w;
    }
    const auto limit = [&](int k) { return k - n == 0 ? 2.0 * d_ : d_; };
    const auto value = [&](int k) {
      const int i = virtual_index(k);
      const double xi = x[i] + grounded_offset(i) + particular(i, 0);
      return k < n ? xi : limit(k) - xi;
    };
    const auto rate = [&](int k) {
      const int i = virtual_index(k);
      return (k < n ? 1.0 : -1.0) * (xd[i] + particular(i, 1));
    };
    const auto jet_of = [&](int k) {
      const int i = virtual_index(k);
      const double sign = k < n ? 1.0 : -1.0;
      const double* row = &tab.S[static_cast<std::size_t>(i) * M];
      const double* abs_row = &tab.abs_S[static_cast<std::size_t>(i) * M];
      Jet jk;
      jk.d[0] = value(k);
      jk.d[1] = rate(k);
      static_assert(P == 6, "the overlap jet below is written out for derivatives 2 .. 5");
      double s2 = 0.0, s3 = 0.0, s4 = 0.0, s5 = 0.0, b2 = 0.0, bP = 0.0;
      for (int j = 0; j < M; ++j) {
        s2 += row[j] * yn[2 * M + j];
        s3 += row[j] * yn[3 * M + j];
        s4 += row[j] * yn[4 * M + j];
        s5 += row[j] * yn[5 * M + j];
        b2 += abs_row[j] * amp2[j];
        bP += abs_row[j] * ampP[j];
      }
      jk.d[2] = sign * (s2 + particular(i, 2));
      jk.d[3] = sign * (s3 + particular(i, 3));
      jk.d[4] = sign * (s4 + particular(i, 4));
      jk.d[5] = sign * (s5 + particular(i, 5));
      const double pa = particular_amp(i);
      jk.m2 = b2 + pa * w * w;
      jk.mP = bP + pa * std::pow(w, P);
      return jk;
    };
    const double skip = kResolutionSkip * tau_c_;
    const double zero =
        it >= kStallSteps ? 8 * std::numeric_limits<double>::epsilon() * (tab.s_max * sum_amp + offset_max + 2 * d_) : 0.0;
    const auto step_of = [&](double f, double step) { return f <= zero ? std::max(step, skip) : step; };
    double h = kInf;
    int which = -1;
    Jet jw;
    for (int k = 0; k < functions; ++k) {
      const double f = value(k), f1 = rate(k);
      if (f <= zero) {
        const Jet jk = jet_of(k);
        if (at_root(jk.d[0] - zero, jk.d[1], jk.d[2], jk.d[3])) return {Root::Found, tau, k};
      }
      if (h < kInf && f > 0 && f + h * (f1 - 0.5 * m2 * h) > 0) continue;  // clear over the best step so far
      const double hq = step_of(f, quadratic_step(f, f1, -0.5 * m2));
      if (!(hq < h)) continue;
      const Jet jk = jet_of(k);
      const double hk = step_of(jk.d[0], safe_step(jk, kInf));
      if (hk < h) {
        h = hk;
        which = k;
        jw = jk;
      }
    }
    if (h == kInf) return {Root::None, kInf, 0};
    if (h == skip && jw.d[0] <= zero) ++counters_.resolution_skips;
    if (jw.root_upper() - h <= 1e-15 * (tau + tau_c_)) return {Root::Found, tau + h, which};
    tau += h;
  }
  return {Root::Refresh, tau, 0};
}

void ExactEngine::predict_grounded() {
  const int n = gn_;
  double reach = 0.0, offset_max = 0.0;
  for (double a : gamp0_) reach += a;
  for (int q = 0; q < n; ++q) {
    const double p = sine_ ? std::hypot(gP_re_[n - 1 + q], gP_im_[n - 1 + q]) : 0.0;
    offset_max = std::max(offset_max, grounded_offset(n - 1 + q) + p);
  }
  const bool watch = tables_[2 * n].s_max * reach + offset_max >= d_;
  const std::uint64_t steps_before = counters_.search_steps;
  const Root r = first_grounded_root(watch);
  ++counters_.cluster_searches;
  counters_.cluster_search_steps += counters_.search_steps - steps_before;
  switch (r.kind) {
    case Root::Found:
      // SlotDetail::pair: -1 for the plate, r for pair r.
      if (r.which >= n) set_slot(cluster_slot(0), gt0_ + r.sigma, SlotKind::PassThrough, r.which - n - 1);
      else set_slot(cluster_slot(0), gt0_ + r.sigma, SlotKind::ContactEnd, r.which - 1, r.sigma);
      break;
    case Root::Refresh: set_slot(cluster_slot(0), gt0_ + r.sigma, SlotKind::Refresh, 0); break;
    case Root::None: set_slot(cluster_slot(0), kInf, SlotKind::None, 0); break;
  }
}

// The gap above the grounded cluster: a parabola (the upper cluster's centre of mass falls freely,
// the plate moves on its piece) plus the upper cluster's bottom edge and the grounded top edge.
void ExactEngine::predict_ground_gap(int i) {
  const int b = i + 1;
  const Time t = gaps_.t[i];
  Time horizon = std::min(slot_time(cluster_slot(0)), slot_time(cluster_slot(b)));
  if (piece_.end < horizon) horizon = piece_.end;
  double reach = cluster_size(b) >= 2 ? edge_reach(b, false, 0.0) : 0.0;
  reach = grounded_reach_top(reach);
  EdgeFunction fn;
  fn.c1 = gaps_.c[i];
  fn.p2 = gp2_;
  fn.c0 = gaps_.s[i] - gap_mb_[i] + gap_ma_[i];
  fn.noise = 8 * std::numeric_limits<double>::epsilon() * (std::abs(gaps_.s[i]) + std::abs(gap_mb_[i]) + std::abs(gap_ma_[i]));
  if (sine_) {
    // f(s) = c0 + c1 s - g s^2/2 - [Z(t+s) - Z(t) - Z'(t) s] + modes: Z(t) and Z'(t) into c0 and c1,
    // -Z(t+s) = -|W| sin(theta + arg W + omega s) a sinusoid term.
    const double th = plate_phase(t), amp = std::hypot(gW_re_, gW_im_);
    fn.c0 += gW_re_ * std::sin(th) + gW_im_ * std::cos(th);
    fn.c1 += ground_zdot(t);
    fn.sin_amp = -amp;
    fn.sin_phase = th + std::atan2(gW_im_, gW_re_);
    fn.sin_omega = plate_->omega();
    fn.noise += 8 * std::numeric_limits<double>::epsilon() * amp;
    reach += amp;
  }
  fn.reach = reach;
  fn.modes_nonnegative = false;
  const double clear = bound_clear(fn.c0, fn.c1, fn.p2, reach, false);
  if (bound_excludes(clear, horizon - t)) {
    clear_slot_before(gap_slot(i), horizon, i);
    return;
  }
  if (cluster_size(b) >= 2) fn.term[fn.terms++] = edge_term(b, false, +1.0, t);
  const ClusterModeTable& tab = tables_[2 * gn_];
  fn.term[fn.terms++] = EdgeTerm{&tab, gy0_.data(), gyd0_.data(), gamp0_.data(), tab.top.data(), -1.0, t - gt0_};
  const Root r = first_root(fn, horizon - t, clear);
  switch (r.kind) {
    case Root::Found: set_slot(gap_slot(i), t + r.sigma, SlotKind::ContactBegin, i); break;
    case Root::Refresh: set_slot(gap_slot(i), t + r.sigma, SlotKind::Refresh, i); break;
    case Root::None: set_slot(gap_slot(i), kInf, SlotKind::None, i); break;
  }
}

// ----------------------------------------------------------------------------------------------
// Events

void ExactEngine::plate_contact(Time t, EventSink& sink) {
  const int hi = hi_[0], n = hi + 1;
  if (hi + 1 < n_) sync_gap(hi, t);
  double* x = sx_.data();
  double* xd = sxd_.data();
  double* u = sv_.data();
  const double *y = nullptr, *yd = nullptr;
  if (n >= 2) cached_modes(0, t, y, yd);
  cluster_relative(0, y, yd, x, xd, u);
  const double V = com_velocity(0, t), v1 = V + u[0], vp = plate_v(t);
  double* xr = gxr_.data();
  double* xdr = gxdr_.data();
  xr[0] = 0.0;
  xdr[0] = 2.0 * (vp - v1);
  for (int q = 1; q < n; ++q) {
    xr[q] = x[q - 1];
    xdr[q] = xd[q - 1];
  }
  form_grounded(n, t, xr, xdr);
  if (hi + 1 < n_) gaps_.c[hi] += V - ground_zdot(t);  // the lower "centre of mass" is now the plate
  if (hi + 1 < n_) rebase_gap(hi, t);
  sink.on_event({EventKind::FloorContact, t.value(), 0, std::abs(vp - v1), t.low()});
  predict_grounded();
  if (hi + 1 < n_) predict_gap(hi);
  predict_floor();
}

void ExactEngine::plate_release(Time t, double tau, EventSink& sink, bool predict_floor_after) {
  const int n = gn_;
  double* xr = gxr_.data();
  double* xdr = gxdr_.data();
  double* v = gv_.data();
  grounded_state(tau, t, xr, xdr, v);
  if (n < n_) sync_gap(n - 1, t);
  double V = 0.0;
  for (int q = 0; q < n; ++q) V += v[q];
  V /= n;
  const double vp = plate_v(t), zp = plate_z(t);
  if (n < n_) gaps_.c[n - 1] += ground_zdot(t) - V;
  grounded_ = false;
  form_cluster(0, n - 1, t, xr + 1, xdr + 1, V);
  floor_s_ = zp - 0.5 * std::max(xr[0], 0.0);  // z_1 - d/2 = z_p - x_w
  rebase_floor(t);
  if (n < n_) rebase_gap(n - 1, t);
  ++counters_.floor_hits;
  sink.on_event({EventKind::FloorHit, t.value(), 0, std::abs(v[0] - vp), t.low()});
  predict_cluster(0);
  if (n < n_) predict_gap(n - 1);
  if (predict_floor_after) predict_floor();
}

void ExactEngine::grounded_split(int pair, Time t, double tau, EventSink& sink) {
  const int n = gn_, r = pair;
  double* xr = gxr_.data();
  double* xdr = gxdr_.data();
  double* v = gv_.data();
  grounded_state(tau, t, xr, xdr, v);
  if (n < n_) sync_gap(n - 1, t);
  double Vu = 0.0;
  for (int q = r + 1; q < n; ++q) Vu += v[q];
  Vu /= n - 1 - r;
  const double speed = std::abs(xdr[r + 1]);
  if (n < n_) gaps_.c[n - 1] += ground_zdot(t) - Vu;  // now above a free cluster
  form_grounded(r + 1, t, xr, xdr);
  form_cluster(r + 1, n - 1, t, xr + r + 2, xdr + r + 2, Vu);
  gaps_.s[r] = 0.0;
  gaps_.t[r] = t;
  gaps_.c[r] = Vu - ground_zdot(t);
  rebase_gap(r, t);
  if (n < n_) rebase_gap(n - 1, t);
  ++counters_.contact_ends;
  sink.on_event({EventKind::ContactEnd, t.value(), r, speed, t.low()});
  predict_grounded();
  predict_cluster(r + 1);
  predict_gap(r);
  if (n < n_) predict_gap(n - 1);
  predict_floor();
}

void ExactEngine::grounded_merge(int pair, Time t, EventSink& sink) {
  const int n = gn_, b = pair + 1, hb = hi_[b], nb = hb - b + 1;
  double* xr = gxr_.data();
  double* xdr = gxdr_.data();
  double* v = gv_.data();
  grounded_state(t - gt0_, t, xr, xdr, v);
  if (hb + 1 < n_) sync_gap(hb, t);
  double* x = sx_.data();
  double* xd = sxd_.data();
  double* u = sv_.data();
  const double *y = nullptr, *yd = nullptr;
  if (nb >= 2) cached_modes(b, t, y, yd);
  cluster_relative(b, y, yd, x, xd, u);
  const double Vb = com_velocity(b, t);
  const double rate = v[n - 1] - (Vb + u[0]);  // x' = v_lower - v_upper of the new pair
  const double scale = std::abs(v[n - 1]) + std::abs(Vb) + std::abs(u[0]);
  xr[n] = 0.0;
  xdr[n] = rate;
  for (int q = 0; q + 1 < nb; ++q) {
    xr[n + 1 + q] = x[q];
    xdr[n + 1 + q] = xd[q];
  }
  set_slot(cluster_slot(b), kInf, SlotKind::None, b);
  set_slot(gap_slot(pair), kInf, SlotKind::None, pair);
  form_grounded(n + nb, t, xr, xdr);
  if (hb + 1 < n_) gaps_.c[hb] += Vb - ground_zdot(t);  // now above the grounded cluster
  const double speed = std::abs(rate);
  if (speed <= 1e-13 * scale) {  // a grazing contact (merge): its end searched from 1e-6 tau_c on
    g_search_from_ = kResolutionSkip * tau_c_;
    ++counters_.grazing_contacts;
  }
  if (hb + 1 < n_) rebase_gap(hb, t);
  sink.on_event({EventKind::ContactBegin, t.value(), pair, speed, t.low()});
  predict_grounded();
  if (hb + 1 < n_) predict_gap(hb);
  predict_floor();
}

void ExactEngine::plate_switch(Time t, EventSink& sink) {
  if (!grounded_) {
    sync_floor(t);
    start_piece(t);
    predict_floor();
    return;
  }
  if (piece_.drop) {  // the surface drops away from particle 1: the contact ends here
    plate_release(t, t - gt0_, sink, false);
    start_piece(t);
    predict_floor();
    return;
  }
  const int n = gn_;
  double* xr = gxr_.data();
  double* xdr = gxdr_.data();
  grounded_state(t - gt0_, t, xr, xdr, nullptr);
  if (n < n_) sync_gap(n - 1, t);  // on the old piece
  start_piece(t);
  form_grounded(n, t, xr, xdr);  // the same overlaps about the new particular solution
  if (n < n_) rebase_gap(n - 1, t);
  predict_grounded();
  if (n < n_) predict_gap(n - 1);
  predict_floor();
}

void ExactEngine::grounded_refresh(Time t) {
  const int n = gn_;
  double* xr = gxr_.data();
  double* xdr = gxdr_.data();
  grounded_state(t - gt0_, t, xr, xdr, nullptr);
  if (n < n_) sync_gap(n - 1, t);
  form_grounded(n, t, xr, xdr);
  if (n < n_) rebase_gap(n - 1, t);
  predict_grounded();
  if (n < n_) predict_gap(n - 1);
  predict_floor();
}

}  // namespace granchain
