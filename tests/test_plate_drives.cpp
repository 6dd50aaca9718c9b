// The vibrating plates (model/plate_motion.hpp): their motion against its closed forms, the plate's
// contact law, and a single sphere on a sinusoidal plate against the known results of the bouncing
// ball (resting for Gamma < 1, take-off where the plate decelerates faster than g, the period-1
// orbit and its period doubling), integrated by the reference engine.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "engines/engine_registry.hpp"
#include "engines/runge_kutta_engine.hpp"
#include "reproduce/store_analysis.hpp"
#include "simulation/driven_run.hpp"
#include "store/results_store.hpp"
#include "store/store_export.hpp"
#include "temp_dir.hpp"
#include "model/chain_parameters.hpp"
#include "model/driven_column.hpp"
#include "model/floor.hpp"
#include "model/plate_motion.hpp"
#include "test_helpers.hpp"

using namespace granchain;

namespace {

constexpr double kPi = std::numbers::pi;

// The angle in (-pi, pi] equivalent to x.
double wrapped(double x) { return std::remainder(x, 2 * kPi); }

}  // namespace

// v = dz/dt and a = dv/dt (central differences away from the switching instants), z within
// [-A, A] reaching both ends, the peak acceleration Gamma g = gamma_factor A omega^2, and the
// switching instants a half period (quadratic) or a period (sawtooth) apart.
TEST(PlateMotion, MatchesItsClosedForms) {
  const double A = 0.3, omega = 2.5, P = 2 * kPi / omega;
  for (DriveKind kind : {DriveKind::Sine, DriveKind::Sawtooth, DriveKind::Quadratic}) {
    const PlateMotion m(kind, A, omega, 1.234);
    double zmin = 1e9, zmax = -1e9, amax = 0;
    const double h = 1e-6;
    for (int j = 0; j < 2000; ++j) {
      const double t = 10.0 + P * j / 2000.0 + 1e-4;
      zmin = std::min(zmin, m.z(t));
      zmax = std::max(zmax, m.z(t));
      amax = std::max(amax, std::abs(m.a(t)));
      if (m.next_switch(t - 2 * h) < t + 2 * h) continue;  // a switch within the differences
      EXPECT_NEAR((m.z(t + h) - m.z(t - h)) / (2 * h), m.v(t), 1e-7) << drive_name(kind) << " t=" << t;
      EXPECT_NEAR((m.v(t + h) - m.v(t - h)) / (2 * h), m.a(t), 1e-5) << drive_name(kind) << " t=" << t;
    }
    EXPECT_GE(zmin, -A) << drive_name(kind);
    EXPECT_LE(zmax, A) << drive_name(kind);
    EXPECT_NEAR(zmin, -A, 2e-3) << drive_name(kind);
    EXPECT_NEAR(zmax, A, 2e-3) << drive_name(kind);
    // (sampled: the sine's peak within (pi / 2000)^2 / 2 of its value)
    if (kind != DriveKind::Sawtooth) EXPECT_NEAR(amax / (gamma_factor(kind) * A * omega * omega), 1.0, 3e-6) << drive_name(kind);
    EXPECT_NEAR(m.max_speed(), kind == DriveKind::Sine ? A * omega : kind == DriveKind::Sawtooth ? A * omega / kPi : 4 * A * omega / kPi,
                1e-15);
  }
  EXPECT_EQ(PlateMotion(DriveKind::Sine, A, omega, 0.0).next_switch(3.0), INFINITY);
  // Switching instants: the quadratic's a_p changes sign every half period with z and v continuous;
  // the sawtooth drops by 2A once a period.
  const PlateMotion q(DriveKind::Quadratic, A, omega, 0.7);
  const PlateMotion s(DriveKind::Sawtooth, A, omega, 0.7);
  double tq = q.next_switch(5.0), ts = s.next_switch(5.0);
  for (int j = 0; j < 6; ++j) {
    const double eps = 1e-9;
    EXPECT_NEAR(q.z(tq - eps), q.z(tq + eps), 1e-8);
    EXPECT_NEAR(q.v(tq - eps), q.v(tq + eps), 1e-7);
    EXPECT_NEAR(q.a(tq - eps), -q.a(tq + eps), 1e-12);
    EXPECT_NEAR(s.z(ts - eps) - s.z(ts + eps), 2 * A, 1e-7);
    const double tq2 = q.next_switch(tq), ts2 = s.next_switch(ts);
    EXPECT_NEAR(tq2 - tq, P / 2, 1e-12);
    EXPECT_NEAR(ts2 - ts, P, 1e-12);
    tq = tq2;
    ts = ts2;
  }
  // Names are what --drive reads.
  for (DriveKind kind : {DriveKind::Thermal, DriveKind::Sine, DriveKind::Sawtooth, DriveKind::Quadratic}) {
    DriveKind back = DriveKind::Thermal;
    ASSERT_TRUE(find_drive(drive_name(kind), back));
    EXPECT_EQ(back, kind);
  }
}

