#include "engines/exact_engine.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace granchain {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Root-free steps allowed per prediction; past that the prediction becomes a "refresh" at the
// last proven-safe time, where the search starts again (no physics happens at a refresh).
constexpr int kMaxIterations = 400;
// Below this fraction of tau_c the engine does not resolve a function that touches zero within
// round-off (grazing contacts whose overlaps are far below the round-off of their neighbours').
constexpr double kResolutionSkip = 1e-6;
// Events allowed at one and the same instant before the engine declares itself stuck.
constexpr std::uint64_t kMaxSameTimeEvents = 1000000;

// First positive root of f + f1 h + a h^2 with a <= 0 and f >= 0 (+inf if there is none): the
// longest step over which a quadratic lower bound of the watched function stays positive.
double quadratic_step(double f, double f1, double a) {
  if (f < 0) f = 0;
  if (a >= 0) return f1 < 0 ? f / -f1 : kInf;
  const double disc = std::sqrt(f1 * f1 - 4.0 * a * f);  // >= |f1|
  return f1 >= 0 ? (f1 + disc) / (-2.0 * a) : 2.0 * f / (disc - f1);
}

constexpr int P = kTaylorOrder;

// 1/n! and the Bernstein weights C(k, i) / C(P, i), i <= k <= P.
struct TaylorTables {
  double inv_fact[P + 1];
  double bernstein[P + 1][P + 1];
  TaylorTables() {
    inv_fact[0] = 1.0;
    for (int n = 1; n <= P; ++n) inv_fact[n] = inv_fact[n - 1] / n;
    auto binom = [](int n, int k) {
      double c = 1.0;
      for (int i = 1; i <= k; ++i) c = c * (n - k + i) / i;
      return c;
    };
    for (int k = 0; k <= P; ++k) {
      for (int i = 0; i <= P; ++i) bernstein[k][i] = i <= k ? binom(k, i) / binom(P, i) : 0.0;
    }
  }
};
const TaylorTables kTaylor;

// The watched function f near the current search time s, for steps h >= 0:
//   f(s + h) >= f + f' h + (p2 - m2) h^2 / 2                                    (quadratic bound)
//   f(s + h) >= sum_{n < P} f^(n) h^n / n! - mP h^P / P!                        (order-P bound)
// with f^(n) the exact derivatives at s, p2 the exact second derivative of its polynomial part
// (the modes' third and higher derivatives are its only ones), and m2 >= |W''|, mP >= |W^(P)|
// bounds on its mode part W over all later times (ModeConstants::bound times the mode amplitudes).
struct Jet {
  double d[P];  // f, f', ..., f^(P-1) at s
  double p2 = 0, m2 = 0, mP = 0;
  // The order-P lower bound and its slope.
  double lower(double h) const {
    double v = -mP * kTaylor.inv_fact[P];
    for (int n = P - 1; n >= 0; --n) v = v * h + d[n] * kTaylor.inv_fact[n];
    return v;
  }
  double lower_slope(double h) const {
    double v = -mP * kTaylor.inv_fact[P - 1];
    for (int n = P - 1; n >= 1; --n) v = v * h + d[n] * kTaylor.inv_fact[n - 1];
    return v;
  }
  // Upper end of the interval that must hold f's first root when f > 0 up to the safe step h:
  // f(s + h) <= f + f' h + (p2 + m2) h^2 / 2, so f has a root by the first root of that parabola
  // (+inf if it has none).
  double root_upper() const {
    const double a = 0.5 * (p2 + m2), f0 = std::max(d[0], 0.0);
    if (!(d[1] < 0)) return kInf;
    const double disc = d[1] * d[1] - 4.0 * a * f0;
    return disc < 0 ? kInf : 2.0 * f0 / (std::sqrt(disc) - d[1]);
  }
  // Is the order-P bound positive on [0, H]? Sufficient test: every Bernstein coefficient of it
  // on [0, H] is positive (the polynomial is a convex combination of them there).
  bool lower_positive(double H) const {
    double a[P + 1];
    double Hn = 1.0;
    for (int n = 0; n < P; ++n, Hn *= H) a[n] = d[n] * kTaylor.inv_fact[n] * Hn;
    a[P] = -mP * kTaylor.inv_fact[P] * Hn;
    if (!(a[0] > 0)) return false;
    for (int k = 1; k <= P; ++k) {
      double b = 0.0;
      for (int i = 0; i <= k; ++i) b += kTaylor.bernstein[k][i] * a[i];
      if (!(b > 0)) return false;
    }
    return true;
  }
};

