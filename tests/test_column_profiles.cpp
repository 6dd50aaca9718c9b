// The classical observables of a vibrated column (analysis/column_profiles.hpp) on trajectories
// whose answer is known: an elastic column on the thermal floor is in equilibrium (barometric
// density, one temperature kT0 at every height), and a sphere resting on a plate below Gamma = 1
// moves with the plate.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "analysis/column_profiles.hpp"
#include "model/plate_motion.hpp"
#include "simulation/trajectory.hpp"
#include "theory/equilibrium_column.hpp"

using namespace granchain;

namespace {

TraceSpec elastic_column(int N, double from, double to, double dt) {
  TraceSpec spec;
  spec.run.params.N = N;
  spec.run.params.e = 1.0;
  spec.run.params.k = 1e6;
  spec.run.seed = 7;
  spec.t_from = from;
  spec.t_to = to;
  spec.dt = dt;
  return spec;
}

}  // namespace

// The first harmonic of a pure cosine sampled at bin centres is exact: f0 + a cos(theta - phi)
// gives amplitude a and phase phi; its errors follow from the bins'.
TEST(ColumnProfiles, FirstHarmonicOfASampledCosine) {
  std::vector<double> theta;
  std::vector<analysis::BinnedValue> f;
  for (int b = 0; b < 24; ++b) {
    theta.push_back((b + 0.5) * 2 * std::numbers::pi / 24);
    f.push_back({2.0 + 0.3 * std::cos(theta.back() - 1.0), 0.01, true});
  }
  const analysis::Harmonic h = analysis::first_harmonic(theta, f);
  ASSERT_TRUE(h.measured);
  EXPECT_NEAR(h.amplitude, 0.3, 1e-12);
  EXPECT_NEAR(h.phase, 1.0, 1e-12);
  EXPECT_NEAR(h.amplitude_error, 0.01 * std::sqrt(2.0 / 24), 1e-12);  // (2/n) sqrt(n/2) sigma
  EXPECT_NEAR(h.phase_error, 0.01 * std::sqrt(2.0 / 24) / 0.3, 1e-12);
  f[3].measured = false;
  EXPECT_FALSE(analysis::first_harmonic(theta, f).measured);
}

// One elastic sphere on the thermal floor (a heat bath for e = 1): the density of its height is
// barometric, (m g / kT0) exp(-m g (z - d/2) / kT0), and its temperature kT0 at every height.
// Each bin against the bin average of that density, within 4 batch-means errors (20 blocks of
// 500 flights each); the integral is 1 up to the part above the bins.
TEST(ColumnProfiles, AnElasticSphereOnTheThermalFloorIsBarometricWithOneTemperature) {
  const TraceSpec spec = elastic_column(1, 10, 20010, 0.02);
  const Trajectory tr = record_trajectory(spec);
  const double w = 0.25, z0 = 0.5;
  const int bins = 24;  // to 6.5: exp(-6) of the density above
  const analysis::HeightProfiles h = analysis::height_profiles(tr.z, tr.v, 1.0, z0, w, bins, 20);
  double integral = 0;
  for (int b = 0; b < bins; ++b) {
    const double s0 = b * w, s1 = s0 + w;
    const double expected = (std::exp(-s0) - std::exp(-s1)) / w;
    ASSERT_TRUE(h.density[b].measured) << b;
    EXPECT_LT(std::abs(h.density[b].value - expected), 4 * h.density[b].error) << "bin " << b << ": " << h.density[b].value << " vs " << expected;
    integral += h.density[b].value * w;
    if (b < 12) {  // below z = 3.5, where every block has samples
      ASSERT_TRUE(h.temperature[b].measured) << b;
      EXPECT_LT(std::abs(h.temperature[b].value - 1.0), 4 * h.temperature[b].error) << "bin " << b << ": T = " << h.temperature[b].value;
      EXPECT_LT(h.temperature[b].error, 0.08) << b;  // the test has power: a 30 % error in T would show
    }
  }
  EXPECT_NEAR(integral + h.outside, 1.0, 1e-12);
  EXPECT_NEAR(h.outside, std::exp(-6.0), 4 * 0.003);
}