namespace {

// One sphere above a plate, integrated by the located reference engine; its floor events.
struct Bounces {
  std::vector<double> begin, end;  // contact begins (FloorContact) and ends (FloorHit)
  std::vector<double> in_speed;    // relative speed at each begin
  std::vector<double> out_speed;   // relative speed at each end
  ChainState last;
};

Bounces bounce(const PlateMotion& motion, double e, double k, double z0, double v0, double t_end,
               EngineKind kind = EngineKind::ReferenceLocated) {
  ChainParameters p{.N = 1, .k = k, .e = e};
  if (engine_info(kind).hard_spheres) p.k = INFINITY;
  VibratingPlate plate(motion, e);
  ChainState s;
  s.z = {z0};
  s.v = {v0};
  const auto engine_ptr = make_engine(EngineChoice{.kind = kind}, p, s, &plate);
  Engine& engine = *engine_ptr;
  test_support::EventRecorder rec;
  engine.advance_to(t_end, rec);
  Bounces b;
  for (const Event& ev : rec.events) {
    if (ev.kind == EventKind::FloorContact) {
      b.begin.push_back(ev.t);
      b.in_speed.push_back(ev.speed);
    }
    if (ev.kind == EventKind::FloorHit) {
      b.end.push_back(ev.t);
      b.out_speed.push_back(ev.speed);
    }
  }
  b.last = engine.state();
  return b;
}

}  // namespace

// The plate's contact is the mirror image's (plate_motion.hpp): on a sawtooth's rising ramp (a
// constant plate velocity, so the plate's frame is inertial) the sphere leaves with e times the
// speed it arrived with, relative to the plate, after a contact of tau_c, as in a binary collision
// (Eqs. Dd, tauc); gravity shifts both by O(g tau_c / u).
TEST(PlateDrives, PlateContactHasTheRestitutionAndDurationOfAPair) {
  for (double e : {0.3, 0.7, 0.95}) {
    const double k = 1e8, omega = 0.05;  // ramp speed A omega / pi, a period of 126
    const PlateMotion ramp(DriveKind::Sawtooth, 1.0, omega, 0.0);
    const double t_end = 1.0;            // far from the drop at t = 2 pi / omega
    const double u0 = 5.0;               // speed towards the plate, relative to it, at t = 0
    const double z0 = ramp.z(0.0) + 0.5 + 0.5 * u0 * 0.5;  // meets the plate at t ~ 0.25
    const Bounces b = bounce(ramp, e, k, z0, ramp.v(0.0) - u0, t_end);
    ASSERT_EQ(b.begin.size(), 1u) << e;
    ASSERT_EQ(b.end.size(), 1u) << e;
    const double u_in = b.in_speed[0];
    EXPECT_NEAR(u_in, u0 + b.begin[0], 1e-3) << e;  // free fall before the contact
    const ContactLaw law = contact_law({.N = 2, .k = k, .e = e});
    const double tol = 10 * law.tau_c / u_in;  // g tau_c / u and more
    EXPECT_NEAR(b.out_speed[0] / u_in, e, tol) << e;
    EXPECT_NEAR((b.end[0] - b.begin[0]) / law.tau_c, 1.0, 2e-2) << e;
  }
}

