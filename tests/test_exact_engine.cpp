// The exact event-driven engine against closed forms, conservation laws, a hard-sphere sequence
// at k = 1e12, and the reference engine at steps small enough to have converged.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <functional>
#include <memory>

#include <fmt/format.h>

#include "engines/engine_registry.hpp"
#include "engines/exact/exact_engine.hpp"
#include "engines/runge_kutta_engine.hpp"
#include "model/driven_column.hpp"
#include "model/random.hpp"
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
  double fine_tolerance = 1e-6;       // of the reference at dt = tau_c / 1e4 against the exact engine
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
    // Nearly perfectly inelastic, e = 1e-6: the binary contact's damping ratio
    // is 0.975, and the cluster modes with Laplacian eigenvalue lambda > 2.1 are overdamped
    // (damping ratio 0.975 sqrt(lambda / 2)); every kind of mode occurs.
    ChainParameters q{.N = 5, .g = 1.0, .k = 1e3, .e = 1e-6};
    // Strong damping makes the reference's error constant larger (2.9e-6 at dt = tau_c / 1e4);
    // it still converges onto the exact engine at second order.
    cases.push_back({"driven column, e = 1e-6", q, driven_column_initial_state(q, 3), 4.0, speeds, 1e-5});
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
// engine (error x100 smaller for a step 10x smaller) and meets it to 1e-6 of the velocities (1e-5 at
// e = 1e-6), with
// the same number of collisions and floor hits. The paper's unlocated scheme converges too, at
// first order (docs/benchmarks.md lists its error).
TEST(ExactEngine, DeterministicCasesAgreeWithConvergedReference) {
  for (const Case& c : deterministic_cases()) {
    const Outcome exact = run_exact(c);
    const Outcome coarse = run_reference(c, 1e3, true);
    const Outcome fine = run_reference(c, 1e4, true);
    const double err_coarse = velocity_error(coarse.v, exact.v);
    const double err_fine = velocity_error(fine.v, exact.v);
    EXPECT_LT(err_fine, c.fine_tolerance) << c.name;
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

// The audit (EngineChoice::audit) reads the state only: the same trajectory with it on, and on a
// short condensed run it evaluates every watched value and finds none of the wrong sign.
TEST(ExactEngine, AuditLeavesTheTrajectoryUnchanged) {
  for (int N : {25, 40}) {
    const ChainParameters p{.N = N, .k = 1e6, .e = 0.2};
    auto final_state = [&](bool audit, ExactCounters& c) {
      ThermalFloor floor(p.kT0, p.m, 7);
      ExactEngine engine(p, driven_column_initial_state(p, 7), &floor, ExactOptions{.audit = audit});
      NullEventSink none;
      engine.advance_to(20.0, none);
      c = engine.work();
      return engine.state();
    };
    ExactCounters plain, audited;
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
    ExactEngine engine(p, driven_column_initial_state(p, 3), &floor, ExactOptions{.audit = true});
    NullEventSink none;
    engine.advance_to(c.T, none);
    const ExactCounters k = engine.work();
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
