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
  int failures = 0;
  double worst_time_error = 0;  // |t_e - root|/tolerance, over contact ends (root from the x_p value)
};

struct Pending {
  int lo, hi;
  double t0;
  OracleCluster cluster;
};

// Runs the driven column until `events` events and checks every cluster prediction.
OracleTally check_against_oracle(const ChainParameters& p, std::uint64_t seed, std::uint64_t events) {
  ThermalFloor floor(p.kT0, p.m, seed);
  ExactEngine engine(p, driven_column_initial_state(p, seed), &floor);
  const ContactLaw law = contact_law(p);
  const double h = law.tau_c / 64;
  const real eps = std::numeric_limits<double>::epsilon();
  StopAtEveryEvent sink;
  std::map<int, Pending> pending;  // by lo
  OracleTally tally;
  std::uint64_t grazing_before = 0;

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
    // The clusters now: pairs with a positive overlap, and the pair whose contact has just begun
    // (its overlap is zero, or round-off either side of it after the projection onto modes and
    // back). A grazing or held contact (overlap at zero, or below it by round-off while
    // held) makes the state ambiguous to the oracle: the cluster is not checked.
    const std::vector<double> x = engine.overlaps();
    const ChainState& s = engine.state();
    const bool grazing = engine.counters().grazing_contacts != grazing_before;
    grazing_before = engine.counters().grazing_contacts;
    for (int lo = 0; lo < p.N;) {
      int hi = lo;
      while (hi + 1 < p.N && (x[hi] > 0 || (e.kind == EventKind::ContactBegin && hi == e.i))) ++hi;
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
  }
  return tally;
}

void expect_agreement(const OracleTally& t, std::uint64_t min_checked) {
  std::printf("checked %llu cluster predictions (%llu own contact ends, %llu other changes), %llu grid points, "
              "%llu skipped (grazing), worst |x_p(t_e)| / tolerance %.3g\n",
              static_cast<unsigned long long>(t.checked), static_cast<unsigned long long>(t.ends),
              static_cast<unsigned long long>(t.other_changes), static_cast<unsigned long long>(t.grid_points),
              static_cast<unsigned long long>(t.skipped_grazing), t.worst_time_error);
  EXPECT_EQ(t.failures, 0);
  EXPECT_GE(t.checked, min_checked);
  EXPECT_LE(t.skipped_grazing, t.checked / 100 + 10);
}

}  // namespace

// N = 25 across the regimes: near-elastic (binary), logarithmic, condensed; soft and stiff.
TEST(ExactEngineOracle, ClusterPredictionsMatchAnIndependentSolution) {
  for (const auto& [e, k] : std::vector<std::pair<double, double>>{{0.9, 1e6}, {0.5, 1e8}, {0.1, 1e5}, {0.3, 1e12}}) {
    SCOPED_TRACE(::testing::Message() << "e = " << e << ", k = " << k);
    expect_agreement(check_against_oracle(ChainParameters{.N = 25, .k = k, .e = e}, 3, 20000), 2000);
  }
}

// At least 1e5 cluster states: N = 25 over e = 0.05 ... 0.9 and k = 1e4 ... 1e12, and the large
// condensed column N = 150 (clusters of up to 150 particles, sine transforms).
TEST(LongExactEngineOracle, ClusterPredictionsMatchAnIndependentSolutionOnAHundredThousandStates) {
  std::uint64_t total = 0;
  for (double e : {0.05, 0.3, 0.6, 0.9}) {
    for (double k : {1e4, 1e6, 1e8, 1e10, 1e12}) {
      SCOPED_TRACE(::testing::Message() << "N = 25, e = " << e << ", k = " << k);
      const OracleTally t = check_against_oracle(ChainParameters{.N = 25, .k = k, .e = e}, 11, 30000);
      expect_agreement(t, 1000);
      total += t.checked;
    }
  }
  for (double k : {1e6, 1e8}) {
    SCOPED_TRACE(::testing::Message() << "N = 150, e = 0.1, k = " << k);
    const OracleTally t = check_against_oracle(ChainParameters{.N = 150, .k = k, .e = 0.1}, 5, 20000);
    expect_agreement(t, 1000);
    total += t.checked;
  }
  std::printf("total: %llu cluster predictions checked\n", static_cast<unsigned long long>(total));
  EXPECT_GE(total, 100000u);
}