// A step h <= cap over which f is proven positive (f > 0 at the start). The quadratic bound
// gives a first safe step; Newton's method on the order-P bound then looks for that bound's
// first root, and the step is extended to just short of it when the Bernstein test proves the
// bound positive up there. Near a simple root of f the bound's root differs from f's by
// O(mP h^P / (P! |f'|)), so the search closes in on an event with few steps. Returns cap when
// the whole interval is safe.
double safe_step(const Jet& j, double cap) {
  const double h = quadratic_step(j.d[0], j.d[1], 0.5 * (j.p2 - j.m2));
  if (h >= cap) return cap;
  if (!(j.d[0] > 0)) return h;
  double r = h;
  for (int k = 0; k < 8; ++k) {
    const double p = j.lower(r), dp = j.lower_slope(r);
    double next = dp < 0 ? r - p / dp : 2.0 * r + h;
    if (!(next > 0)) break;
    if (next >= cap) {
      r = cap;
      break;
    }
    const bool converged = std::abs(next - r) <= 1e-8 * (next - h);
    r = next;
    if (converged) break;
  }
  if (!(r > h)) return h;
  // Just short of the bound's root, where it is still clearly positive.
  double H = r >= cap ? cap : h + (r - h) * (1.0 - 1e-6);
  for (int tries = 0; tries < 2; ++tries, H = h + 0.5 * (H - h)) {
    if (j.lower_positive(H)) return H;
  }
  return h;
}

// Is a watched function at (or, by round-off, just past) zero and moving down? The first
// non-zero derivative decides; a function whose value and first three derivatives all vanish is
// taken as at its root.
bool at_root(double f, double f1, double f2, double f3) {
  return f <= 0 && (f1 < 0 || (f1 == 0 && (f2 < 0 || (f2 == 0 && f3 <= 0))));
}

}  // namespace

ExactEngine::ExactEngine(const ChainParameters& p, const ChainState& initial, FloorDrive* floor)
    : n_(p.N),
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
  smode_.assign(2 * static_cast<std::size_t>(n_), 0.0);
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
      amp0_[lo + j] = std::sqrt((yd * yd + mc.omega0_sq * y * y) / mc.omega0_sq);
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
// Prediction

