// The exact engine's contact-end predictions against an independent oracle, on cluster states taken
// from real runs. After every event the engine is stopped and every cluster it has just formed is
// read through its public interface (overlaps at full precision, velocities); the oracle evolves
// that cluster on its own — sine modes and damped oscillators written out here in long double, no
// engine code — and samples every overlap on a grid of tau_c / 64. When the cluster next changes:
//   - by one of its own contacts ending (pair p at t_e): the oracle's overlap p must be zero at t_e
//     within its conditioning (|x_p'| times the rounding of t_e, plus round-off of the amplitudes),
//     and no overlap may be below zero beyond that tolerance at any grid point before t_e;
//   - by anything else (a contact beginning at its edge, a floor hit) at t_e: no overlap may be
//     below zero beyond tolerance at any grid point before t_e (no contact end was missed).
// The same for every open gap and the floor height: after each event the oracle takes each gap
// whose neighbouring clusters have just changed (gap, the relative velocity of the two centres of
// mass, the clusters' own oracles for their edges; gravity cancels) and the height of particle 1
// (a parabola plus the bottom edge of its cluster), and when either neighbour next changes at t_e:
//   - by that gap closing (a contact begins) or particle 1 reaching the floor: the oracle's gap or
//     height must be zero at t_e within its conditioning;
//   - by anything else: it must not be below zero beyond tolerance at `gap_samples` instants
//     evenly spaced before t_e (16 in the quick test, 256 in the long one).
// Contacts that begin without a resolvable approach speed (grazing, held contacts: see
// ExactEngine::merge) are outside what the engine resolves; clusters formed at such an event are
// not checked, and counted.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>
#include <vector>

#include "engines/exact/exact_engine.hpp"
#include "model/chain_parameters.hpp"
#include "model/driven_column.hpp"
#include "model/floor.hpp"

using namespace granchain;

namespace {

using real = long double;

// Overlaps x (M = n - 1 values) and their rates of an n-particle cluster, closed form.
class OracleCluster {
 public:
  OracleCluster(const std::vector<double>& x, const std::vector<double>& xd, double k_over_m, double D)
      : M_(static_cast<int>(x.size())), n_(M_ + 1), S_(static_cast<std::size_t>(M_) * M_) {
    const real pi = std::numbers::pi_v<real>;
    for (int i = 0; i < M_; ++i)
      for (int j = 0; j < M_; ++j) S_[i * M_ + j] = std::sqrt(2.0L / n_) * std::sin(pi * (i + 1) * (j + 1) / n_);
    for (int j = 0; j < M_; ++j) {
      const real s = std::sin(pi * (j + 1) / (2.0L * n_));
      const real lambda = 4 * s * s;
      Mode m;
      m.beta = 0.5L * D * lambda;
      m.w0sq = k_over_m * lambda;
      m.w = std::sqrt(std::abs(m.w0sq - m.beta * m.beta));
      m.under = m.w0sq > m.beta * m.beta;
      for (int i = 0; i < M_; ++i) {
        m.y0 += S_[i * M_ + j] * x[i];
        m.v0 += S_[i * M_ + j] * xd[i];
      }
      amplitude_ += std::abs(m.y0) + std::abs(m.v0) / std::sqrt(m.w0sq);
      modes_.push_back(m);
    }
  }
  int pairs() const { return M_; }
  // Displacement of the bottom (top = false) or top particle from the centre of mass, up to a
  // constant: z_1 - z_com = const + sum_i x_i (n-1-i)/n, z_n - z_com = const - sum_i x_i (i+1)/n.
  real edge(real tau, bool top) const {
    std::vector<real> x, xd;
    at(tau, x, xd);
    real u = 0;
    for (int i = 0; i < M_; ++i) u += top ? -x[i] * (i + 1) / n_ : x[i] * (n_ - 1 - i) / n_;
    return u;
  }
  // Bound on every overlap's size (sum of mode amplitudes): the scale of its round-off.
  real amplitude() const { return amplitude_; }
  void at(real tau, std::vector<real>& x, std::vector<real>& xd) const {
    std::vector<real> y(M_), yd(M_);
    for (int j = 0; j < M_; ++j) {
      const Mode& m = modes_[j];
      real c, s;  // e^{-beta t} C(t), e^{-beta t} S(t) with C(0) = 1, S'(0) = 1
      if (m.under) {
        c = std::exp(-m.beta * tau) * std::cos(m.w * tau);
        s = std::exp(-m.beta * tau) * std::sin(m.w * tau) / m.w;
      } else {
        c = std::exp(-m.beta * tau) * std::cosh(m.w * tau);
        s = std::exp(-m.beta * tau) * (m.w > 0 ? std::sinh(m.w * tau) / m.w : tau);
      }
      y[j] = m.y0 * c + (m.v0 + m.beta * m.y0) * s;
      yd[j] = m.v0 * c - (m.beta * m.v0 + m.w0sq * m.y0) * s;
    }
    x.assign(M_, 0);
    xd.assign(M_, 0);
    for (int i = 0; i < M_; ++i)
      for (int j = 0; j < M_; ++j) {
        x[i] += S_[i * M_ + j] * y[j];
        xd[i] += S_[i * M_ + j] * yd[j];
      }
  }

