// The exact event-driven engine against closed forms, conservation laws, a hard-sphere sequence
// at k = 1e12, and the reference engine at steps small enough to have converged.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <functional>
#include <memory>

#include <fmt/format.h>

#include "engines/engine_factory.hpp"
#include "engines/exact/exact_engine.hpp"
#include "engines/runge_kutta_engine.hpp"
#include "model/driven_column.hpp"
#include "model/random.hpp"
#include "simulation/collapse_run.hpp"
#include "simulation/driven_run.hpp"
#include "test_helpers.hpp"

using namespace granchain;
using test_support::EventRecorder;

namespace {

// Sec. III.D: x_i = (i - (N+1)/2)(d + a), v_i = -v0 sgn(x_i) + dv0 xi_i (xi normal, fixed seed).
ChainState free_space_launch(int N, double a, double v0, double dv0, std::uint64_t seed) {
  Rng r(seed);
  ChainState s;
  for (int i = 1; i <= N; ++i) {
    const double x = (i - 0.5 * (N + 1)) * (1.0 + a);
    s.z.push_back(x);
    s.v.push_back(-v0 * ((x > 0) - (x < 0)) + dv0 * r.normal());
  }
  return s;
}

struct Outcome {
  std::vector<double> v, z;
  std::size_t ends = 0, begins = 0, floor_hits = 0;
};

Outcome run(Engine& engine, double t_end) {
  EventRecorder rec;
  engine.advance_to(t_end, rec);
  return {engine.state().v, engine.state().z, rec.count(EventKind::ContactEnd),
          rec.count(EventKind::ContactBegin), rec.count(EventKind::FloorHit)};
}

// max_i |v_i - w_i| / max_i |w_i|
double velocity_error(const std::vector<double>& v, const std::vector<double>& w) {
  double err = 0, scale = 0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    err = std::max(err, std::abs(v[i] - w[i]));
    scale = std::max(scale, std::abs(w[i]));
  }
  return err / scale;
}

struct Case {
  const char* name;
  ChainParameters p;
  ChainState s;
  double t_end;
  std::vector<double> floor_speeds;  // empty: free space
};

Outcome run_exact(const Case& c) {
  std::unique_ptr<ScriptedFloor> floor;
  if (!c.floor_speeds.empty()) floor = std::make_unique<ScriptedFloor>(c.floor_speeds);
  ExactEngine engine(c.p, c.s, floor.get());
  return run(engine, c.t_end);
}

Outcome run_reference(const Case& c, double dt_factor, bool located) {
  std::unique_ptr<ScriptedFloor> floor;
  if (!c.floor_speeds.empty()) floor = std::make_unique<ScriptedFloor>(c.floor_speeds);
  RungeKuttaEngine engine(c.p, c.s, floor.get(), {dt_factor, located});
  return run(engine, c.t_end);
}

std::vector<Case> deterministic_cases() {
  std::vector<Case> cases;
  cases.push_back({"binary", {.N = 2, .g = 0.0, .k = 1e4, .e = 0.5}, {0, {0.0, 1.5}, {1.0, -0.5}}, 1.0, {}});
  cases.push_back({"binary under gravity", {.N = 2, .g = 1.0, .k = 1e4, .e = 0.3}, {0, {0.0, 1.5}, {1.0, -0.5}}, 1.0, {}});
  // e = 0.02 < e_c(3) = 7 - 4 sqrt 3: particle 2 is squeezed between 1 and 3 (a collapse sequence).
  cases.push_back({"three-body collapse", {.N = 3, .g = 0.0, .k = 1e6, .e = 0.02},
                   {0, {0.0, 1.1, 2.25}, {1.0, 0.0, -0.9}}, 2.0, {}});
  // A driven column from a fixed state with a fixed sequence of floor speeds.
  {
    ChainParameters p{.N = 5, .g = 1.0, .k = 1e3, .e = 0.8};
    std::vector<double> speeds;
    Rng r(11);
    for (int i = 0; i < 200; ++i) speeds.push_back(1.0 + r.uniform01());
    cases.push_back({"driven column, scripted floor", p, driven_column_initial_state(p, 3), 4.0, speeds});
  }
  return cases;
}

}  // namespace

