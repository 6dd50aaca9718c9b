// The driven column run by the reference engine, against exact results.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "simulation/driven_run.hpp"
#include "store/run_json.hpp"
#include "theory/equilibrium_column.hpp"
#include "test_helpers.hpp"

using namespace granchain;
using granchain::test_support::z_score;

namespace {

RunSpec spec_for(int N, double e, double k, double T, std::uint64_t seed) {
  RunSpec s;
  s.params.N = N;
  s.params.e = e;
  s.params.k = k;
  s.T = T;
  s.transient = 100.0;
  s.seed = seed;
  return s;
}

// Every profile and the collision rates of a run against the exact e = 1 equilibrium, within 4
// standard errors.
void expect_gibbs_equilibrium(const RunResult& r, const ElasticColumnEquilibrium& eq) {
  for (int i = 0; i < r.spec.params.N; ++i) {
    const ParticleProfile& q = r.profiles[i];
    EXPECT_LT(z_score(q.z_mean.value, q.z_mean.error, eq.z_mean[i]), 4.0) << "particle " << i + 1;
    EXPECT_LT(z_score(q.z_std.value, q.z_std.error, eq.z_std[i]), 4.0) << "particle " << i + 1;
    EXPECT_LT(z_score(q.kinetic.value, q.kinetic.error, eq.kinetic), 4.0) << "particle " << i + 1;
  }
  EXPECT_LT(z_score(r.floor_rate.value, r.floor_rate.error, eq.floor_rate), 4.0);
  double pair_rate = 0;
  for (double x : eq.contact_end_rate) pair_rate += x;
  EXPECT_LT(z_score(r.pp_rate.value, r.pp_rate.error, pair_rate), 4.0);
  EXPECT_LT(z_score(r.n_coll.value, r.n_coll.error, eq.n_coll), 4.0);
}

}  // namespace

// One particle on the thermal floor is in equilibrium at kT0 (the floor is a heat bath): the
// barometric law gives <z> = d/2 + kT0/(mg) and sigma = kT0/(mg) (the floor touches the lower
// edge: a centre-touching floor would give <z> = kT0/(mg)), equipartition K = kT0/2, and the
// floor is hit at the rate 1/<2v/g> = g sqrt(m / (2 pi kT0)).
TEST(DrivenColumn, SingleParticleIsBarometric) {
  RunSpec s = spec_for(1, 0.9, 100.0, 2e4, 3);
  s.params.kT0 = 2.0;
  s.params.g = 1.5;
  s.params.d = 0.8;
  const RunResult r = run_driven_column(s);
  const double h = s.params.kT0 / (s.params.m * s.params.g);
  EXPECT_LT(z_score(r.profiles[0].z_mean.value, r.profiles[0].z_mean.error, 0.5 * s.params.d + h), 4.0);
  EXPECT_LT(z_score(r.profiles[0].z_std.value, r.profiles[0].z_std.error, h), 4.0);
  EXPECT_LT(z_score(r.profiles[0].kinetic.value, r.profiles[0].kinetic.error, 0.5 * s.params.kT0), 4.0);
  const double rate = s.params.g * std::sqrt(s.params.m / (2 * std::numbers::pi * s.params.kT0));
  EXPECT_LT(z_score(r.floor_rate.value, r.floor_rate.error, rate), 4.0);
  EXPECT_EQ(r.n_coll.value, r.floor_rate.value);  // N = 1: floor hits are all the collisions
  EXPECT_EQ(r.particle_collisions, 0u);
}

// The error bars must be right, not only the values. Floor hits of one particle form a renewal
// process with flight times tau = 2v/g; its rate has the standard error sqrt(var(tau) / (<tau>^3 T)).
// <v> = sqrt(pi/2) s, var(v) = (2 - pi/2) s^2 with s^2 = kT0/m.
TEST(DrivenColumn, FloorRateErrorMatchesRenewalTheory) {
  const RunSpec s = spec_for(1, 0.9, 100.0, 4e4, 4);
  const RunResult r = run_driven_column(s);
  const double mean_tau = 2.0 * std::sqrt(std::numbers::pi / 2);
  const double var_tau = 4.0 * (2.0 - std::numbers::pi / 2);
  const double exact_se = std::sqrt(var_tau / (mean_tau * mean_tau * mean_tau * s.T));
  // The blocked SE scatters by 1/sqrt(2(n_blocks - 1)) <= 18%; allow 3 of those.
  EXPECT_NEAR(r.floor_rate.error, exact_se, 3 * 0.18 * exact_se);
  EXPECT_TRUE(r.floor_rate.converged);
}

// Calibration over independent seeds: the z-scores of 16 runs against exact values must have a
// mean square near 1 (chi^2 with 16 degrees of freedom / 16 lies in [0.35, 2.0] with
// probability > 99%).
TEST(DrivenColumn, ErrorBarsAreCalibratedAcrossSeeds) {
  double chi2_rate = 0, chi2_z = 0;
  const int R = 16;
  for (int seed = 1; seed <= R; ++seed) {
    const RunResult r = run_driven_column(spec_for(1, 0.9, 100.0, 3000.0, 100 + seed));
    const double zr = (r.floor_rate.value - 1.0 / std::sqrt(2 * std::numbers::pi)) / r.floor_rate.error;
    const double zz = (r.profiles[0].z_mean.value - 1.5) / r.profiles[0].z_mean.error;
    chi2_rate += zr * zr;
    chi2_z += zz * zz;
  }
  EXPECT_GT(chi2_rate / R, 0.35);
  EXPECT_LT(chi2_rate / R, 2.0);
  EXPECT_GT(chi2_z / R, 0.35);
  EXPECT_LT(chi2_z / R, 2.0);
}