// Gamma <= 1: a sphere at rest on the plate stays on it (the plate never pulls it down faster
// than g); Gamma > 1: it first leaves where the plate's deceleration reaches g, sin theta = 1/Gamma
// with the plate still rising (cos theta > 0), for the sine; for the quadratic arcs, at the start of
// the decelerating arc. The quadratic's acceleration jumps by 2 Gamma g there, and the soft contact,
// compressed for the old acceleration, rings: below Gamma = 1 the sphere hops off with a speed of
// at most about 2 Gamma g tau_c / pi (zero in the hard-sphere limit), never more.
TEST(PlateDrives, ASphereAtRestStaysBelowGammaOneAndLeavesAbove) {
  const double omega = 2.0, e = 0.5, k = 1e6;
  for (DriveKind kind : {DriveKind::Sine, DriveKind::Quadratic}) {
    for (double Gamma : {0.6, 0.95, 1.5}) {
      const double A = Gamma / (gamma_factor(kind) * omega * omega);
      // Phase 3 pi / 2 + small: the sine plate at its lowest, where it pushes up hardest; the
      // quadratic's accelerating arc. Resting: overlap g / (2 k/m) (the mirror image's spring).
      const double phase = kind == DriveKind::Sine ? 1.5 * kPi : 1.2 * kPi;
      const PlateMotion m(kind, A, omega, phase);
      const double z0 = m.z(0.0) + 0.5 - (1.0 + m.a(0.0)) / (2 * k);
      const Bounces b = bounce(m, e, k, z0, m.v(0.0), 10 * 2 * kPi / omega);
      if (Gamma <= 1 && kind == DriveKind::Sine) {
        EXPECT_TRUE(b.end.empty()) << drive_name(kind) << " Gamma=" << Gamma << " left at t=" << b.end.front();
        continue;
      }
      if (Gamma <= 1) {
        const double tau_c = contact_law({.N = 2, .k = k, .e = e}).tau_c;
        for (double u : b.out_speed) EXPECT_LT(u, 2 * Gamma * tau_c / kPi) << "Gamma=" << Gamma;
        continue;
      }
      ASSERT_FALSE(b.end.empty()) << drive_name(kind) << " Gamma=" << Gamma;
      const double theta = omega * b.end.front() + phase;
      if (kind == DriveKind::Sine) {
        // The contact opens a little after the force vanishes: within a few omega tau_c.
        EXPECT_NEAR(wrapped(theta - std::asin(1.0 / Gamma)), 0.0, 0.05) << "Gamma=" << Gamma;
      } else {
        // The decelerating arc starts at cycle fraction 3/4 + ... of the phase convention: c = 0.
        const double c = theta / (2 * kPi) - std::floor(theta / (2 * kPi));
        EXPECT_LT(std::min(c, 1 - c), 0.01) << "left at cycle fraction " << c;
      }
    }
  }
}

// The period-1 orbit of the bouncing ball (one impact per plate period, take-off speed pi g / omega)
// exists for Gamma >= pi (1 - r) / (1 + r) and is stable up to
// Gamma+ = sqrt([pi (1 - r) / (1 + r)]^2 + [2 (1 + r^2) / (1 + r)^2]^2), impacting where
// cos theta* = pi (1 - r) / ((1 + r) Gamma), sin theta* > 0 (Holmes, J. Sound Vib. 84, 173 (1982),
// the exact impact map). Just above Gamma+ the orbit doubles its period: the flight times alternate.
class BouncingBall : public ::testing::TestWithParam<EngineKind> {};