// An elastic column of three: the density integrates to N and its first moment is the sum of the
// equilibrium <z_i> (theory/equilibrium_column.hpp); one temperature kT0 wherever measured.
TEST(ColumnProfiles, AnElasticColumnOfThreeHasItsEquilibriumHeightsAndOneTemperature) {
  const TraceSpec spec = elastic_column(3, 10, 3010, 0.02);
  const Trajectory tr = record_trajectory(spec);
  const ElasticColumnEquilibrium eq = elastic_column_equilibrium(spec.run.params);
  const double w = 0.25;
  const analysis::HeightProfiles h = analysis::height_profiles(tr.z, tr.v, 1.0, 0.0, w, 60, 20);
  double integral = 0, moment = 0;
  for (std::size_t b = 0; b < h.z.size(); ++b) {
    integral += h.density[b].value * w;
    moment += h.density[b].value * w * h.z[b];
    if (h.temperature[b].measured && h.z[b] < 4.0)
      EXPECT_LT(std::abs(h.temperature[b].value - 1.0), 4 * h.temperature[b].error) << "z = " << h.z[b];
  }
  EXPECT_NEAR(integral + 3 * h.outside, 3.0, 1e-12);
  double expected = 0;
  for (double z : eq.z_mean) expected += z;
  std::vector<double> sum;
  for (const auto& s : tr.z) sum.push_back(s[0] + s[1] + s[2]);
  const analysis::BinnedValue direct = analysis::batch_mean(sum, 20);
  EXPECT_LT(std::abs(direct.value - expected), 4 * direct.error) << direct.value << " vs " << expected;
  // The binned first moment differs from the direct one by the bins' rounding only (w^2 / 12 per
  // particle in the variance, nothing in the mean of a smooth density to first order).
  EXPECT_NEAR(moment, direct.value, 0.05);
}

// A sphere resting on a sinusoidal plate (Gamma = 0.5 < 1) moves with it: through the cycle its
// height is the surface's plus d/2 minus the contact's compression m (g + a_p) / 2k, its velocity
// the surface's; the first harmonics agree in amplitude and phase.
TEST(ColumnProfiles, ASphereRestingOnAPlateFollowsItThroughTheCycle) {
  TraceSpec spec;
  spec.run.params.N = 1;
  spec.run.params.e = 0.5;
  spec.run.params.k = 1e6;
  spec.run.drive = {DriveKind::Sine, 0.5 / 100.0, 10.0};  // Gamma = A omega^2 / g = 0.5
  spec.run.seed = 3;
  spec.t_from = 20;  // settled: the drop from z = A has long been damped
  spec.t_to = 80;
  spec.dt = 0.003;
  const Trajectory tr = record_trajectory(spec);
  const analysis::PhaseProfiles p = analysis::phase_profiles(tr.z, tr.v, tr.plate_phase, tr.plate, tr.plate_v, 24, 10);
  const double compression_max = (1.0 + 0.5) / (2 * 1e6);
  for (std::size_t b = 0; b < p.theta.size(); ++b) {
    ASSERT_TRUE(p.z_cm[b].measured);
    const double gap = p.z_cm[b].value - p.z_plate[b].value - 0.5;
    EXPECT_LE(gap, 0.0) << b;
    EXPECT_GE(gap, -compression_max) << b;
    EXPECT_NEAR(p.v_cm[b].value, p.v_plate[b].value, 1e-4) << b;
  }
  const analysis::Harmonic hz = analysis::first_harmonic(p.theta, p.z_cm), hp = analysis::first_harmonic(p.theta, p.z_plate);
  EXPECT_NEAR(hz.amplitude / hp.amplitude, 1.0, 1e-3);
  EXPECT_NEAR(std::remainder(hz.phase - hp.phase, 2 * std::numbers::pi), 0.0, 1e-3);
}