// A binary contact is a damped oscillator in the overlap: it lasts exactly tau_c (Eq. tauc) and
// returns the relative velocity times -e (Eq. Dd), at every stiffness, up to k = 1e14.
TEST(ExactEngine, BinaryContactLastsTauCAndRestitutesE) {
  for (double k : {1e4, 1e8, 1e12, 1e14}) {
    for (double e : {0.02, 0.5, 0.9, 1.0}) {
      for (double g : {0.0, 1.0}) {
        ChainParameters p{.N = 2, .g = g, .k = k, .e = e};
        const ChainState s{0.0, {0.0, 1.25}, {1.0, -1.0}};
        ExactEngine engine(p, s, nullptr);
        EventRecorder rec;
        engine.advance_to(0.5, rec);
        ASSERT_EQ(rec.events.size(), 2u) << "k=" << k << " e=" << e;
        const Event& begin = rec.events[0];
        const Event& end = rec.events[1];
        ASSERT_EQ(begin.kind, EventKind::ContactBegin);
        ASSERT_EQ(end.kind, EventKind::ContactEnd);
        // Gravity cancels in the gap: contact at t = 0.25 / 2 exactly.
        EXPECT_NEAR(begin.t, 0.125, 1e-16);
        const double tau_c = contact_law(p).tau_c;
        const double ulp = std::numeric_limits<double>::epsilon() * end.t;
        EXPECT_NEAR(end.t - begin.t, tau_c, 1e-12 * tau_c + 4 * ulp) << "k=" << k << " e=" << e;
        EXPECT_NEAR(end.speed / begin.speed, e, 1e-12) << "k=" << k << " e=" << e;
        const ChainState& st = engine.state();
        EXPECT_NEAR(st.v[1] - st.v[0], 2.0 * e, 2e-12) << "k=" << k << " e=" << e;
        EXPECT_NEAR(st.v[0] + st.v[1], -2.0 * g * 0.5, 1e-14) << "momentum, k=" << k;
      }
    }
  }
}

// The reference engine with its switches located converges at second order onto the exact
// engine (error x100 smaller for a step 10x smaller) and meets it to 1e-6 of the velocities, with
// the same number of collisions and floor hits. The paper's unlocated scheme converges too, at
// first order (docs/benchmarks.md lists its error).
TEST(ExactEngine, DeterministicCasesAgreeWithConvergedReference) {
  for (const Case& c : deterministic_cases()) {
    const Outcome exact = run_exact(c);
    const Outcome coarse = run_reference(c, 1e3, true);
    const Outcome fine = run_reference(c, 1e4, true);
    const double err_coarse = velocity_error(coarse.v, exact.v);
    const double err_fine = velocity_error(fine.v, exact.v);
    EXPECT_LT(err_fine, 1e-6) << c.name;
    EXPECT_GT(err_coarse / err_fine, 30.0) << c.name << ": not second-order convergence";
    EXPECT_EQ(fine.ends, exact.ends) << c.name;
    EXPECT_EQ(fine.begins, exact.begins) << c.name;
    EXPECT_EQ(fine.floor_hits, exact.floor_hits) << c.name;
    EXPECT_GT(exact.ends, 0u) << c.name;
    const Outcome paper = run_reference(c, 1e2, false);
    const Outcome paper_fine = run_reference(c, 1e4, false);
    EXPECT_LT(velocity_error(paper_fine.v, exact.v), velocity_error(paper.v, exact.v)) << c.name;
  }
}

