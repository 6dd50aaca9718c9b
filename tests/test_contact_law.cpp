// The contact law (Sec. II.B) and the binary collision as integrated by the reference engine.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "engines/runge_kutta_engine.hpp"
#include "model/chain_parameters.hpp"
#include "test_helpers.hpp"

using namespace granchain;

// Eq. (Dd) inverts e = exp(-D tau_c) with tau_c from Eq. (tauc).
TEST(ContactLaw, DampingReproducesRestitution) {
  for (double e : {0.01, 0.0718, 0.3, 0.5, 0.88, 0.99}) {
    for (double k : {1e2, 1e5, 1e10}) {
      const ContactLaw c = contact_law({.N = 2, .k = k, .e = e});
      EXPECT_NEAR(std::exp(-c.D * c.tau_c), e, 1e-13 * std::max(1.0, 1.0 / e)) << "e=" << e << " k=" << k;
    }
  }
}

// Hard-sphere limit at fixed e: D ~ k^(1/2), tau_c ~ k^(-1/2); e = 1 is undamped with tau_c = pi/sqrt(2k/m).
TEST(ContactLaw, ScalingWithStiffness) {
  const ContactLaw a = contact_law({.N = 2, .k = 1e6, .e = 0.5});
  const ContactLaw b = contact_law({.N = 2, .k = 1e8, .e = 0.5});
  EXPECT_NEAR(b.D / a.D, 10.0, 1e-12);
  EXPECT_NEAR(a.tau_c / b.tau_c, 10.0, 1e-12);
  const ContactLaw el = contact_law({.N = 2, .m = 2.0, .k = 50.0, .e = 1.0});
  EXPECT_EQ(el.D, 0.0);
  EXPECT_NEAR(el.tau_c, std::numbers::pi / std::sqrt(2.0 * 50.0 / 2.0), 1e-14);
}

namespace {

struct BinaryOutcome {
  double restitution;  // -u_out / u_in
  double duration;     // ContactEnd - ContactBegin
  std::size_t ends;
};

// Two particles in free space (no gravity, no floor) meeting head on; they touch exactly at t = 0
// so the contact starts on a step boundary.
BinaryOutcome binary_collision(double e, double dt_factor, double k = 1e4) {
  ChainParameters p{.N = 2, .g = 0.0, .k = k, .e = e};
  ChainState s;
  s.z = {0.0, p.d};
  s.v = {0.7, -0.3};
  RungeKuttaEngine engine(p, s, nullptr, {dt_factor});
  test_support::EventRecorder rec;
  engine.advance_to(3.0 * contact_law(p).tau_c, rec);
  const double u_in = 0.7 - (-0.3);
  const double u_out = engine.state().v[0] - engine.state().v[1];
  BinaryOutcome o{-u_out / u_in, 0.0, rec.count(EventKind::ContactEnd)};
  double t_begin = NAN;
  for (const auto& ev : rec.events) {
    if (ev.kind == EventKind::ContactBegin) t_begin = ev.t;
    if (ev.kind == EventKind::ContactEnd) o.duration = ev.t - t_begin;
  }
  return o;
}

}  // namespace

// Restitution and contact time of one binary collision. The dashpot force jumps from D m u to 0
// when the overlap closes, mid-step, so the outgoing relative speed carries an error of at most
// 2 D u' dt = 2 |ln e| / dt_factor (relative); the smooth part of the midpoint rule adds O(dt^2).
TEST(ReferenceEngineBinary, RestitutionWithinStepErrorBound) {
  for (double e : {0.05, 0.5, 0.9, 1.0}) {
    for (double F : {100.0, 1000.0}) {
      const BinaryOutcome o = binary_collision(e, F);
      const double bound = e * (2.0 * std::abs(std::log(e)) / F + 10.0 / (F * F));
      EXPECT_EQ(o.ends, 1u);
      EXPECT_NEAR(o.restitution, e, bound) << "e=" << e << " dt_factor=" << F;
      const double tau_c = contact_law({.N = 2, .k = 1e4, .e = e}).tau_c;
      EXPECT_NEAR(o.duration, tau_c, 2.0 * tau_c / F) << "e=" << e << " dt_factor=" << F;
    }
  }
}

// The step error shrinks at least linearly with dt (first order from the dashpot jump).
TEST(ReferenceEngineBinary, ConvergesAsStepShrinks) {
  for (double e : {0.05, 0.5}) {
    double previous = std::abs(binary_collision(e, 50.0).restitution - e);
    for (double F : {200.0, 800.0, 3200.0}) {
      const double err = std::abs(binary_collision(e, F).restitution - e);
      EXPECT_LT(err, previous / 3.0) << "e=" << e << " dt_factor=" << F;
      previous = err;
    }
  }
}

// The outcome depends on k only through the time scale: restitution is k-independent.
TEST(ReferenceEngineBinary, RestitutionIndependentOfStiffness) {
  const double r4 = binary_collision(0.5, 1000.0, 1e4).restitution;
  const double r8 = binary_collision(0.5, 1000.0, 1e8).restitution;
  EXPECT_NEAR(r4, r8, 1e-9);
}