TEST_P(BouncingBall, FindsThePeriodOneOrbitAndItsPeriodDoubling) {
  const EngineKind kind = GetParam();
  const double omega = 2 * kPi, P = 1.0, r = 0.5, k = 1e7;
  const double lower = kPi * (1 - r) / (1 + r);
  const double upper = std::hypot(lower, 2 * (1 + r * r) / ((1 + r) * (1 + r)));
  ASSERT_NEAR(upper, 1.5268, 1e-4);
  const auto launch = [&](double Gamma, double t_end) {
    // On the period-1 orbit (if it exists) but 5 % fast: leaving the plate at theta* with 1.05 pi g / omega.
    const double theta_star = std::acos(std::min(1.0, lower / Gamma)), A = Gamma / (omega * omega);
    const PlateMotion m(DriveKind::Sine, A, omega, theta_star);
    return bounce(m, r, k, m.z(0.0) + 0.5 + 1e-9, 1.05 * kPi / omega, t_end, kind);
  };
  // Inside the stable window: the perturbation decays, each impact one period after the last, at theta*.
  {
    const double Gamma = 1.3;
    const Bounces b = launch(Gamma, 60 * P);
    ASSERT_GT(b.end.size(), 50u);
    ASSERT_LT(b.end.size(), 70u);
    const double theta_star = std::acos(lower / Gamma);
    for (std::size_t j = b.end.size() - 10; j < b.end.size(); ++j) {
      EXPECT_NEAR(b.end[j] - b.end[j - 1], P, 1e-3) << j;
      const double mid = 0.5 * (b.begin[j] + b.end[j]);  // the hard impact: the middle of the contact
      EXPECT_NEAR(wrapped(omega * mid + theta_star - theta_star), 0.0, 0.01) << j;  // phase omega t + theta*
      // leaving with pi g / omega, i.e. pi g / omega - A omega cos theta* relative to the plate
      EXPECT_NEAR(b.out_speed[j], kPi / omega - Gamma / omega * lower / Gamma, 0.01 * kPi / omega) << j;
    }
  }
  // Above Gamma+: two flight times that alternate, their mean still one period.
  {
    const Bounces b = launch(1.6, 80 * P);
    ASSERT_GT(b.end.size(), 60u);
    const std::size_t n = b.end.size();
    const double d1 = b.end[n - 1] - b.end[n - 2], d2 = b.end[n - 2] - b.end[n - 3], d3 = b.end[n - 3] - b.end[n - 4];
    EXPECT_GT(std::abs(d1 - d2), 0.02);
    EXPECT_NEAR(d1, d3, 1e-3);
    EXPECT_NEAR(d1 + d2, 2 * P, 1e-3);
  }
}

// The reference engine at k = 1e7 and the hard-sphere engine (k = infinity, the exact impact map
// but for the root's round-off) find the same orbits.
INSTANTIATE_TEST_SUITE_P(PlateEngines, BouncingBall, ::testing::Values(EngineKind::ReferenceLocated, EngineKind::Hard),
                         [](const auto& info) { return std::string(engine_name(info.param)) == "hard" ? std::string("hard") : std::string("reference_located"); });

namespace {

// Heights and events of a column above a plate from `driven_column_initial_state` with its seed,
// the plate's phase drawn from the same seed (as a run does), by one engine up to each sample time.
struct ColumnTrace {
  std::vector<std::vector<double>> z;
  std::size_t contact_ends = 0, floor_contacts = 0, floor_hits = 0;
};

ColumnTrace column_trace(EngineKind kind, const ChainParameters& p, const DriveSpec& drive, const std::vector<double>& times) {
  const auto floor = column_drive(p, drive, 11);
  const ChainState initial = driven_column_initial_state(p, 11, drive);
  EngineChoice choice{.kind = kind};
  choice.dt_factor = 1000.0;
  const auto engine = make_engine(choice, p, initial, floor.get());
  test_support::EventRecorder rec;
  ColumnTrace out;
  for (double t : times) {
    engine->advance_to(t, rec);
    out.z.push_back(engine->state().z);
  }
  out.contact_ends = rec.count(EventKind::ContactEnd);
  out.floor_contacts = rec.count(EventKind::FloorContact);
  out.floor_hits = rec.count(EventKind::FloorHit);
  return out;
}

}  // namespace