// e < e_c(3) = 7 - 4 sqrt 3 = 0.0718: the soft three-body collapse is a sequence of alternating
// 1-2, 2-3 collisions cut off when the intervals reach tau_c, so the count grows like log k
// (Sec. III.D); for e > e_c(3) it converges to the finite hard-sphere count.
TEST(ExactEngine, ThreeBodyCollapseCountGrowsLikeLogK) {
  auto count = [](double e, double k) {
    ChainParameters p{.N = 3, .g = 0.0, .k = k, .e = e};
    ExactEngine engine(p, {0.0, {0.0, 1.1, 2.25}, {1.0, 0.0, -0.9}}, nullptr);
    EventRecorder rec;
    engine.advance_to(10.0, rec);
    return static_cast<int>(rec.count(EventKind::ContactEnd));
  };
  int previous = count(0.05, 1e6);
  for (double k : {1e8, 1e10, 1e12, 1e14}) {
    const int n = count(0.05, k);
    EXPECT_GE(n, previous + 1) << "k=" << k;  // at least one more collision per two decades
    previous = n;
  }
  EXPECT_EQ(count(0.2, 1e10), count(0.2, 1e14));
}

// N = 25 launched as in Sec. III.D. Many-body collision cascades amplify any difference, so the
// reference is Richardson-extrapolated from two located runs (its error is O(dt^2)).
TEST(ExactEngine, FreeSpaceN25AgreesWithExtrapolatedReference) {
  const Case c{"N=25 free space", {.N = 25, .g = 0.0, .k = 1e3, .e = 0.9}, free_space_launch(25, 1.0, 1.0, 0.1, 7),
               30.0, {}};
  const Outcome exact = run_exact(c);
  const Outcome r1 = run_reference(c, 5e3, true);
  const Outcome r2 = run_reference(c, 1e4, true);
  std::vector<double> extrapolated(c.p.N);
  for (int i = 0; i < c.p.N; ++i) extrapolated[i] = (4.0 * r2.v[i] - r1.v[i]) / 3.0;
  const double e1 = velocity_error(r1.v, exact.v), e2 = velocity_error(r2.v, exact.v);
  EXPECT_GT(e1 / e2, 3.0) << "halving dt should cut the error about 4x";
  EXPECT_LT(e1 / e2, 5.5);
  EXPECT_LT(velocity_error(extrapolated, exact.v), 1e-6);
  EXPECT_EQ(r2.ends, exact.ends);
  EXPECT_EQ(r1.ends, exact.ends);
  EXPECT_GT(exact.ends, 200u);
}

// e = 1, no floor, no gravity: N = 1001 particles with velocities decreasing upwards pass every
// velocity to every other, N(N-1)/2 ~ 5e5 collisions, 1e6 contact events. Energy (kinetic +
// elastic) and momentum are conserved to round-off.
TEST(ExactEngine, ElasticChainConservesEnergyOverAMillionEvents) {
  for (double k : {1e8, 1e12}) {
    const int N = 1001;
    ChainParameters p{.N = N, .g = 0.0, .k = k, .e = 1.0};
    ChainState s;
    Rng r(3);
    for (int i = 0; i < N; ++i) {
      s.z.push_back(i * 1.5);
      s.v.push_back(2.0 * r.uniform01() - 1.0);
    }
    std::sort(s.v.begin(), s.v.end(), std::greater<>());  // every pair must collide once
    ExactEngine engine(p, s, nullptr);
    const double E0 = engine.mechanical_energy_per_mass();
    double P0 = 0;
    for (double v : s.v) P0 += v;
    EventRecorder rec;
    engine.advance_to(1e9, rec);
    EXPECT_GE(rec.events.size(), 999000u) << "k=" << k;
    const double E1 = engine.mechanical_energy_per_mass();
    double P1 = 0, abs_v = 0;
    for (double v : engine.state().v) {
      P1 += v;
      abs_v += std::abs(v);
    }
    EXPECT_NEAR(E1 / E0, 1.0, 1e-12) << "k=" << k;
    EXPECT_NEAR(P1, P0, 1e-13 * abs_v) << "k=" << k;
    // Every pair has collided: no neighbours approach any more.
    const std::vector<double>& v = engine.state().v;
    EXPECT_TRUE(std::is_sorted(v.begin(), v.end())) << "k=" << k;
  }
}