// e = 1: the column samples the exact Gibbs equilibrium of theory/equilibrium_column.hpp.
// Heights, widths, K_i = kT0/2, the floor rate and every collision rate agree within 4
// standard errors (the scheme's own bias at dt = tau_c/100 is ~1e-4, far below them).
TEST(DrivenColumn, ElasticColumnIsInGibbsEquilibrium) {
  const RunSpec s = spec_for(3, 1.0, 1e4, 2e4, 7);
  const RunResult r = run_driven_column(s);
  const ElasticColumnEquilibrium eq = elastic_column_equilibrium(s.params);
  expect_gibbs_equilibrium(r, eq);
  // The errors are small enough for this to be a sharp test: 2% on n_coll or better.
  EXPECT_LT(r.n_coll.error, 0.02 * eq.n_coll);
}

// The hard-sphere engine (k = infinity) samples the k -> infinity limit of the same Gibbs measure:
// exponential gaps of mean kT0 / W_j and the hard-rod collision rates.
TEST(DrivenColumn, HardSphereElasticColumnIsInGibbsEquilibrium) {
  RunSpec s = spec_for(3, 1.0, std::numeric_limits<double>::infinity(), 2e4, 7);
  s.engine.kind = EngineKind::Hard;
  const RunResult r = run_driven_column(s);
  ChainParameters hard_limit = s.params;
  hard_limit.k = 1e14;  // the equilibrium integrals at k = 1e14 differ from k = infinity by ~1e-7
  const ElasticColumnEquilibrium eq = elastic_column_equilibrium(hard_limit);
  expect_gibbs_equilibrium(r, eq);
  EXPECT_LT(r.n_coll.error, 0.02 * eq.n_coll);
  EXPECT_EQ(r.law.tau_c, 0.0);
}

// Dissipation far from collapse (N(1-e) = 0.5 << 2.6): energy enters at the floor and is lost on
// the way up, so every K_i lies below kT0/2 and K_i falls with height (paper Sec. III.C.2).
TEST(DrivenColumn, DissipativeColumnCoolsUpward) {
  const RunResult r = run_driven_column(spec_for(5, 0.9, 1e4, 5e3, 9));
  for (int i = 0; i < 5; ++i) EXPECT_LT(r.profiles[i].kinetic.value + 3 * r.profiles[i].kinetic.error, 0.5);
  for (int i = 0; i + 1 < 5; ++i) {
    const double a = r.profiles[i].kinetic.value, b = r.profiles[i + 1].kinetic.value;
    const double err = std::hypot(r.profiles[i].kinetic.error, r.profiles[i + 1].kinetic.error);
    EXPECT_GT(a - b, -2 * err) << "particles " << i + 1 << ", " << i + 2;
  }
  EXPECT_GT(r.profiles[0].kinetic.value - r.profiles[4].kinetic.value, 0.0);
}

// The same seed and parameters give bit-identical results on the same build; another seed does not.
TEST(DrivenColumn, BitIdenticalFromSeed) {
  const RunSpec s = spec_for(6, 0.7, 1e4, 200.0, 21);
  auto physics = [](const RunResult& r) {
    nlohmann::json j = run_result_to_json(r);
    j.erase("cost");
    return j.dump();
  };
  const std::string a = physics(run_driven_column(s));
  const std::string b = physics(run_driven_column(s));
  EXPECT_EQ(a, b);
  RunSpec other = s;
  other.seed = 22;
  EXPECT_NE(a, physics(run_driven_column(other)));
}

// Long validation (ctest -L long): a heavier elastic column, N = 10 at k = 1e5, where the
// weight on the lowest contacts is 9 m g and the soft-overlap corrections to the hard-rod
// equilibrium are visible; every profile and rate within 4 standard errors of the exact result.
// The stationarity check on real runs: N = 25, e = 0.5 from its initial state with a window of
// [0.2, 2.2] (the column is still falling onto the floor: n_coll and the mean height change
// between the halves by many errors) is flagged; the same column after a transient of 20 with a
// window of 100 passes.
TEST(DrivenColumn, UnsettledWindowIsFlaggedAndSettledOnePasses) {
  RunSpec s = spec_for(25, 0.5, 1e5, 2.0, 1);
  s.transient = 0.2;
  const RunResult early = run_driven_column(s);
  EXPECT_FALSE(early.stationary());
  EXPECT_FALSE(early.height_halves.stationary) << early.height_halves.z;
  s.T = 100.0;
  s.transient = 20.0;
  const RunResult settled = run_driven_column(s);
  EXPECT_TRUE(settled.stationary()) << settled.n_coll_halves.z << " " << settled.height_halves.z;
}

TEST(LongDrivenColumn, ElasticTenParticleColumnIsInGibbsEquilibrium) {
  RunSpec s = spec_for(10, 1.0, 1e5, 2e4, 17);
  s.transient = 1000.0;
  const RunResult r = run_driven_column(s);
  expect_gibbs_equilibrium(r, elastic_column_equilibrium(s.params));
  EXPECT_TRUE(r.n_coll.converged);
}