// The exact engine runs every plate (its grounded cluster: the mirror cluster forced by 2 (g + a_p),
// exact_plate.cpp); the reference engine is its check. A column of three on each drive: the same
// contacts with the plate and between the spheres, and heights that agree to the reference's step
// error (dt = tau_c / 1000) until the column's chaos amplifies it; a condensed column of ten
// (e = 0.5, resting on the plate between bounces): the same n_coll within the errors.
TEST(PlateDrives, ExactAgreesWithTheReferenceOnEveryPlate) {
  for (DriveKind kind : {DriveKind::Sine, DriveKind::Quadratic, DriveKind::Sawtooth}) {
    const ChainParameters p{.N = 3, .k = 1e5, .e = 0.7};
    const DriveSpec drive{kind, 0.3, 4.0};
    const std::vector<double> times{1.0, 2.0, 3.0, 4.0};
    const ColumnTrace exact = column_trace(EngineKind::Exact, p, drive, times);
    const ColumnTrace ref = column_trace(EngineKind::ReferenceLocated, p, drive, times);
    EXPECT_EQ(exact.contact_ends, ref.contact_ends) << drive_name(kind);
    EXPECT_EQ(exact.floor_contacts, ref.floor_contacts) << drive_name(kind);
    EXPECT_EQ(exact.floor_hits, ref.floor_hits) << drive_name(kind);
    EXPECT_GE(exact.floor_hits, 2u) << drive_name(kind);
    EXPECT_GE(exact.contact_ends, 5u) << drive_name(kind);
    for (std::size_t s = 0; s < times.size(); ++s)
      for (int i = 0; i < p.N; ++i) EXPECT_NEAR(exact.z[s][i], ref.z[s][i], 1e-4) << drive_name(kind) << " t=" << times[s] << " i=" << i;
  }
  for (DriveKind kind : {DriveKind::Sine, DriveKind::Quadratic, DriveKind::Sawtooth}) {
    RunSpec spec;
    spec.params = {.N = 10, .k = 1e5, .e = 0.5};
    spec.drive = {kind, kind == DriveKind::Sawtooth ? 0.1 : 2.0 / (gamma_factor(kind) * 25.0), 5.0};
    spec.T = 300;
    spec.transient = 30;
    spec.seed = 3;
    const RunResult exact = run_driven_column(spec);
    spec.engine.kind = EngineKind::ReferenceLocated;
    const RunResult ref = run_driven_column(spec);
    const double sigma = std::hypot(exact.n_coll.error, ref.n_coll.error);
    EXPECT_LT(std::abs(exact.n_coll.value - ref.n_coll.value), 3 * sigma)
        << drive_name(kind) << ": exact " << exact.n_coll.value << " reference " << ref.n_coll.value;
    EXPECT_GT(exact.floor_hits, 100u) << drive_name(kind);
  }
}

// The analysis's families are per drive: a store holding the thermal floor's run and a plate's run
// at the same (engine, N, T0, e, k) analyses them as two families, each with its own n_coll, and
// the profiles of the one never enter the other's condensation check.
TEST(PlateDrives, AnAnalysisKeepsEachDriveApart) {
  TempDir dir;
  const std::string db = dir.file("s.db");
  RunSpec spec;
  spec.params = {.N = 3, .k = 1e4, .e = 0.5};
  spec.T = 50;
  spec.transient = 5;
  RunResult thermal, plate;
  {
    ResultsStore store(db);
    thermal = run_driven_column(spec);
    store.insert_run(thermal);
    spec.drive = {DriveKind::Sine, 0.08, 5.0};
    plate = run_driven_column(spec);
    store.insert_run(plate);
  }
  ASSERT_NE(thermal.n_coll.value, plate.n_coll.value);
  const StoreAnalysis a = analyze_store(db, ExportSelection{}, 1e3);
  ASSERT_EQ(a.report.families.size(), 2u);
  for (const auto& f : a.report.families) {
    ASSERT_EQ(f.curves.size(), 1u);
    ASSERT_EQ(f.curves[0].n_coll_of_k.size(), 1u);
    EXPECT_EQ(f.curves[0].n_coll_of_k[0].y, f.drive.plate() ? plate.n_coll.value : thermal.n_coll.value);
  }
  EXPECT_TRUE(a.report.excluded.empty());
  EXPECT_EQ(a.json.at("families").size(), 2u);
  // Each family's condensation check reads its own run's profiles: one per (drive, e) here.
  EXPECT_EQ(a.condensation.size(), 2u);
}