namespace {

// Hard spheres in free space with restitution e: the k -> infinity limit, by direct event loop.
std::vector<double> hard_sphere_final_velocities(std::vector<double> z, std::vector<double> v, double d, double e,
                                                 int& collisions) {
  const int n = static_cast<int>(z.size());
  collisions = 0;
  for (;;) {
    double t_next = std::numeric_limits<double>::infinity();
    int pair = -1;
    for (int i = 0; i + 1 < n; ++i) {
      const double closing = v[i] - v[i + 1];
      if (closing > 0) {
        const double t = (z[i + 1] - z[i] - d) / closing;
        if (t < t_next) t_next = t, pair = i;
      }
    }
    if (pair < 0) return v;
    for (int i = 0; i < n; ++i) z[i] += v[i] * t_next;
    const double vc = 0.5 * (v[pair] + v[pair + 1]), rel = v[pair] - v[pair + 1];
    v[pair] = vc - 0.5 * e * rel;
    v[pair + 1] = vc + 0.5 * e * rel;
    ++collisions;
  }
}

}  // namespace

// At k = 1e12 no time-stepped run is possible; there the exact engine must reproduce the
// hard-sphere sequence (e > e_c(3), so it is finite) up to corrections of order tau_c ~ 1e-6.
TEST(ExactEngine, StiffContactsReproduceHardSpheres) {
  const std::vector<double> z{0.0, 1.1, 2.25, 3.3, 4.6};
  const std::vector<double> v{1.0, 0.2, -0.9, 0.3, -0.7};
  for (double e : {0.3, 0.6, 0.9}) {
    int collisions = 0;
    const std::vector<double> hard = hard_sphere_final_velocities(z, v, 1.0, e, collisions);
    for (double k : {1e10, 1e12, 1e14}) {
      ChainParameters p{.N = 5, .g = 0.0, .k = k, .e = e};
      ExactEngine engine(p, {0.0, z, v}, nullptr);
      EventRecorder rec;
      engine.advance_to(50.0, rec);
      EXPECT_EQ(static_cast<int>(rec.count(EventKind::ContactEnd)), collisions) << "e=" << e << " k=" << k;
      EXPECT_LT(velocity_error(engine.state().v, hard), 30.0 / std::sqrt(k)) << "e=" << e << " k=" << k;
    }
  }
}

// Overlaps are kept relative: at k = 1e12 the largest overlap of a binary contact at relative
// speed 2 is 2/sqrt(2k) ~ 1.4e-6 d, and the engine returns it to full relative precision.
TEST(ExactEngine, OverlapsKeepRelativePrecisionAtHighStiffness) {
  const double k = 1e12;
  ChainParameters p{.N = 2, .g = 0.0, .k = k, .e = 1.0};
  ExactEngine engine(p, {0.0, {10000.0, 10001.25}, {1.0, -1.0}}, nullptr);
  NullEventSink none;
  const double omega = std::sqrt(2.0 * k);  // e = 1: x(t) = (2/omega) sin(omega (t - 0.125))
  const double t = 0.125 + 0.5 * std::acos(-1.0) / omega;  // maximum compression
  engine.advance_to(t, none);
  const std::vector<double> x = engine.overlaps();
  EXPECT_NEAR(x[0] / (2.0 / omega), 1.0, 1e-8);
}

// Momentum in free space is exchanged only in equal and opposite amounts.
TEST(ExactEngine, FreeSpaceConservesMomentum) {
  ChainParameters p{.N = 25, .g = 0.0, .k = 1e6, .e = 0.3};
  const ChainState s = free_space_launch(25, 0.5, 1.0, 0.3, 9);
  ExactEngine engine(p, s, nullptr);
  EventRecorder rec;
  engine.advance_to(20.0, rec);
  double P0 = 0, P1 = 0;
  for (double v : s.v) P0 += v;
  for (double v : engine.state().v) P1 += v;
  EXPECT_GT(rec.count(EventKind::ContactEnd), 100u);
  EXPECT_NEAR(P1, P0, 1e-12);
}

