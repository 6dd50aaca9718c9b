// The fine structure of n_coll(e) (analysis/fine_structure) on synthetic curves sampled on the
// small-N figures' e grid: planted peaks, dips and a broad peak are found where they were put,
// pure noise gives false extrema at the rate the bivariate normal predicts, replicas of one curve
// agree by chi^2, and growth per decade of k is measured with calibrated errors (fixed seeds;
// tolerances from the expected spread).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "analysis/fine_structure.hpp"
#include "model/random.hpp"
#include "theory/collapse_theory.hpp"

using namespace granchain;
using namespace granchain::analysis;

namespace {

// The small-N figures' grid: 0.05 ... 1.0 by 0.05 and e_c(n) + {0, +-0.005, +-0.01}, n = 3 ... 7.
std::vector<double> small_n_grid() {
  std::set<double> e;
  for (int i = 1; i <= 20; ++i) e.insert(0.05 * i);
  for (int n = 3; n <= 7; ++n)
    for (double d : {-0.01, -0.005, 0.0, 0.005, 0.01}) e.insert(std::round((theory::ec_free(n) + d) * 1e4) / 1e4);
  return {e.begin(), e.end()};
}

template <class F>
std::vector<DataPoint> sample(F y_of_e, double sigma, Rng& rng) {
  std::vector<DataPoint> c;
  for (double e : small_n_grid()) c.push_back({e, y_of_e(e) + sigma * rng.normal(), sigma});
  return c;
}

double normal_tail(double x) { return 0.5 * std::erfc(x / std::sqrt(2.0)); }

// P(X > t, Y > t) for standard normals with correlation rho, by quadrature over X.
double both_above(double t, double rho) {
  double p = 0;
  const double h = 1e-3;
  for (double x = t + 0.5 * h; x < t + 12; x += h) {
    const double phi = std::exp(-0.5 * x * x) / std::sqrt(2 * M_PI);
    p += h * phi * normal_tail((t - rho * x) / std::sqrt(1 - rho * rho));
  }
  return p;
}

bool near(double a, double b) { return std::abs(a - b) < 1e-9; }

}  // namespace

// On a flat curve with equal errors each interior point's two differences from its neighbours are
// normal with correlation 1/2, so a point is a false peak (or dip) at threshold z with probability
// P(X > z, Y > z | rho = 1/2). Over many curves the count of false extrema lies around that
// expectation within 4 of its Poisson standard deviations, at z = 2 and at the analysis's z = 3.
TEST(FineStructure, FalseExtremaOnPureNoiseOccurAtThePredictedRate) {
  Rng rng(5);
  for (const auto& [z, curves] : {std::pair{2.0, 1000}, std::pair{3.0, 5000}}) {
    int found = 0;
    std::size_t interior = 0;
    for (int c = 0; c < curves; ++c) {
      const auto curve = sample([](double) { return 5.0; }, 0.1, rng);
      interior += curve.size() - 2;
      found += static_cast<int>(significant_extrema(curve, z).size());
    }
    const double expected = 2.0 * static_cast<double>(interior) * both_above(z, 0.5);
    EXPECT_GT(expected, 25.0);
    EXPECT_LT(std::abs(found - expected), 4.0 * std::sqrt(expected)) << "z = " << z << ": found " << found << ", expected " << expected;
  }
}

// A sharp peak of 8 sigma at e_c(3), a dip of 8 sigma at e_c(4) + 0.01 and a broad bump of
// 30 sigma and width 0.03 at e_c(5) on a falling baseline (N = 4). Each is missed with probability
// about 2 Phi(-(8/sqrt(2) - 3)) = 0.8 %, so over 200 curves each is found at least 190 times; the
// broad bump counts as the broad peak near e_c(N + 1), within the refined window around its centre
// (the baseline's slope moves the bump's top and the noise picks among the flat samples there).
TEST(FineStructure, PlantedPeakDipAndBroadPeakAreFoundWhereTheyWerePut) {
  Rng rng(17);
  const double s = 0.05, e3 = theory::ec_free(3), e4 = theory::ec_free(4), e5 = theory::ec_free(5);
  const auto grid = small_n_grid();
  const double dip_at = *std::min_element(grid.begin(), grid.end(), [&](double a, double b) {
    return std::abs(a - (e4 + 0.01)) < std::abs(b - (e4 + 0.01));
  });
  int peaks = 0, dips = 0, broads = 0, misplaced = 0;
  for (int c = 0; c < 200; ++c) {
    const auto curve = sample(
        [&](double e) {
          double y = 10.0 - 6.0 * e;
          if (std::abs(e - e3) < 1e-4) y += 8 * s;
          if (near(e, dip_at)) y -= 8 * s;
          return y + 30 * s * std::exp(-0.5 * std::pow((e - e5) / 0.03, 2));
        },
        s, rng);
    const FineStructure fs = find_fine_structure(4, curve);
    ASSERT_EQ(fs.at_critical.size(), 3u);  // n = 3, 4, 5
    for (const auto& x : fs.at_critical[0].extrema) peaks += x.kind == ExtremumKind::Peak && std::abs(x.x - e3) < 1e-3;
    for (const auto& x : fs.at_critical[1].extrema) dips += x.kind == ExtremumKind::Dip && near(x.x, dip_at);
    broads += fs.near_next.found && std::abs(fs.near_next.x - e5) <= 0.0105;
    for (const auto& x : fs.at_critical[0].extrema) misplaced += x.kind == ExtremumKind::Dip;
  }
  EXPECT_GE(peaks, 190);
  EXPECT_GE(dips, 190);
  EXPECT_GE(broads, 190);
  EXPECT_LE(misplaced, 5);  // a dip next to a planted peak is noise at the false rate
}