ExactEngine::Root ExactEngine::first_root(const EdgeFunction& fn, double sigma_max) const {
  if (fn.terms == 0) {  // free flight: a line or a parabola, solved in closed form
    // A gap that is zero with no relative velocity and no relative acceleration (two free spheres
    // touching at equal velocities, in free space) stays zero: no force acts, no contact begins.
    const double s = fn.c0 <= 0 && (fn.c1 < 0 || (fn.c1 == 0 && fn.p2 < 0))
                         ? 0.0
                         : quadratic_step(fn.c0, fn.c1, 0.5 * fn.p2);
    ++counters_.closed_form_predictions;
    return s <= sigma_max ? Root{Root::Found, s, 0} : Root{Root::None, s, 0};
  }
  // The mode part W(s) of f never exceeds reach = sum_j |a_j| sqrt(E_j) / omega0_j in size (each
  // mode's energy never grows), so f(s) >= c0 - reach + c1 s + p2 s^2 / 2: no root before that
  // parabola's first root. Better still, compression only pulls a cluster's edge particle towards
  // its centre of mass: when no pair is held, W is a non-negative combination of the cluster's
  // overlaps (predict_gap), and every overlap stays >= 0 until the cluster's own next event, which
  // bounds sigma_max; then W >= 0 up to a margin for overlaps of round-off size below zero
  // (resolution skips, grazing contacts searched from 1e-6 tau_c), far below 1e-10 of reach.
  // Either way no mode is evaluated, and most gaps next to a cluster end here.
  double reach = 0.0;
  for (int k = 0; k < fn.terms; ++k) {
    const EdgeTerm& term = fn.term[k];
    for (int j = 0; j < term.table->M; ++j) reach += std::abs(term.coef[j]) * term.amp0[j];
  }
  double sigma = 0.0;
  const double lower0 = fn.c0 - (fn.modes_nonnegative ? 1e-10 : 1.0) * reach;
  if (lower0 > 0) {
    const double clear = quadratic_step(lower0, fn.c1, 0.5 * fn.p2);
    if (clear >= sigma_max) {
      ++counters_.bound_exclusions;
      return {Root::None, sigma_max, 0};
    }
    sigma = clear;
  }
  ++counters_.edge_searches;
  for (int it = 0; it < kMaxIterations; ++it) {
    ++counters_.search_steps;
    Jet jet;
    jet.d[0] = fn.c0 + sigma * (fn.c1 + 0.5 * fn.p2 * sigma);
    jet.d[1] = fn.c1 + fn.p2 * sigma;
    jet.d[2] = fn.p2;
    for (int n = 3; n < P; ++n) jet.d[n] = 0.0;
    jet.p2 = fn.p2;
    for (int k = 0; k < fn.terms; ++k) {
      const EdgeTerm& term = fn.term[k];
      const double tau = term.tau0 + sigma;
      for (int j = 0; j < term.table->M; ++j) {
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
    if (at_root(jet.d[0], jet.d[1], jet.d[2], jet.d[3])) return {Root::Found, sigma, 0};
    const double cap = sigma_max - sigma;
    double h = safe_step(jet, cap);
    // At or below zero within round-off but not moving down (a function leaving zero, or touching
    // it from below): the bound measures from zero, so the proven steps would be ~ 2 f1 / m2, far
    // below the resolution when f1 is a grazing speed, and f would need ~ (skip / step)^2 of them
    // to rise clear. Step over a resolution interval instead; a root within it would be a contact
    // or gap shorter than kResolutionSkip tau_c, which the engine does not resolve.
    if (jet.d[0] <= 0 && h < kResolutionSkip * tau_c_) {
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

// First time an overlap of the cluster returns to zero (which = pair within the cluster) or, when
// watch_pass_through, first time an overlap reaches d (which = M + pair).
ExactEngine::Root ExactEngine::first_internal_root(int lo, bool watch_pass_through) const {
  const ClusterModeTable& tab = tables_[cluster_size(lo)];
  const int M = tab.M;
  // Modes and their rates (yn, yn + M), the amplitudes times bound[2] and bound[P], and the
  // overlaps and their rates (x = S y).
  double* yn = smode_.data();
  double* amp2 = samp_.data();
  double* ampP = samp_.data() + M;
  double* x = sx2_[0].data();
  double* xd = sx2_[1].data();
  double tau = search_from_[lo];
  for (int it = 0; it < kMaxIterations; ++it) {
    ++counters_.search_steps;
    double sum2 = 0.0;
    for (int j = 0; j < M; ++j) {
      const ModeConstants& mc = tab.modes[j];
      double y, yd;
      mc.evolve(y0_[lo + j], yd0_[lo + j], tau, y, yd);
      yn[j] = y;
      yn[M + j] = yd;
      const double amp = mc.amplitude(y, yd);
      amp2[j] = mc.bound[2] * amp;
      ampP[j] = mc.bound[P] * amp;
      sum2 += amp2[j];
    }
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
      double sum[P] = {};
      double b2 = 0.0, bP = 0.0;
      for (int j = 0; j < M; ++j) {
        // Derivatives 2 .. P-1 of mode j by its own equation, kept in registers.
        const ModeConstants& mc = tab.modes[j];
        double ym = yn[j], yc = yn[M + j];
        for (int n = 2; n < P; ++n) {
          const double next = mc.acceleration(ym, yc);
          sum[n] += row[j] * next;
          ym = yc;
          yc = next;
        }
        b2 += abs_row[j] * amp2[j];
        bP += abs_row[j] * ampP[j];
      }
      for (int n = 2; n < P; ++n) jk.d[n] = sign * sum[n];
      jk.m2 = b2;
      jk.mP = bP;
      return jk;
    };
    // Quadratic steps first (cheap, from x and x' with the common m2); the full bound can only
    // lengthen a step, so it is worked out only for functions whose quadratic step is shorter
    // than the best step so far.
    double* hq = shq_.data();
    double h = kInf;
    int which = -1;
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
    // as its step (as in first_root): its proven steps would be far below the resolution.
    const double skip = kResolutionSkip * tau_c_;
    auto step_of = [&](double f, double step) { return f <= 0 ? std::max(step, skip) : step; };
    // The quadratic bound of function k: concave, so positive over [0, H] when positive at H.
    auto value = [&](int k) { return k < M ? x[k] : d_ - x[k - M]; };
    auto rate = [&](int k) { return k < M ? xd[k] : -xd[k - M]; };
    auto quadratic_clear = [&](int k, double H) {
      const double f = value(k);
      return f > 0 && f + H * (rate(k) - 0.5 * m2 * H) > 0;
    };
    constexpr double kUnknown = -1.0;  // quadratic step not worked out: longer than some step
    for (int k = 0; k < functions; ++k) {
      if (held(k)) {
        hq[k] = kInf;
        continue;
      }
      const double f = value(k), f1 = rate(k);
      if (f <= 0) {
        const Jet jk = jet_of(k);
        if (at_root(jk.d[0], jk.d[1], jk.d[2], jk.d[3])) return {Root::Found, tau, k};
      }
      if (h < kInf && quadratic_clear(k, h)) {
        hq[k] = kUnknown;
        continue;
      }
      hq[k] = step_of(f, quadratic_step(f, f1, -0.5 * m2));
      if (hq[k] < h) {
        h = hq[k];
        which = k;
      }
    }
    Jet jw;
    if (which >= 0) {
      jw = jet_of(which);
      h = step_of(jw.d[0], safe_step(jw, kInf));
      for (int k = 0; k < functions; ++k) {
        if (k == which) continue;
        if (hq[k] == kUnknown) {
          if (quadratic_clear(k, h)) continue;
          hq[k] = step_of(value(k), quadratic_step(value(k), rate(k), -0.5 * m2));
        }
        if (!(hq[k] < h) || hq[k] == kInf) continue;
        const Jet jk = jet_of(k);
        if (jk.d[0] > 0 && jk.lower_positive(h)) continue;  // proven positive over the whole step
        const double hk = step_of(jk.d[0], safe_step(jk, h));
        if (hk < h) {
          h = hk;
          which = k;
          jw = jk;
        }
      }
    }
    if (hold_end < kInf && tau + h >= hold_end) {  // no root before the first hold ends: go there
      tau = hold_end;
      continue;
    }
    if (h == kInf) return {Root::None, kInf, 0};  // every mode at rest: the overlaps never change
    // At zero within round-off, not moving down, and its step raised to the resolution interval:
    // a resolution skip (no root can be bracketed from it: root_upper is infinite when f1 >= 0).
    if (h == skip && jw.d[0] <= 0) ++counters_.resolution_skips;
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
  const double phi = std::atan2(y0, (v0 + mc.beta * y0) / mc.w);  // in [0, pi]
  return (std::numbers::pi - phi) / mc.w;
}

void ExactEngine::predict_cluster(int lo) {
  const int n = cluster_size(lo);
  if (n == 1) {
    set_slot(cluster_slot(lo), kInf, SlotKind::None, lo);
    return;
  }
  const ClusterModeTable& tab = tables_[n];
  // Largest overlap any later time can reach: |x_i| <= sqrt(2/n) sum_j sqrt(E_j) / omega0_j.
  double reach = 0.0;
  for (int j = 0; j < tab.M; ++j) reach += amp0_[lo + j];
  const bool watch = tab.s_max * reach >= d_;
  const double t0 = t0_[lo];
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

// Held pairs (merge) may sit below zero while held, so their cluster's overlaps are not bounded.
bool ExactEngine::has_holds(int lo) const {
  for (int i = lo; i < hi_[lo]; ++i) {
    if (hold_until_[i] > t0_[lo]) return true;
  }
  return false;
}

void ExactEngine::predict_gap(int i) {
  const int a = lo_of_[i], b = i + 1;
  const double t = gap_t_[i];
  // Valid until either neighbour changes on its own (its internal event or refresh); any other
  // change of a neighbour re-predicts this gap.
  const double horizon = std::min(slots_[cluster_slot(a)].t, slots_[cluster_slot(b)].t);
  EdgeFunction fn;
  // f(s) = gap(t) + [u_b(t+s) - u_b(t)] - [u_a(t+s) - u_a(t)]; gravity cancels in the
  // centre-of-mass parts, which leaves a line plus the mode parts.
  const double ta = t - t0_[a], tb = t - t0_[b];
  fn.c1 = (V0_[b] - g_ * tb) - (V0_[a] - g_ * ta);
  fn.c0 = gap_s_[i] - (gap_ub_[i] - tb * (V0_[b] - 0.5 * g_ * tb)) + (gap_ua_[i] - ta * (V0_[a] - 0.5 * g_ * ta));
  if (cluster_size(b) >= 2) fn.term[fn.terms++] = edge_term(b, false, +1.0, t);
  if (cluster_size(a) >= 2) fn.term[fn.terms++] = edge_term(a, true, -1.0, t);
  // The top particle of a: z_top - z_com = const - sum_i x_i (i+1)/n; the bottom one of b:
  // z_bottom - z_com = const + sum_i x_i (n-1-i)/n. Both mode parts enter f with weights >= 0.
  fn.modes_nonnegative = !has_holds(a) && !has_holds(b);
  const Root r = first_root(fn, horizon - t);
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
  const double t = floor_t_;
  const double tau = t - t0_[0];
  EdgeFunction fn;
  // f(s) = h(t) + u_1(t+s) - u_1(t): a parabola under gravity plus the modes of the cluster.
  fn.c1 = V0_[0] - g_ * tau;
  fn.p2 = -g_;
  fn.c0 = floor_s_ - (floor_u_ - tau * (V0_[0] - 0.5 * g_ * tau));
  if (cluster_size(0) >= 2) fn.term[fn.terms++] = edge_term(0, false, +1.0, t);
  fn.modes_nonnegative = !has_holds(0);
  const Root r = first_root(fn, slots_[cluster_slot(0)].t - t);
  switch (r.kind) {
    case Root::Found: set_slot(floor_slot(), t + r.sigma, SlotKind::FloorHit, 0); break;
    case Root::Refresh: set_slot(floor_slot(), t + r.sigma, SlotKind::Refresh, 0); break;
    case Root::None: set_slot(floor_slot(), kInf, SlotKind::None, 0); break;
  }
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
