// Conservation laws and failure modes of the reference (Runge-Kutta) engine.
#include <gtest/gtest.h>

#include <cmath>

#include "engines/runge_kutta_engine.hpp"
#include "model/random.hpp"
#include "test_helpers.hpp"

using namespace granchain;

namespace {

// Closely spaced particles with alternating velocities in free space: many collisions.
ChainState crowded_chain(const ChainParameters& p, std::uint64_t seed) {
  Rng r(seed);
  ChainState s;
  for (int i = 0; i < p.N; ++i) {
    s.z.push_back(i * (p.d + 0.05));
    s.v.push_back((i % 2 == 0 ? 1.0 : -1.0) + 0.2 * r.normal());
  }
  return s;
}

double momentum(const ChainState& s, double m) {
  double P = 0;
  for (double v : s.v) P += m * v;
  return P;
}

// Kinetic plus spring energy.
double energy(const ChainState& s, const ChainParameters& p) {
  double E = 0;
  for (double v : s.v) E += 0.5 * p.m * v * v;
  for (int i = 0; i + 1 < p.N; ++i) {
    const double x = p.d - (s.z[i + 1] - s.z[i]);
    if (x > 0) E += 0.5 * p.k * x * x;
  }
  return E;
}

}  // namespace

// Pair forces are equal and opposite, and the midpoint rule is linear in them: total momentum
// changes only by gravity, -N m g t, to round-off.
TEST(ReferenceEngine, MomentumChangesOnlyByGravity) {
  for (double g : {0.0, 1.0}) {
    ChainParameters p{.N = 12, .g = g, .k = 1e5, .e = 0.3};
    const ChainState s0 = crowded_chain(p, 5);
    RungeKuttaEngine eng(p, s0, nullptr);
    test_support::EventRecorder rec;
    eng.advance_to(2.0, rec);
    EXPECT_GT(rec.count(EventKind::ContactEnd), 10u);
    const double expected = momentum(s0, p.m) - p.N * p.m * g * 2.0;
    EXPECT_NEAR(momentum(eng.state(), p.m), expected, 1e-11 * p.N);
  }
}

// e = 1, no gravity, no floor: the energy is conserved up to the scheme's error. For a harmonic
// contact the midpoint rule multiplies the energy by 1 + (omega dt)^4 / 4 per step, i.e. about
// pi (omega dt)^3 / 4 = pi^4 / (4 F^3) per contact for dt = tau_c / F; the spring force's kink at
// zero overlap adds an error of the same order. We allow 10 x pi^4/(4 F^3) per contact, and require
// the error to fall at least 4-fold when F doubles (second order or better).
TEST(ReferenceEngine, ElasticEnergyConservedToSchemeOrder) {
  double previous = 0;
  for (double F : {100.0, 200.0}) {
    ChainParameters p{.N = 10, .g = 0.0, .k = 1e4, .e = 1.0};
    const ChainState s0 = crowded_chain(p, 8);
    RungeKuttaEngine eng(p, s0, nullptr, {F});
    test_support::EventRecorder rec;
    eng.advance_to(5.0, rec);
    const double contacts = static_cast<double>(rec.count(EventKind::ContactEnd));
    ASSERT_GT(contacts, 20);
    const double drift = std::abs(energy(eng.state(), p) / energy(s0, p) - 1.0);
    EXPECT_LT(drift, contacts * 10.0 * std::pow(M_PI, 4) / (4.0 * F * F * F)) << "F=" << F;
    if (previous > 0) EXPECT_LT(drift, previous / 4.0);
    previous = drift;
  }
}

// With dissipation energy only decreases (e < 1, no gravity, no floor).
TEST(ReferenceEngine, InelasticEnergyNeverIncreases) {
  ChainParameters p{.N = 10, .g = 0.0, .k = 1e4, .e = 0.7};
  RungeKuttaEngine eng(p, crowded_chain(p, 9), nullptr);
  NullEventSink sink;
  double E = energy(eng.state(), p);
  for (int j = 1; j <= 200; ++j) {
    eng.advance_to(0.01 * j, sink);
    const double En = energy(eng.state(), p);
    EXPECT_LE(En, E * (1 + 1e-6));
    E = En;
  }
}

// Springs far too soft for the weight above them: the particles pass through each other, and the
// engine stops with an error naming the time and the particles.
TEST(ReferenceEngine, PassingThroughIsAnError) {
  ChainParameters p{.N = 20, .g = 1.0, .k = 1.0, .e = 0.5};
  ChainState s;
  for (int i = 0; i < p.N; ++i) {
    s.z.push_back(0.5 + i * 1.01);
    s.v.push_back(0.0);
  }
  ScriptedFloor floor(std::vector<double>(100000, 0.0));
  RungeKuttaEngine eng(p, s, &floor);
  NullEventSink sink;
  try {
    eng.advance_to(100.0, sink);
    FAIL() << "expected UnphysicalStateError";
  } catch (const UnphysicalStateError& e) {
    EXPECT_GT(e.time(), 0.0);
    EXPECT_EQ(e.particle_b(), e.particle_a() + 1);
    EXPECT_NE(std::string(e.what()).find("passed through"), std::string::npos);
  }
}

// Time lands exactly on the requested values, and events come in time order.
TEST(ReferenceEngine, AdvancesToExactTimesWithOrderedEvents) {
  ChainParameters p{.N = 6, .g = 1.0, .k = 1e4, .e = 0.8};
  ThermalFloor floor(1.0, 1.0, 3);
  ChainState s;
  for (int i = 0; i < p.N; ++i) {
    s.z.push_back(0.6 + 1.1 * i);
    s.v.push_back(0.0);
  }
  RungeKuttaEngine eng(p, s, &floor);
  test_support::EventRecorder rec;
  for (double t : {0.123456789, 1.0, 3.3333333}) {
    eng.advance_to(t, rec);
    EXPECT_EQ(eng.time(), t);
  }
  ASSERT_GT(rec.events.size(), 10u);
  for (std::size_t i = 1; i < rec.events.size(); ++i) EXPECT_LE(rec.events[i - 1].t, rec.events[i].t);
  EXPECT_GT(rec.count(EventKind::FloorHit), 0u);
  EXPECT_THROW(eng.advance_to(1.0, rec), std::logic_error);
}