// A steeply falling curve (4 sigma between the closest samples) has no extremum and no broad peak.
TEST(FineStructure, MonotoneCurveHasNoBroadPeak) {
  Rng rng(3);
  const auto curve = sample([](double e) { return 10.0 - 8.0 * e; }, 0.01, rng);
  EXPECT_FALSE(broad_peak(curve, theory::ec_free(6), 0.05).found);
  EXPECT_TRUE(significant_extrema(curve, 3.0).empty());
}

// Two replicas of one curve: chi2_z over 300 pairs has mean 0 and standard deviation 1 to within
// 4 sampling errors (1/sqrt(300), 1/sqrt(600)); a replica shifted by 2 sigma everywhere (the
// difference per point is 2/sqrt(2) of its error, chi2/dof about 3) is rejected; a planted peak in
// both recurs.
TEST(FineStructure, ReplicasOfOneCurveAgreeAndAShiftedOneDoesNot) {
  Rng rng(23);
  const double s = 0.05, e3 = theory::ec_free(3);
  auto shape = [&](double e) { return 8.0 - 4.0 * e + (std::abs(e - e3) < 1e-4 ? 10 * s : 0.0); };
  double sum = 0, sum2 = 0;
  const int pairs = 300;
  int recurred = 0, planted = 0;
  for (int i = 0; i < pairs; ++i) {
    const auto a = sample(shape, s, rng), b = sample(shape, s, rng);
    const ReplicaAgreement r = compare_replicas(a, b);
    EXPECT_EQ(r.dof, static_cast<int>(a.size()));
    sum += r.chi2_z;
    sum2 += r.chi2_z * r.chi2_z;
    for (const auto& x : significant_extrema(a, 3.0)) planted += std::abs(x.x - e3) < 1e-3;
    recurred += r.recurring_in_b;
  }
  const double mean = sum / pairs, sd = std::sqrt(sum2 / pairs - mean * mean);
  EXPECT_LT(std::abs(mean), 4.0 / std::sqrt(pairs));
  EXPECT_LT(std::abs(sd - 1.0), 4.0 / std::sqrt(2.0 * pairs));
  EXPECT_GE(recurred, planted - 3);  // the planted peak recurs; chance extrema of a rarely do
  const auto a = sample(shape, s, rng);
  auto b = sample(shape, s, rng);
  for (auto& p : b) p.y += 2 * s;
  EXPECT_GT(compare_replicas(a, b).chi2_z, 5.0);
}

// y = a + b log10 k has constant increments b per decade; with noise the pull of rising_z is
// standard normal, for two increments (which share a sample) and for five; (log10 k)^2 rises.
TEST(FineStructure, GrowthPerDecadeIsConstantForLogAndRisesFasterThanLog) {
  Rng rng(29);
  for (const std::vector<double>& ks : {std::vector<double>{1e5, 1e6, 1e7}, std::vector<double>{1e5, 1e6, 1e7, 1e8, 1e9, 1e10}}) {
    double sum = 0, sum2 = 0;
    const int sets = 2000;
    for (int i = 0; i < sets; ++i) {
      std::vector<DataPoint> y;
      for (double k : ks) y.push_back({k, 2.0 + 0.7 * std::log10(k) + 0.05 * rng.normal(), 0.05});
      const GrowthPerDecade g = growth_per_decade(y);
      ASSERT_EQ(g.increments.size(), ks.size() - 1);
      sum += g.rising_z;
      sum2 += g.rising_z * g.rising_z;
    }
    const double mean = sum / sets, sd = std::sqrt(sum2 / sets - mean * mean);
    EXPECT_LT(std::abs(mean), 4.0 / std::sqrt(sets));
    EXPECT_LT(std::abs(sd - 1.0), 4.0 / std::sqrt(2.0 * sets)) << ks.size() << " values of k";
  }
  std::vector<DataPoint> y;
  for (double k : {1e5, 1e6, 1e7, 1e8}) y.push_back({k, 0.1 * std::pow(std::log10(k), 2), 0.01});
  const GrowthPerDecade g = growth_per_decade(y);
  EXPECT_NEAR(g.increments.front().dy, 0.1 * (36 - 25), 1e-12);
  EXPECT_GT(g.rising_z, 10.0);
}