 private:
  struct Mode {
    real beta = 0, w0sq = 0, w = 0, y0 = 0, v0 = 0;
    bool under = true;
  };
  int M_, n_;
  std::vector<real> S_;
  std::vector<Mode> modes_;
  real amplitude_ = 0;
};

// Stops the engine after every event and remembers it.
class StopAtEveryEvent final : public EventSink {
 public:
  void on_event(const Event& e) override {
    last = e;
    request_stop();
  }
  Event last{};
};

struct OracleTally {
  std::uint64_t checked = 0, ends = 0, other_changes = 0, skipped_grazing = 0, grid_points = 0;
  std::uint64_t gaps_checked = 0, closings = 0, floor_hits = 0;
  int failures = 0;
  double worst_time_error = 0;  // |t_e - root|/tolerance, over contact ends (root from the x_p value)
};

struct Pending {
  int lo, hi;
  double t0;
  OracleCluster cluster;
};

// An open gap (pair i, between clusters la..i and i+1..hb) or the floor height (i = -1, cluster
// 0..hb): value and centre-of-mass relative velocity at t0, with the neighbours' edge oracles
// (absent for a single particle).
struct PendingGap {
  int i, la, hb;
  double t0;
  real g0, dV, g;  // g: gravity in the floor height, 0 in a gap
  std::vector<OracleCluster> below, above;  // zero or one each
  real scale;                               // size of the neighbours' mode parts and speeds
  real above0 = 0, below0 = 0;              // the edges at t0 (set by start_edges)
  void start_edges() {
    if (!above.empty()) above0 = above[0].edge(0, false);
    if (!below.empty()) below0 = below[0].edge(0, true);
  }
  real value(real tau) const {
    real v = g0 + dV * tau - 0.5L * g * tau * tau;
    if (!above.empty()) v += above[0].edge(tau, false) - above0;
    if (!below.empty()) v -= below[0].edge(tau, true) - below0;
    return v;
  }
};

// Runs the driven column until `events` events and checks every cluster prediction.
OracleTally check_against_oracle(const ChainParameters& p, std::uint64_t seed, std::uint64_t events, int gap_samples) {
  ThermalFloor floor(p.kT0, p.m, seed);
  ExactEngine engine(p, driven_column_initial_state(p, seed), &floor);
  const ContactLaw law = contact_law(p);
  const double h = law.tau_c / 64;
  const real eps = std::numeric_limits<double>::epsilon();
  StopAtEveryEvent sink;
  std::map<int, Pending> pending;  // by lo
  OracleTally tally;
  std::uint64_t grazing_before = 0;

  std::map<int, PendingGap> gaps;  // by i (-1: the floor)
  // Checks gap c against an engine event at t_e (`closes`: the gap's own closing or floor hit).
  auto check_gap = [&](const PendingGap& c, double t_e, bool closes) {
    const real tau_e = static_cast<real>(t_e) - static_cast<real>(c.t0);
    const real t_tol = 2 * eps * std::abs(static_cast<real>(t_e));
    // The rate is at most scale (speeds), the value's round-off 64 ulps of the terms it sums and
    // of the speeds times the elapsed time (absolute velocities enter dV).
    const real tol = c.scale * t_tol + 64 * eps * (c.scale * (1 + tau_e) + std::abs(c.g0) + p.d);
    bool ok = true;
    if (closes) {
      const real v = c.value(tau_e);
      if (std::abs(v) > tol) {
        ok = false;
        std::printf("%s %d at t = %.17g: oracle value %.3Lg (tolerance %.3Lg)\n", c.i < 0 ? "floor hit" : "gap closing",
                    c.i, t_e, v, tol);
      }
      ++(c.i < 0 ? tally.floor_hits : tally.closings);
    }
    for (int q = 1; q < gap_samples && ok; ++q) {
      const real tau = tau_e * q / gap_samples;
      if (tau >= tau_e - t_tol) break;
      ++tally.grid_points;
      const real v = c.value(tau);
      if (v < -tol) {
        ok = false;
        std::printf("%s %d below zero (%.3Lg) at t = %.17Lg, before the engine's event at %.17g\n",
                    c.i < 0 ? "floor height" : "gap", c.i, v, static_cast<real>(c.t0) + tau, t_e);
      }
    }
    ++tally.gaps_checked;
    if (!ok) ++tally.failures;
  };

  // Checks cluster c against an engine event at t_e (own contact end of pair `end`, or -1).
  auto check = [&](const Pending& c, double t_e, int end) {
    const real tau_e = static_cast<real>(t_e) - static_cast<real>(c.t0);
    const real scale = c.cluster.amplitude();
    std::vector<real> x, xd;
    c.cluster.at(tau_e, x, xd);
    // Tolerances: t_e carries the rounding of one ulp of t (2 with the subtraction), the overlaps
    // the round-off of their mode sums, and the engine's "zero" after its stall rule (8 ulps).
    const real t_tol = 2 * eps * std::abs(static_cast<real>(t_e));
    real rate_max = 0;
    for (real r : xd) rate_max = std::max(rate_max, std::abs(r));
    const real x_tol = rate_max * t_tol + 64 * eps * (scale + p.d);
    bool ok = true;
    if (end >= 0) {
      const int i = end - c.lo;
      const real err = std::abs(x[i]);
      tally.worst_time_error = std::max(tally.worst_time_error, static_cast<double>(err / x_tol));
      if (err > x_tol) {
        ok = false;
        std::printf("contact end of pair %d at t = %.17g: oracle overlap %.3Lg (tolerance %.3Lg, rate %.3Lg) in cluster %d..%d formed at %.17g\n",
                    end, t_e, x[i], x_tol, xd[i], c.lo, c.hi, c.t0);
      }
      ++tally.ends;
    } else {
      ++tally.other_changes;
    }
    // No overlap below zero before t_e - t_tol: sample the grid.
    for (real tau = h; tau < tau_e - t_tol; tau += h) {
      c.cluster.at(tau, x, xd);
      ++tally.grid_points;
      for (int i = 0; i < c.cluster.pairs(); ++i) {
        if (x[i] < -(std::abs(xd[i]) * t_tol + 64 * eps * (scale + p.d))) {
          ok = false;
          std::printf("pair %d of cluster %d..%d below zero (%.3Lg) at t = %.17Lg, before the engine's event at %.17g\n",
                      c.lo + i, c.lo, c.hi, x[i], static_cast<real>(c.t0) + tau, t_e);
          break;
        }
      }
      if (!ok) break;
    }
    ++tally.checked;
    if (!ok) ++tally.failures;
  };

  for (std::uint64_t ev = 0; ev < events && tally.failures < 5; ++ev) {
    sink.clear_stop();
    engine.advance_to(std::numeric_limits<double>::max(), sink);
    const Event e = sink.last;
    const double t = engine.time();
    // The event changed the clusters holding particle a or b (pair a, a+1; the floor: particle 0).
    const int a = e.i, b = e.kind == EventKind::FloorHit ? 0 : e.i + 1;
    auto holds = [&](int lo, int hi) { return (lo <= a && a <= hi) || (lo <= b && b <= hi); };
    for (auto it = pending.begin(); it != pending.end();) {
      const Pending& c = it->second;
      if (!holds(c.lo, c.hi)) {
        ++it;
        continue;
      }
      const bool own_end = e.kind == EventKind::ContactEnd && e.i >= c.lo && e.i < c.hi;
      check(c, t, own_end ? e.i : -1);
      it = pending.erase(it);
    }
    for (auto it = gaps.begin(); it != gaps.end();) {
      const PendingGap& c = it->second;
      if (!holds(c.la, c.hb)) {
        ++it;
        continue;
      }
      const bool closes = c.i < 0 ? e.kind == EventKind::FloorHit : (e.kind == EventKind::ContactBegin && e.i == c.i);
      check_gap(c, t, closes);
      it = gaps.erase(it);
    }
    // The clusters now: pairs with a positive overlap, and the pair whose contact has just begun
    // (its overlap is zero, or round-off either side of it after the projection onto modes and
    // back). A grazing or held contact (overlap at zero, or below it by round-off while
    // held) makes the state ambiguous to the oracle: the cluster is not checked.
    const std::vector<double> x = engine.overlaps();
    const ChainState& s = engine.state();
    const bool grazing = engine.below_resolution().grazing_contacts != grazing_before;
    grazing_before = engine.below_resolution().grazing_contacts;
    std::vector<int> lo_of(p.N), hi_of(p.N);  // each particle's cluster, bottom and top
    for (int lo = 0; lo < p.N;) {
      int hi = lo;
      while (hi + 1 < p.N && (x[hi] > 0 || (e.kind == EventKind::ContactBegin && hi == e.i))) ++hi;
      for (int q = lo; q <= hi; ++q) {
        lo_of[q] = lo;
        hi_of[q] = hi;
      }
      if (hi > lo && holds(lo, hi) && pending.count(lo) == 0) {
        if (grazing) {
          ++tally.skipped_grazing;
        } else {
          std::vector<double> cx(x.begin() + lo, x.begin() + hi), cxd(hi - lo);
          for (int i = lo; i < hi; ++i) cxd[i - lo] = s.v[i] - s.v[i + 1];
          pending.emplace(lo, Pending{lo, hi, t, OracleCluster(cx, cxd, law.k_over_m, law.D)});
        }
      }
      lo = hi + 1;
    }
    // Open gaps and the floor height whose neighbours just changed (not pending any more).
    auto oracle_of = [&](int lo, int hi, std::vector<OracleCluster>& out) {
      if (hi == lo) return;
      std::vector<double> cx(x.begin() + lo, x.begin() + hi), cxd(hi - lo);
      for (int q = lo; q < hi; ++q) cxd[q - lo] = s.v[q] - s.v[q + 1];
      out.emplace_back(cx, cxd, law.k_over_m, law.D);
    };
    auto com_velocity = [&](int lo, int hi) {
      real sum = 0;
      for (int q = lo; q <= hi; ++q) sum += s.v[q];
      return sum / (hi - lo + 1);
    };
    auto speed_scale = [&](int lo, int hi) {
      real m = 0;
      for (int q = lo; q <= hi; ++q) m = std::max(m, static_cast<real>(std::abs(s.v[q])));
      return m;
    };
    if (!grazing) {
      for (int i = -1; i + 1 < p.N; ++i) {
        if (gaps.count(i) > 0) continue;
        if (i >= 0 && hi_of[i] != i) continue;  // a closed pair
        const int la = i < 0 ? 0 : lo_of[i], hb = i < 0 ? hi_of[0] : hi_of[i + 1];
        if (!holds(la, hb) && ev > 0) continue;  // unchanged neighbours: pending since they formed
        PendingGap c{i, la, hb, t, 0, 0, 0, {}, {}, 0};
        if (i < 0) {
          if (e.kind == EventKind::FloorHit) continue;  // leaves the floor: height 0, rising
          c.g0 = s.z[0] - 0.5 * p.d;
          c.dV = com_velocity(0, hb);
          c.g = p.g;
          oracle_of(0, hb, c.above);
          c.scale = speed_scale(0, hb) + p.g;
        } else {
          if (e.kind == EventKind::ContactEnd && e.i == i) continue;  // opens from zero, parting
          c.g0 = -x[i];
          c.dV = com_velocity(i + 1, hb) - com_velocity(la, i);
          oracle_of(la, i, c.below);
          oracle_of(i + 1, hb, c.above);
          c.scale = speed_scale(la, hb);
        }
        c.start_edges();
        gaps.emplace(i, std::move(c));
      }
    }
  }
  return tally;
}

void expect_agreement(const OracleTally& t, std::uint64_t min_checked) {
  std::printf("checked %llu cluster predictions (%llu own contact ends, %llu other changes), %llu gap and floor "
              "predictions (%llu closings, %llu floor hits), %llu grid points, %llu skipped (grazing), "
              "worst |x_p(t_e)| / tolerance %.3g\n",
              static_cast<unsigned long long>(t.checked), static_cast<unsigned long long>(t.ends),
              static_cast<unsigned long long>(t.other_changes), static_cast<unsigned long long>(t.gaps_checked),
              static_cast<unsigned long long>(t.closings), static_cast<unsigned long long>(t.floor_hits),
              static_cast<unsigned long long>(t.grid_points), static_cast<unsigned long long>(t.skipped_grazing),
              t.worst_time_error);
  EXPECT_EQ(t.failures, 0);
  EXPECT_GE(t.checked, min_checked);
  EXPECT_GE(t.closings, min_checked / 2);
  EXPECT_GE(t.floor_hits, 10u);
  EXPECT_LE(t.skipped_grazing, t.checked / 100 + 10);
}

}  // namespace