// A soft spring cannot stop a fast particle: the overlap reaches d and the engine stops with an
// error that names the particles, instead of producing numbers.
TEST(ExactEngine, PassThroughIsAnError) {
  ChainParameters p{.N = 3, .g = 0.0, .k = 10.0, .e = 0.9};
  ExactEngine engine(p, {0.0, {0.0, 1.5, 3.0}, {0.0, 0.0, -100.0}}, nullptr);
  NullEventSink none;
  try {
    engine.advance_to(1.0, none);
    FAIL() << "no error";
  } catch (const UnphysicalStateError& err) {
    EXPECT_EQ(err.particle_a(), 2);
    EXPECT_EQ(err.particle_b(), 3);
    EXPECT_NE(std::string(err.what()).find("passed through"), std::string::npos);
  }
}

// The same seed gives the same trajectory, event for event.
TEST(ExactEngine, IsDeterministic) {
  ChainParameters p{.N = 25, .k = 1e6, .e = 0.5};
  auto once = [&] {
    ThermalFloor floor(p.kT0, p.m, 42);
    ExactEngine engine(p, driven_column_initial_state(p, 42), &floor);
    EventRecorder rec;
    engine.advance_to(20.0, rec);
    return std::make_pair(rec.events.size(), engine.state().z);
  };
  const auto a = once(), b = once();
  EXPECT_EQ(a.first, b.first);
  EXPECT_EQ(a.second, b.second);
}

