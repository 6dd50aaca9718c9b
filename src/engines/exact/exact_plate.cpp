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
#include "engines/plate_flight.hpp"

namespace granchain {

void ExactEngine::start_piece(Time t) {
  const plate_flight::PieceState p = plate_flight::piece_state(*plate_, t.value());
  piece_.t0 = t;
  piece_.z = p.z;
  piece_.v = p.v;
  piece_.a = p.a;
  piece_.end = Time(plate_->next_switch(t.value()));
  if (sine_) piece_.a = 0.0;  // one piece for ever; the sinusoid's own functions (plate_z, ground_zdev) serve
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
    for (int i = 0; i < M; ++i) gP_abs_[i] = std::hypot(gP_re_[i], gP_im_[i]);
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
  if (plate_->kind() == DriveKind::Sawtooth) {  // the surface drops away from particle 1: the contact ends here
    plate_release(t, t - gt0_, sink, false);
    start_piece(t);
    predict_floor();
    return;
  }
  reform_grounded(t, true);
}

void ExactEngine::reform_grounded(Time t, bool new_piece) {
  const int n = gn_;
  double* xr = gxr_.data();
  double* xdr = gxdr_.data();
  grounded_state(t - gt0_, t, xr, xdr, nullptr);
  if (n < n_) sync_gap(n - 1, t);  // on the old piece
  if (new_piece) start_piece(t);
  form_grounded(n, t, xr, xdr);  // the same overlaps about the (new) particular solution
  if (n < n_) rebase_gap(n - 1, t);
  predict_grounded();
  if (n < n_) predict_gap(n - 1);
  predict_floor();
}

}  // namespace granchain
