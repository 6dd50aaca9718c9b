// The exact engine against the reference engine on statistics: driven runs on a grid of (N, e, k),
// a large condensed column, and free-space collapses at high stiffness (all labelled long). The
// deterministic comparisons with the converged reference are in test_exact_engine.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <cstdio>
#include <fmt/format.h>
#include <string>
#include <vector>

#include "simulation/collapse_run.hpp"
#include "simulation/driven_run.hpp"

using namespace granchain;

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
// 8 replicas, z is close to Student's t with 7 degrees of freedom, whose tails are heavy: |z| > 3
// has probability 0.02 per cell, so over the 12 cells a 3-sigma rule would fail one run in five
// with nothing wrong. The n_coll criterion is set for a false alarm of 1 % over the whole grid
// (Bonferroni: two-sided 1e-2 / 12 per cell of t with 7 degrees of freedom, |z| < 5.58).
// Prints the table.
namespace {

constexpr int kReplicas = 8;

RunResult grid_run(int N, double e, double k, const std::string& engine, double dt_factor, std::uint64_t seed) {
  RunSpec spec;
  spec.params = ChainParameters{.N = N, .k = k, .e = e};
  spec.engine = EngineChoice{.kind = find_engine(engine)->kind, .dt_factor = dt_factor};
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

// Student's t distribution with 7 degrees of freedom: P(T <= t) in closed form (odd degrees:
// 1/2 + (theta + sin theta (cos theta + 2/3 cos^3 theta + 8/15 cos^5 theta)) / pi, tan theta =
// t / sqrt 7), and its quantile by bisection (tests only).
double student7_cdf(double t) {
  const double th = std::atan(t / std::sqrt(7.0)), c = std::cos(th);
  return 0.5 + (th + std::sin(th) * (c + 2.0 / 3.0 * c * c * c + 8.0 / 15.0 * c * c * c * c * c)) / std::numbers::pi;
}
double student7_quantile(double p) {
  double lo = -100, hi = 100;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (student7_cdf(mid) < p ? lo : hi) = mid;
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
  const double z_cell = student7_quantile(1.0 - 0.5 * 1e-2 / 12);  // 1 % over the 12 cells: 5.58
  EXPECT_NEAR(student7_cdf(2.998), 0.99, 1e-4);                     // the t(7) table's 99th percentile
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
        EXPECT_LT(std::abs(z_loc), z_cell) << "N=" << N << " e=" << e << " k=" << k;
        EXPECT_LT(zmax, zbound) << "N=" << N << " e=" << e << " k=" << k;
      }
    }
  }
}

// Long: a large condensed column, where the exact engine projects its clusters (up to 150
// particles) through FFTW's sine transform: N = 150, e = 0.1 (power-law regime) at k = 1e5, 1e6
// and 1e7, transient 30, window T = 20, four independent seeds per engine. The reference is the
// paper's scheme at dt = tau_c / 1000 (ten times finer than the paper's; tau_c / 300 at k = 1e7,
// where its O(dt^2) bias in the restitution, ~1e-5, is still far below the statistical errors of
// ~1 %). For each of n_coll, the floor rate, and the column's mean height, mean thickness and
// kinetic energy (profile values averaged over the particles), the error of a mean is the spread
// of its four runs over sqrt(4), and z = difference / combined error is close to Student's t with
// 6 degrees of freedom: |z| > 4 has probability 0.007 per quantity.
// (The instantiation's prefix "Long" puts it under the long label.)
class LargeCondensedColumn : public ::testing::TestWithParam<double> {};

TEST_P(LargeCondensedColumn, AgreesWithReference) {
  const double k = GetParam();
  constexpr int kSeeds = 4;
  auto run = [k](const std::string& engine, std::uint64_t seed) {
    RunSpec spec;
    spec.params = ChainParameters{.N = 150, .k = k, .e = 0.1};
    spec.engine = EngineChoice{.kind = find_engine(engine)->kind, .dt_factor = k > 1e6 ? 300.0 : 1000.0};
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
    EXPECT_LT(std::abs(z), 4.0) << names[q] << " at k = " << k;
  }
}

INSTANTIATE_TEST_SUITE_P(Long, LargeCondensedColumn, ::testing::Values(1e5, 1e6, 1e7),
                         [](const ::testing::TestParamInfo<double>& info) {
                           return "k1e" + std::to_string(static_cast<int>(std::lround(std::log10(info.param))));
                         });


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
  s.engine.kind = EngineKind::Reference;
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