// ---------------------------------------------------------------------------------------------
// Long: driven runs of the exact engine agree statistically with the reference engine on the grid
// N in {3, 25}, e in {0.05, 0.5, 0.9}, k in {1e4, 1e6}. References: the paper's scheme at
// dt = tau_c/100 and tau_c/1000, and the located scheme at tau_c/1000 (second order, converged).
//
// The error of one run: the blocking error of a run of length T can miss fluctuations slower than
// its blocks. In the strongly collapsing cells (N = 25, e = 0.05, k = 1e6) the condensed column
// keeps its mean heights for a large part of T = 200, and two exact runs with different seeds
// differ by up to 4.4 of their combined blocking errors in 39 of the 75 profile values. So the
// exact engine is run with kReplicas independent seeds; the spread s of a quantity over them is a
// direct measure of one run's error. One run's error is taken as max(s, its blocking error), the
// replica mean's as that over sqrt(kReplicas), and z = difference / combined error. With s from
// 8 replicas, z is close to Student's t with 7 degrees of freedom: |z| > 3 has probability 0.02.
// Prints the table.
namespace {

constexpr int kReplicas = 8;

RunResult grid_run(int N, double e, double k, const std::string& engine, double dt_factor, std::uint64_t seed) {
  RunSpec spec;
  spec.params = ChainParameters{.N = N, .k = k, .e = e};
  spec.engine = EngineChoice{.name = engine, .dt_factor = dt_factor};
  spec.T = N < 10 ? (k > 1e5 ? 1000.0 : 5000.0) : (k > 1e5 ? 200.0 : 500.0);
  spec.transient = 0.1 * spec.T;
  spec.seed = seed;
  return run_driven_column(spec, {}, 1.0);
}

// Mean of the exact engine's replicas, the error of one run and the error of the mean.
struct ReplicaEstimate {
  double mean = 0, one_run = 0, of_mean = 0;
};
ReplicaEstimate over_replicas(const std::vector<Estimate>& xs) {
  const double R = static_cast<double>(xs.size());
  double mean = 0, block2 = 0;
  for (const Estimate& x : xs) {
    mean += x.value / R;
    block2 += x.error * x.error / R;
  }
  double var = 0;
  for (const Estimate& x : xs) var += (x.value - mean) * (x.value - mean) / (R - 1);
  const double one = std::max(std::sqrt(var), std::sqrt(block2));
  return {mean, one, one / std::sqrt(R)};
}

// Phi^-1(p) of the standard normal, by bisection on erfc (tests only).
double normal_quantile(double p) {
  double lo = -10, hi = 10;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (0.5 * std::erfc(-mid / std::sqrt(2.0)) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// z of one reference run against the replica mean; the reference run's error is at least the
// replicas' spread (same physics, same run length).
double z_against(const ReplicaEstimate& ex, const Estimate& ref) {
  const double ref_error = std::max(ref.error, ex.one_run);
  return (ex.mean - ref.value) / std::sqrt(ex.of_mean * ex.of_mean + ref_error * ref_error);
}

}  // namespace

TEST(LongExactEngine, AgreesStatisticallyWithReferenceOnTheGrid) {
  std::printf("%4s %5s %6s | %-16s | %-16s %6s | %-16s %6s | %-16s %6s | %s\n", "N", "e", "k", "exact (mean of 8)",
              "ref dt=tc/100", "z", "ref dt=tc/1000", "z", "located tc/1000", "z", "profiles |z|>3 / max|z|");
  for (int N : {3, 25}) {
    for (double e : {0.05, 0.5, 0.9}) {
      for (double k : {1e4, 1e6}) {
        std::vector<RunResult> ex;
        for (int r = 0; r < kReplicas; ++r) ex.push_back(grid_run(N, e, k, "exact", 100, 1 + 10 * r));
        auto replicas = [&](auto pick) {
          std::vector<Estimate> xs;
          for (const RunResult& run : ex) xs.push_back(pick(run));
          return over_replicas(xs);
        };
        const ReplicaEstimate n_coll = replicas([](const RunResult& run) { return run.n_coll; });
        const RunResult paper = grid_run(N, e, k, "reference", 100, 2);
        const RunResult fine = grid_run(N, e, k, "reference", 1000, 3);
        const RunResult located = grid_run(N, e, k, "reference-located", 1000, 4);
        const double z_paper = z_against(n_coll, paper.n_coll);
        const double z_fine = z_against(n_coll, fine.n_coll);
        const double z_loc = z_against(n_coll, located.n_coll);
        int beyond3 = 0;
        double zmax = 0;
        std::string per_particle;  // printed when the profile criterion fails
        for (int i = 0; i < N; ++i) {
          const ParticleProfile& b = located.profiles[i];
          const double zs[] = {
              z_against(replicas([i](const RunResult& run) { return run.profiles[i].z_mean; }), b.z_mean),
              z_against(replicas([i](const RunResult& run) { return run.profiles[i].z_std; }), b.z_std),
              z_against(replicas([i](const RunResult& run) { return run.profiles[i].kinetic; }), b.kinetic)};
          for (double z : zs) {
            beyond3 += std::abs(z) > 3;
            zmax = std::max(zmax, std::abs(z));
          }
          per_particle += fmt::format("      particle {:2d}: z of <z_i> {:6.2f}, sigma_i {:6.2f}, K_i {:6.2f}\n", i + 1,
                                      zs[0], zs[1], zs[2]);
        }
        auto cell = [](const Estimate& x) { return fmt::format("{:.4f} ± {:.4f}", x.value, x.error); };
        const std::string ex_cell = fmt::format("{:.4f} ± {:.4f}", n_coll.mean, n_coll.of_mean);
        std::printf("%4d %5.2f %6.0e | %-16s | %-16s %6.2f | %-16s %6.2f | %-16s %6.2f | %d of %d / %.2f\n", N, e, k,
                    ex_cell.c_str(), cell(paper.n_coll).c_str(), z_paper, cell(fine.n_coll).c_str(), z_fine,
                    cell(located.n_coll).c_str(), z_loc, beyond3, 3 * N, zmax);
        std::fflush(stdout);
        // The 3N profile values of a column are strongly correlated (a column that sits a little
        // higher in the one reference run moves every <z_i> together), so the number beyond 3 sigma
        // says little; the largest |z| is tested, against the Bonferroni bound for 3N values at a
        // false-alarm probability of 1e-3 per cell: |z| < Phi^-1(1 - 0.0005 / (3N)) (3.87 for
        // N = 3, 4.35 for N = 25), which holds whatever the correlation.
        const double zbound = normal_quantile(1.0 - 0.0005 / (3 * N));
        if (zmax >= zbound || beyond3 > std::max(1, 3 * N / 25)) std::printf("%s", per_particle.c_str());
        EXPECT_LT(std::abs(z_loc), 3.0) << "N=" << N << " e=" << e << " k=" << k;
        EXPECT_LT(zmax, zbound) << "N=" << N << " e=" << e << " k=" << k;
      }
    }
  }
}

// Long: a large condensed column, where the exact engine projects its clusters (up to 150
// particles) through FFTW's sine transform: N = 150, e = 0.1, k = 1e6 (power-law regime),
// transient 30, window T = 20, four independent seeds per engine. The reference is the paper's
// scheme at dt = tau_c / 1000 (ten times finer than the paper's). For each of n_coll, the floor
// rate, and the column's mean height, mean thickness and kinetic energy (profile values averaged
// over the particles), the error of a mean is the spread of its four runs over sqrt(4), and
// z = difference / combined error is close to Student's t with 6 degrees of freedom:
// |z| > 4 has probability 0.007 per quantity.
TEST(LongExactEngine, LargeCondensedColumnAgreesWithReference) {
  constexpr int kSeeds = 4;
  auto run = [](const std::string& engine, std::uint64_t seed) {
    RunSpec spec;
    spec.params = ChainParameters{.N = 150, .k = 1e6, .e = 0.1};
    spec.engine = EngineChoice{.name = engine, .dt_factor = 1000};
    spec.T = 20.0;
    spec.transient = 30.0;
    spec.seed = seed;
    return run_driven_column(spec, {}, 1.0);
  };
  // The five quantities of one run.
  auto quantities = [](const RunResult& r) {
    double z = 0, s = 0, K = 0;
    for (const ParticleProfile& p : r.profiles) {
      z += p.z_mean.value / 150;
      s += p.z_std.value / 150;
      K += p.kinetic.value / 150;
    }
    return std::vector<double>{r.n_coll.value, r.floor_rate.value, z, s, K};
  };
  std::vector<std::vector<double>> ex, ref;
  for (int r = 0; r < kSeeds; ++r) {
    ex.push_back(quantities(run("exact", 1 + 10 * r)));
    ref.push_back(quantities(run("reference", 2 + 10 * r)));
  }
  const char* names[] = {"n_coll", "floor rate", "mean height", "mean sigma_i", "mean K_i"};
  for (int q = 0; q < 5; ++q) {
    auto mean_and_error = [q](const std::vector<std::vector<double>>& runs) {
      double m = 0, v = 0;
      for (const auto& r : runs) m += r[q] / kSeeds;
      for (const auto& r : runs) v += (r[q] - m) * (r[q] - m) / (kSeeds - 1);
      return std::pair{m, std::sqrt(v / kSeeds)};
    };
    const auto [me, se] = mean_and_error(ex);
    const auto [mr, sr] = mean_and_error(ref);
    const double z = (me - mr) / std::sqrt(se * se + sr * sr);
    std::printf("%-13s exact %.5g ± %.2g   reference %.5g ± %.2g   z = %.2f\n", names[q], me, se, mr, sr, z);
    EXPECT_LT(std::abs(z), 4.0) << names[q];
  }
}

// The audit (EngineChoice::audit) reads the state only: the same trajectory with it on, and on a
// short condensed run it evaluates every watched value and finds none of the wrong sign.
TEST(ExactEngine, AuditLeavesTheTrajectoryUnchanged) {
  for (int N : {25, 40}) {
    const ChainParameters p{.N = N, .k = 1e6, .e = 0.2};
    auto final_state = [&](bool audit, EngineCounters& c) {
      ThermalFloor floor(p.kT0, p.m, 7);
      EngineChoice choice;
      choice.audit = audit;
      auto engine = make_engine(choice, p, driven_column_initial_state(p, 7), &floor);
      NullEventSink none;
      engine->advance_to(20.0, none);
      c = engine->counters();
      return engine->state();
    };
    EngineCounters plain, audited;
    const ChainState a = final_state(false, plain), b = final_state(true, audited);
    EXPECT_EQ(a.z, b.z) << "N=" << N;
    EXPECT_EQ(a.v, b.v) << "N=" << N;
    EXPECT_EQ(plain.steps, audited.steps);
    EXPECT_EQ(plain.audit_instants, 0u);
    EXPECT_GT(audited.audit_instants, audited.steps);  // two instants per event, nearly all used
    EXPECT_GE(audited.audit_values, audited.audit_instants * static_cast<std::uint64_t>(N - 1));
    EXPECT_EQ(audited.audit_violations, 0u) << "N=" << N;
  }
}

// Long: the audit over more than 10^7 events, on condensed and collisional columns, small and
// large clusters (the large ones through the sine transform), k = 1e6 ... 1e10. Prints the counts.
TEST(LongExactEngine, AuditFindsNoValueOfTheWrongSignOverTenMillionEvents) {
  struct Case {
    int N;
    double e, k, T;
  };
  std::uint64_t events = 0, values = 0, violations = 0;
  for (const Case& c : {Case{25, 0.5, 1e8, 2500}, Case{25, 0.9, 1e10, 200}, Case{25, 0.05, 1e6, 500},
                        Case{40, 0.3, 1e8, 200}, Case{150, 0.1, 1e6, 50}, Case{150, 0.1, 1e8, 50}}) {
    const ChainParameters p{.N = c.N, .k = c.k, .e = c.e};
    ThermalFloor floor(p.kT0, p.m, 3);
    EngineChoice choice;
    choice.audit = true;
    auto engine = make_engine(choice, p, driven_column_initial_state(p, 3), &floor);
    NullEventSink none;
    engine->advance_to(c.T, none);
    const EngineCounters k = engine->counters();
    std::printf("N = %3d  e = %4.2f  k = %6.0e  T = %5.0f: %9llu events, %9llu instants, %11llu values, %llu of the wrong sign\n",
                c.N, c.e, c.k, c.T, static_cast<unsigned long long>(k.steps),
                static_cast<unsigned long long>(k.audit_instants), static_cast<unsigned long long>(k.audit_values),
                static_cast<unsigned long long>(k.audit_violations));
    std::fflush(stdout);
    events += k.steps;
    values += k.audit_values;
    violations += k.audit_violations;
  }
  std::printf("in all: %llu events, %llu values checked, %llu of the wrong sign\n",
              static_cast<unsigned long long>(events), static_cast<unsigned long long>(values),
              static_cast<unsigned long long>(violations));
  EXPECT_GE(events, 10000000u);
  EXPECT_EQ(violations, 0u);
}

// Free-space collapse of N = 25 (Sec. III.D) at k = 1e8, e = 0.5: the collision count per launch
// from the exact engine and from the reference (dt = tau_c/100, the paper's), over the same 60
// launches. Cascades of many-body collisions amplify any difference, so the launches are compared
// as samples: the means must agree within 3 standard errors of their difference (the reference's
// O(dt^2) bias is far below that error at dt = tau_c/100).
TEST(LongExactEngine, FreeSpaceCollapseAtHighStiffnessAgreesWithReference) {
  CollapseSpec s;
  s.params.N = 25;
  s.params.e = 0.5;
  s.params.k = 1e8;
  s.realizations = 60;
  s.threads = 2;
  const CollapseResult exact = run_collapse(s);
  s.engine.name = "reference";
  const CollapseResult ref = run_collapse(s);
  ASSERT_EQ(exact.collapsed, 0);
  ASSERT_EQ(ref.collapsed, 0);
  const double diff = exact.n_tot_mean - ref.n_tot_mean;
  const double err = std::hypot(exact.n_tot_error, ref.n_tot_error);
  std::printf("n_tot: exact %.1f +- %.1f, reference %.1f +- %.1f, z = %.2f\n", exact.n_tot_mean, exact.n_tot_error,
              ref.n_tot_mean, ref.n_tot_error, diff / err);
  EXPECT_LT(std::abs(diff), 3 * err);
  EXPECT_GT(exact.n_tot_mean, 1000.0) << "a many-body cascade, not a few binary collisions";
}