// N = 25 across the regimes: near-elastic (binary), logarithmic, condensed; soft and stiff.
TEST(ExactEngineOracle, ClusterPredictionsMatchAnIndependentSolution) {
  for (const auto& [e, k] : std::vector<std::pair<double, double>>{{0.9, 1e6}, {0.5, 1e8}, {0.1, 1e5}, {0.3, 1e12}}) {
    SCOPED_TRACE(::testing::Message() << "e = " << e << ", k = " << k);
    expect_agreement(check_against_oracle(ChainParameters{.N = 25, .k = k, .e = e}, 3, 20000, 16), 2000);
  }
}

// At least 1e5 cluster states: N = 25 over e = 0.05 ... 0.9 and k = 1e4 ... 1e12, and the large
// condensed column N = 150 (clusters of up to 150 particles, sine transforms).
TEST(LongExactEngineOracle, ClusterPredictionsMatchAnIndependentSolutionOnAHundredThousandStates) {
  std::uint64_t total = 0;
  for (double e : {0.05, 0.3, 0.6, 0.9}) {
    for (double k : {1e4, 1e6, 1e8, 1e10, 1e12}) {
      SCOPED_TRACE(::testing::Message() << "N = 25, e = " << e << ", k = " << k);
      const OracleTally t = check_against_oracle(ChainParameters{.N = 25, .k = k, .e = e}, 11, 30000, 256);
      expect_agreement(t, 1000);
      total += t.checked;
    }
  }
  for (double k : {1e6, 1e8}) {
    SCOPED_TRACE(::testing::Message() << "N = 150, e = 0.1, k = " << k);
    const OracleTally t = check_against_oracle(ChainParameters{.N = 150, .k = k, .e = 0.1}, 5, 20000, 256);
    expect_agreement(t, 1000);
    total += t.checked;
  }
  std::printf("total: %llu cluster predictions checked\n", static_cast<unsigned long long>(total));
  EXPECT_GE(total, 100000u);
}
