// The exact engine's event predictions: each event time is the first root of a watched function
// (an overlap, a gap, the floor height), found by root-free steps proven with the Taylor bounds of
// taylor_bounds.hpp, or in closed form where the motion allows it.
#include "engines/exact/exact_engine.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "engines/exact/step_choice.hpp"
#include "engines/exact/taylor_bounds.hpp"
#include "engines/free_flight.hpp"
#include "engines/plate_flight.hpp"

namespace granchain {

using taylor::Jet;
using taylor::StepChoice;
using taylor::shortest_safe_step;
using taylor::at_root;
using taylor::quadratic_step;
using taylor::safe_step;
using taylor::P;

// ----------------------------------------------------------------------------------------------
// Prediction

double ExactEngine::edge_reach(int lo, bool top, double acc) const {
  const ClusterModeTable& tab = tables_[cluster_size(lo)];
  const double* coef = top ? tab.top.data() : tab.bottom.data();
  for (int j = 0; j < tab.M; ++j) acc += std::abs(coef[j]) * amp0_[lo + j];
  return acc;
}

// The mode part W(s) of a gap or of the floor height never exceeds reach = sum_j |a_j| sqrt(E_j) /
// omega0_j in size (each mode's energy never grows), so f(s) >= c0 - reach + c1 s + p2 s^2 / 2: no
// root before that parabola's first root. Better still, compression only pulls a cluster's edge
// particle towards its centre of mass: when no pair is held, W is a non-negative combination of
// the cluster's overlaps (predict_gap), and every overlap stays >= 0 until the cluster's own next
// event, which bounds the search; then W >= 0 up to a margin for overlaps of round-off size below
// zero (resolution skips, grazing contacts searched from 1e-6 tau_c), far below 1e-10 of reach.
// Either way no mode is evaluated, and most gaps next to a cluster end here.
double ExactEngine::bound_clear(double c0, double c1, double p2, double reach, bool modes_nonnegative) const {
  const double lower0 = bound_at_zero(c0, reach, modes_nonnegative);
  return lower0 > 0 ? quadratic_step(lower0, c1, 0.5 * p2) : 0.0;
}

ExactEngine::Root ExactEngine::first_root(const EdgeFunction& fn, double sigma_max, double sigma0) const {
  if (fn.terms == 0 && fn.sin_amp == 0) {
    // (p2 > 0 only above a plate whose deceleration exceeds g: first_root_any takes either sign)
    const double s = plate_flight::first_root_any(fn.c0, fn.c1, fn.p2);
    ++counters_.closed_form_predictions;
    return s <= sigma_max ? Root{Root::Found, s, 0} : Root{Root::None, s, 0};
  }
  double sigma = sigma0;
  const double noise = fn.noise + 8 * std::numeric_limits<double>::epsilon() * fn.reach;
  ++counters_.edge_searches;
  for (int it = 0; it < kMaxIterations; ++it) {
    ++counters_.search_steps;
    Jet jet;
    jet.d[0] = fn.c0 + sigma * (fn.c1 + 0.5 * fn.p2 * sigma);
    jet.d[1] = fn.c1 + fn.p2 * sigma;
    jet.d[2] = fn.p2;
    for (int n = 3; n < P; ++n) jet.d[n] = 0.0;
    jet.p2 = fn.p2;
    if (fn.sin_amp != 0) {  // a sin(phase + w s): derivative q is a w^q sin(phase + w s + q pi / 2)
      const double ph = fn.sin_phase + fn.sin_omega * sigma, sn = std::sin(ph), cs = std::cos(ph);
      double wq = fn.sin_amp;
      for (int q = 0; q < P; ++q) {
        const double v = q % 4 == 0 ? sn : q % 4 == 1 ? cs : q % 4 == 2 ? -sn : -cs;
        jet.d[q] += wq * v;
        wq *= fn.sin_omega;
      }
      const double a = std::abs(fn.sin_amp);
      jet.m2 += a * fn.sin_omega * fn.sin_omega;
      jet.mP += a * std::pow(fn.sin_omega, P);
    }
    for (int k = 0; k < fn.terms; ++k) {
      const EdgeTerm& term = fn.term[k];
      const double tau = term.tau0 + sigma;
      for (int j = 0; j < term.table->M; ++j) {
        if (term.y0[j] == 0.0 && term.yd0[j] == 0.0) continue;  // at rest for ever: adds nothing
        const ModeConstants& mc = term.table->modes[j];
        double y, yd;
        mc.evolve(term.y0[j], term.yd0[j], tau, y, yd);
        const double a = term.sign * term.coef[j];
        // Derivatives 0 .. P-1 of a y_j by the mode's own equation.
        double ym = y, yn = yd;
        jet.d[0] += a * y;
        jet.d[1] += a * yd;
        for (int n = 2; n < P; ++n) {
          const double next = mc.acceleration(ym, yn);
          jet.d[n] += a * next;
          ym = yn;
          yn = next;
        }
        const double amp = std::abs(a) * mc.amplitude(y, yd);
        jet.m2 += mc.bound[2] * amp;
        jet.mP += mc.bound[P] * amp;
      }
    }
    // A search that has not closed in on a root after kStallSteps steps counts values within
    // round-off of zero as zero: a function hovering there (a gap closing at a grazing speed next
    // to an energetic cluster) would otherwise take proven steps far below the resolution, and a
    // search that cannot move the global time piles up refreshes at one instant.
    const double zero = it >= kStallSteps ? noise : 0.0;
    if (at_root(jet.d[0] - zero, jet.d[1], jet.d[2], jet.d[3])) return {Root::Found, sigma, 0};
    const double cap = sigma_max - sigma;
    double h = safe_step(jet, cap);
    // At or below zero within round-off but not moving down (a function leaving zero, or touching
    // it from below): the bound measures from zero, so the proven steps would be ~ 2 f1 / m2, far
    // below the resolution when f1 is a grazing speed, and f would need ~ (skip / step)^2 of them
    // to rise clear. Step over a resolution interval instead; a root within it would be a contact
    // or gap shorter than kResolutionSkip tau_c, which the engine does not resolve.
    if (jet.d[0] <= zero && h < kResolutionSkip * tau_c_) {
      h = std::min(cap, kResolutionSkip * tau_c_);
      ++counters_.resolution_skips;
    }
    if (h >= cap) return {Root::None, sigma_max, 0};
    // Converged: the root lies in (sigma + h, sigma + root_upper], an interval of round-off size.
    if (jet.root_upper() - h <= 1e-15 * (sigma + tau_c_)) return {Root::Found, sigma + h, 0};
    sigma += h;
  }
  return {Root::Refresh, sigma, 0};
}

void ExactEngine::mode_jets(const ClusterModeTable& tab, const double* y0, const double* yd0, double tau, double* yn, double* amp2,
                            double* ampP, double& sum2, double& sum_amp) {
  const int M = tab.M;
  for (int j = 0; j < M; ++j) {
    if (y0[j] == 0.0 && yd0[j] == 0.0) {  // a mode at rest stays exactly at rest (a grounded cluster's odd modes)
      for (int n = 0; n < P; ++n) yn[n * M + j] = 0.0;
      amp2[j] = ampP[j] = 0.0;
      continue;
    }
    const ModeConstants& mc = tab.modes[j];
    double y, yd;
    mc.evolve(y0[j], yd0[j], tau, y, yd);
    yn[j] = y;
    yn[M + j] = yd;
    // Derivatives 2 .. P-1 of mode j by its own equation (rows 2 .. P-1 of yn).
    double ym = y, yc = yd;
    for (int n = 2; n < P; ++n) {
      const double next = mc.acceleration(ym, yc);
      yn[n * M + j] = next;
      ym = yc;
      yc = next;
    }
    const double amp = mc.amplitude(y, yd);
    amp2[j] = mc.bound[2] * amp;
    ampP[j] = mc.bound[P] * amp;
    sum2 += amp2[j];
    sum_amp += amp;
  }
}

// First time an overlap of the cluster returns to zero (which = pair within the cluster) or, when
// watch_pass_through, first time an overlap reaches d (which = M + pair).
ExactEngine::Root ExactEngine::first_internal_root(int lo, bool watch_pass_through) const {
  const ClusterModeTable& tab = tables_[cluster_size(lo)];
  const int M = tab.M;
  // Modes and their derivatives 0 .. P-1 (row n of yn), the amplitudes times bound[2] and
  // bound[P], and the overlaps and their rates (x = S y).
  double* yn = smode_.data();
  double* amp2 = samp_.data();
  double* ampP = samp_.data() + M;
  double* x = sx2_[0].data();
  double* xd = sx2_[1].data();
  double tau = search_from_[lo];
  for (int it = 0; it < kMaxIterations; ++it) {
    ++counters_.search_steps;
    double sum2 = 0.0, sum_amp = 0.0;
    mode_jets(tab, &y0_[lo], &yd0_[lo], tau, yn, amp2, ampP, sum2, sum_amp);
    const double m2 = tab.s_max * sum2;  // >= |x_i''| for every i (|S_ij| <= sqrt(2/n))
    tab.to_overlaps(yn, x);
    tab.to_overlaps(yn + M, xd);
    // Function k < M is overlap k; k >= M (when watched) is d - overlap (k - M). Its full jet:
    // higher derivatives and remainder bounds from its own row of S.
    const int functions = watch_pass_through ? 2 * M : M;
    auto jet_of = [&](int k) {
      const int i = k < M ? k : k - M;
      const double sign = k < M ? 1.0 : -1.0;
      const double* row = &tab.S[static_cast<std::size_t>(i) * M];
      const double* abs_row = &tab.abs_S[static_cast<std::size_t>(i) * M];
      Jet jk;
      jk.d[0] = k < M ? x[i] : d_ - x[i];
      jk.d[1] = sign * xd[i];
      static_assert(P == 6, "the overlap jet below is written out for derivatives 2 .. 5");
      const double *y2 = yn + 2 * M, *y3 = yn + 3 * M, *y4 = yn + 4 * M, *y5 = yn + 5 * M;
      double s2 = 0.0, s3 = 0.0, s4 = 0.0, s5 = 0.0, b2 = 0.0, bP = 0.0;  // six independent sums
      for (int j = 0; j < M; ++j) {
        s2 += row[j] * y2[j];
        s3 += row[j] * y3[j];
        s4 += row[j] * y4[j];
        s5 += row[j] * y5[j];
        b2 += abs_row[j] * amp2[j];
        bP += abs_row[j] * ampP[j];
      }
      jk.d[2] = sign * s2;
      jk.d[3] = sign * s3;
      jk.d[4] = sign * s4;
      jk.d[5] = sign * s5;
      jk.m2 = b2;
      jk.mP = bP;
      return jk;
    };
    // Held pairs (see merge) take no part until their hold ends; the step stops there.
    double hold_end = kInf;
    auto held = [&](int k) {
      if (k >= M) return false;
      const double until = hold_until_[lo + k] - t0_[lo];  // in the cluster's local time
      if (!(until > tau)) return false;
      hold_end = std::min(hold_end, until);
      return true;
    };
    // A function at or below zero within round-off but not moving down takes a resolution interval
    // as its step (as in first_root): its proven steps would be far below the resolution. After
    // kStallSteps steps without closing in, "zero" includes the round-off of the overlaps (8 ulps
    // of the mode amplitudes that sum to them), as in first_root.
    const double skip = kResolutionSkip * tau_c_;
    const double zero =
        it >= kStallSteps ? 8 * std::numeric_limits<double>::epsilon() * (tab.s_max * sum_amp + d_) : 0.0;
    auto value = [&](int k) { return k < M ? x[k] : d_ - x[k - M]; };
    auto rate = [&](int k) { return k < M ? xd[k] : -xd[k - M]; };
    const StepChoice c = shortest_safe_step(functions, m2, zero, skip, shq_.data(), value, rate, jet_of, held);
    if (c.root_now) return {Root::Found, tau, c.which};
    const double h = c.h;
    const int which = c.which;
    const Jet& jw = c.jet;
    if (hold_end < kInf && tau + h >= hold_end) {  // no root before the first hold ends: go there
      tau = hold_end;
      continue;
    }
    if (h == kInf) return {Root::None, kInf, 0};  // every mode at rest: the overlaps never change
    // At zero within round-off, not moving down, and its step raised to the resolution interval:
    // a resolution skip (no root can be bracketed from it: root_upper is infinite when f1 >= 0).
    if (h == skip && jw.d[0] <= zero) ++counters_.resolution_skips;
    if (jw.root_upper() - h <= 1e-15 * (tau + tau_c_)) return {Root::Found, tau + h, which};
    tau += h;
  }
  return {Root::Refresh, tau, 0};
}

// Two particles: one underdamped mode (lambda = 2), x = y = e^{-beta t} R sin(w t + phi), so the
// contact ends at w t + phi = pi. From x = 0 this is t = pi / w = tau_c, Eq. (tauc).
double ExactEngine::pair_contact_end(int lo) const {
  const ModeConstants& mc = tables_[2].modes[0];
  const double y0 = std::max(y0_[lo], 0.0), v0 = yd0_[lo];
  if (y0 == 0 && v0 <= 0) return 0.0;
  if (y0 == 0) return pair_.tau;  // phi = 0: the whole contact, tau_c
  const double phi = std::atan2(y0, (v0 + mc.beta * y0) / mc.w);  // in [0, pi]
  return (std::numbers::pi - phi) / mc.w;
}

void ExactEngine::predict_cluster(int lo) {
  if (lo == 0 && grounded_) return predict_grounded();
  const int n = cluster_size(lo);
  if (n == 1) {
    set_slot(cluster_slot(lo), kInf, SlotKind::None, lo);
    return;
  }
  const ClusterModeTable& tab = tables_[n];
  const bool watch = overlap_reach(lo) >= d_;  // could an overlap reach d?
  const Time t0 = t0_[lo];
  if (n == 2 && !watch && tab.modes[0].kind == ModeKind::Under) {
    const double tau = pair_contact_end(lo);
    ++counters_.closed_form_predictions;
    set_slot(cluster_slot(lo), t0 + tau, SlotKind::ContactEnd, lo, tau);
    return;
  }
  const std::uint64_t steps_before = counters_.search_steps;
  const Root r = first_internal_root(lo, watch);
  ++counters_.cluster_searches;
  counters_.cluster_search_steps += counters_.search_steps - steps_before;
  switch (r.kind) {
    case Root::Found:
      if (r.which >= tab.M) {
        set_slot(cluster_slot(lo), t0 + r.sigma, SlotKind::PassThrough, lo + r.which - tab.M);
      } else {
        set_slot(cluster_slot(lo), t0 + r.sigma, SlotKind::ContactEnd, lo + r.which, r.sigma);
      }
      break;
    case Root::Refresh: set_slot(cluster_slot(lo), t0 + r.sigma, SlotKind::Refresh, lo); break;
    case Root::None: set_slot(cluster_slot(lo), kInf, SlotKind::None, lo); break;
  }
}

double ExactEngine::overlap_reach(int lo) const {
  const int n = cluster_size(lo);
  if (n < 2) return 0.0;
  double reach = 0.0;
  for (int j = 0; j < n - 1; ++j) reach += amp0_[lo + j];
  return tables_[n].s_max * reach;
}

// Held pairs (merge) may sit below zero while held, so their cluster's overlaps are not bounded.
bool ExactEngine::has_holds(int lo) const {
  for (int i = lo; i < hi_[lo]; ++i) {
    if (hold_until_[i] > t0_[lo]) return true;
  }
  return false;
}

void ExactEngine::predict_gap(int i) {
  if (i == ground_gap()) return predict_ground_gap(i);
  const int a = lo_of_[i], b = i + 1;
  const Time t = gaps_.t[i];
  if (a == i && hi_[b] == b) {  // two free particles: a line, no edge function to build
    const double horizon = std::min(slot_time(cluster_slot(a)), slot_time(cluster_slot(b))) - t;
    const double s = gaps_.closing(i);
    ++counters_.closed_form_predictions;
    if (s <= horizon) set_slot(gap_slot(i), t + s, SlotKind::ContactBegin, i);
    else set_slot(gap_slot(i), kInf, SlotKind::None, i);
    return;
  }
  // Valid until either neighbour changes on its own (its internal event or refresh); any other
  // change of a neighbour re-predicts this gap.
  const Time horizon = std::min(slot_time(cluster_slot(a)), slot_time(cluster_slot(b)));
  // The lower bound of first_root first, without building the edge function: most gaps next to a
  // cluster end here. Reach summed in first_root's order (b's bottom, then a's top).
  const bool modes_nonnegative = !has_holds(a) && !has_holds(b);
  double reach = cluster_size(b) >= 2 ? edge_reach(b, false, 0.0) : 0.0;
  if (cluster_size(a) >= 2) reach = edge_reach(a, true, reach);
  const double clear = bound_clear(gaps_.s[i] - gap_mb_[i] + gap_ma_[i], gaps_.c[i], 0.0, reach, modes_nonnegative);
  if (bound_excludes(clear, horizon - t)) {
    clear_slot_before(gap_slot(i), horizon, i);
    return;
  }
  EdgeFunction fn;
  fn.reach = reach;
  // f(s) = gap(t) + c s + [m_b(t+s) - m_b(t)] - [m_a(t+s) - m_a(t)] (gap_at): a line, since
  // gravity cancels between the centres of mass, plus the mode parts.
  fn.c1 = gaps_.c[i];
  fn.c0 = gaps_.s[i] - gap_mb_[i] + gap_ma_[i];
  fn.noise = 8 * std::numeric_limits<double>::epsilon() * (std::abs(gaps_.s[i]) + std::abs(gap_mb_[i]) + std::abs(gap_ma_[i]));
  if (cluster_size(b) >= 2) fn.term[fn.terms++] = edge_term(b, false, +1.0, t);
  if (cluster_size(a) >= 2) fn.term[fn.terms++] = edge_term(a, true, -1.0, t);
  // The top particle of a: z_top - z_com = const - sum_i x_i (i+1)/n; the bottom one of b:
  // z_bottom - z_com = const + sum_i x_i (n-1-i)/n. Both mode parts enter f with weights >= 0.
  fn.modes_nonnegative = modes_nonnegative;
  const Root r = first_root(fn, horizon - t, clear);
  switch (r.kind) {
    case Root::Found: set_slot(gap_slot(i), t + r.sigma, SlotKind::ContactBegin, i); break;
    case Root::Refresh: set_slot(gap_slot(i), t + r.sigma, SlotKind::Refresh, i); break;
    case Root::None: set_slot(gap_slot(i), kInf, SlotKind::None, i); break;
  }
}

void ExactEngine::predict_floor() {
  if (floor_ == nullptr) {
    set_slot(floor_slot(), kInf, SlotKind::None, 0);
    return;
  }
  // A grounded cluster: the floor's only event is the end of the plate's piece.
  if (grounded_) {
    set_slot(floor_slot(), piece_.end, SlotKind::PlateSwitch, 0);
    return;
  }
  const Time t = floor_t_;
  const double tau = t - t0_[0];
  EdgeFunction fn;
  // f(s) = h(t) + u_1(t+s) - u_1(t): a parabola under gravity plus the modes of the cluster; above
  // a plate, minus the surface's polynomial on its piece, up to the piece's end.
  fn.c1 = V0_[0] - g_ * tau;
  fn.p2 = -g_;
  fn.c0 = floor_s_ - (floor_u_ - tau * (V0_[0] - 0.5 * g_ * tau));
  fn.noise = 8 * std::numeric_limits<double>::epsilon() *
             (std::abs(floor_s_) + std::abs(floor_u_) + std::abs(tau * (V0_[0] - 0.5 * g_ * tau)));
  Time horizon = slot_time(cluster_slot(0));
  bool switch_first = false;  // the piece ends before cluster 0's own next event
  if (sine_) {  // minus A sin(theta(t) + omega s): a sinusoid term (bound by its amplitude)
    fn.sin_amp = -plate_->amplitude();
    fn.sin_phase = plate_phase(t);
    fn.sin_omega = plate_->omega();
  } else if (plate_ != nullptr) {
    const double zp = plate_z(t);
    fn.c0 -= zp;
    fn.c1 -= plate_v(t);
    fn.p2 -= piece_.a;
    fn.noise += 8 * std::numeric_limits<double>::epsilon() * std::abs(zp);
    if (piece_.end <= horizon) {
      horizon = piece_.end;
      switch_first = true;
    }
  }
  const auto no_event = [&] {
    if (switch_first) set_slot(floor_slot(), piece_.end, SlotKind::PlateSwitch, 0);
    else clear_slot_before(floor_slot(), horizon, 0);
  };
  fn.modes_nonnegative = !has_holds(0) && !sine_;
  const double sigma_max = horizon - t;
  double clear = 0.0;
  fn.reach = std::abs(fn.sin_amp);
  if (sine_) clear = bound_clear(fn.c0, fn.c1, fn.p2, fn.reach, false);
  if (cluster_size(0) >= 2) {
    fn.reach = edge_reach(0, false, fn.reach);
    clear = bound_clear(fn.c0, fn.c1, fn.p2, fn.reach, fn.modes_nonnegative);
    if (bound_excludes(clear, sigma_max)) {
      no_event();
      return;
    }
    fn.term[fn.terms++] = edge_term(0, false, +1.0, t);
  }
  const Root r = first_root(fn, sigma_max, clear);
  switch (r.kind) {
    case Root::Found: set_slot(floor_slot(), t + r.sigma, SlotKind::FloorHit, 0); break;
    case Root::Refresh: set_slot(floor_slot(), t + r.sigma, SlotKind::Refresh, 0); break;
    case Root::None:
      if (switch_first) set_slot(floor_slot(), piece_.end, SlotKind::PlateSwitch, 0);
      else set_slot(floor_slot(), kInf, SlotKind::None, 0);
      break;
  }
}

}  // namespace granchain
