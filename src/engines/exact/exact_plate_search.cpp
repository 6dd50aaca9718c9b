// The exact engine's searches above a vibrating plate (exact_plate.cpp): the grounded cluster's
// contact ends, over its mirror modes plus the particular solution (for the sine a sinusoid in
// every overlap, whose derivatives are bounded by |P_i| omega^n), and the gap above it.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "engines/exact/exact_engine.hpp"
#include "engines/exact/step_choice.hpp"
#include "engines/exact/taylor_bounds.hpp"

namespace granchain {

using taylor::Jet;
using taylor::StepChoice;
using taylor::shortest_safe_step;
using taylor::P;

// As first_internal_root, over the mirror modes with the particular solution added, watching the
// real overlaps only: function k < n is real overlap k (0: the plate's X, r + 1: pair r), k >= n
// (when watched) its distance to passing through (2d - X for the plate, d - x for a pair).
ExactEngine::Root ExactEngine::first_grounded_root(bool watch_pass_through) const {
  const int n = gn_;
  const ClusterModeTable& tab = tables_[2 * n];
  const int M = tab.M;
  double* yn = smode_.data();  // the same scratch as first_internal_root, sized for 2N - 1 modes above a plate
  double* amp2 = samp_.data();
  double* ampP = samp_.data() + M;
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
    // (the antisymmetric modes are zero at formation and stay exactly zero)
    mode_jets(tab, gy0_.data(), gyd0_.data(), tau, yn, amp2, ampP, sum2, sum_amp);
    double m2 = tab.s_max * sum2;
    tab.to_overlaps(yn, x);
    tab.to_overlaps(yn + M, xd);
    // The sine's particular solution of overlap i: Im(P_i e^{i theta}), derivative q Im(P_i (i w)^q e^{i theta}).
    const double w = sine_ ? plate_->omega() : 0.0;
    const double th = sine_ ? plate_phase(gt0_) + w * tau : 0.0, sn = std::sin(th), cs = std::cos(th);
    double wpow[P + 1];
    wpow[0] = 1.0;
    for (int q = 1; q <= P; ++q) wpow[q] = wpow[q - 1] * w;
    const auto particular = [&](int i, int q) {  // q-th derivative
      if (!sine_) return 0.0;
      const double re = gP_re_[i] * cs - gP_im_[i] * sn, im = gP_re_[i] * sn + gP_im_[i] * cs;  // P e^{i theta}
      const double wq = wpow[q];
      switch (q % 4) {  // Im(i^q P e^{i theta})
        case 0: return wq * im;
        case 1: return wq * re;
        case 2: return -wq * im;
        default: return -wq * re;
      }
    };
    const auto particular_amp = [&](int i) { return sine_ ? gP_abs_[i] : 0.0; };
    if (sine_) {
      double pmax = 0.0;
      for (int q = 0; q < n; ++q) pmax = std::max(pmax, particular_amp(n - 1 + q));
      m2 += pmax * w * w;
    }
    // Each watched function's value and rate, worked out once per step.
    double* fv = gf_.data();
    double* fr = gfd_.data();
    for (int k = 0; k < functions; ++k) {
      const int i = virtual_index(k);
      const double xi = x[i] + grounded_offset(i) + particular(i, 0), ri = xd[i] + particular(i, 1);
      if (k < n) {
        fv[k] = xi;
        fr[k] = ri;
      } else {
        fv[k] = (k == n ? 2.0 * d_ : d_) - xi;  // 2d - X for the plate, d - x for a pair
        fr[k] = -ri;
      }
    }
    const auto value = [fv](int k) { return fv[k]; };
    const auto rate = [fr](int k) { return fr[k]; };
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
      for (int j = 0; j < M; j += 2) {  // (the odd modes are exactly zero: adding them changes no bit)
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
      jk.mP = bP + pa * wpow[P];
      return jk;
    };
    const double skip = kResolutionSkip * tau_c_;
    const double zero =
        it >= kStallSteps ? 8 * std::numeric_limits<double>::epsilon() * (tab.s_max * sum_amp + offset_max + 2 * d_) : 0.0;
    const auto free = [](int) { return false; };  // (no holds above a plate)
    const StepChoice c = shortest_safe_step(functions, m2, zero, skip, shq_.data(), value, rate, jet_of, free);
    if (c.root_now) return {Root::Found, tau, c.which};
    const double h = c.h;
    const int which = c.which;
    const Jet& jw = c.jet;
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
  for (int j = 0; j < 2 * n - 1; ++j) reach += gamp0_[j];  // (entries beyond belong to an earlier, larger cluster)
  for (int q = 0; q < n; ++q) {
    const double p = sine_ ? gP_abs_[n - 1 + q] : 0.0;
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
  fn.p2 = -(g_ + piece_.a);  // the plate's piece; the sine's curvature is in its sinusoid term
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

}  // namespace granchain
