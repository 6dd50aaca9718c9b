// The asymptotic forms of a count y(k) (analysis/asymptotic_forms) on synthetic data with known
// Gaussian errors over k = 1e4 ... 1e13: each form is recovered when it generated the data, chi^2
// of the true form follows its distribution (also with correlated points, as paired launches give),
// pulls of the fitted exponent are standard normal, and the local-slope trend finds a planted
// drift. Fixed seeds; tolerances from the spread expected over the repetitions.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "analysis/asymptotic_forms.hpp"
#include "model/random.hpp"

using namespace granchain;
using namespace granchain::analysis;

namespace {

std::vector<double> k_grid() {
  std::vector<double> k;
  for (int d = 4; d <= 13; ++d) k.push_back(std::pow(10.0, d));
  return k;
}

// y(k) with relative error `rel` on each point, independent.
std::vector<DataPoint> synthetic(const std::function<double(double)>& y, double rel, Rng& rng) {
  std::vector<DataPoint> pts;
  for (double k : k_grid()) {
    const double sigma = rel * y(k);
    pts.push_back({k, y(k) + sigma * rng.normal(), sigma});
  }
  return pts;
}

const std::function<double(double)> kPower = [](double k) { return 3.0 * std::pow(k, 0.2); };
const std::function<double(double)> kLog = [](double k) { return 10.0 + 20.0 * std::log(k); };
const std::function<double(double)> kLogSquared = [](double k) { return 10.0 + 5.0 * std::log(k) + 0.8 * std::pow(std::log(k), 2); };
const std::function<double(double)> kPowerLog = [](double k) { return 30.0 * std::pow(k, 0.25) * std::pow(std::log(k), -1.5); };
const std::function<double(double)> kPowerOfLog = [](double k) { return 0.5 * std::pow(std::log(k), 4.0); };

// Mean chi^2 and the mean and standard deviation of the exponent's pull over repetitions.
struct PullStats {
  int count = 0;
  double chi2 = 0, pull = 0, pull2 = 0;
  void add(const FormFit& f, double alpha) {
    ++count;
    chi2 += f.chi2;
    const double z = (f.param[1] - alpha) / f.error[1];
    pull += z;
    pull2 += z * z;
  }
  double mean_chi2() const { return chi2 / count; }
  double mean_pull() const { return pull / count; }
  double pull_spread() const { return std::sqrt(pull2 / count - mean_pull() * mean_pull()); }
};

int picked(const std::function<double(double)>& y, AsymptoticForm truth, int reps, std::uint64_t seed, double rel = 0.01) {
  Rng rng(seed);
  int hits = 0;
  for (int r = 0; r < reps; ++r) {
    const FormComparison c = compare_asymptotic_forms(synthetic(y, rel, rng));
    hits += c.fits[static_cast<std::size_t>(c.best_aicc)].form == truth;
  }
  return hits;
}

}  // namespace

// Each generating form is the AICc choice. A nested form with one more parameter than the truth
// wins by chance when its chi^2 falls by more than the AICc penalty difference (4.3 at n = 10):
// P(chi^2_1 > 4.3) = 4 %, so the simple truth wins in about 96 % of 200 repetitions (at least 85 %,
// over 5 standard deviations of the binomial away); the larger forms, with their extra term well
// above the errors, win every time but for rare chance (at least 95 %). A log squared with a
// positive curvature is close to a power of ln k, which the power law with log contains
// (alpha = 0): over these nine decades the two differ by a few tenths of a percent, so that case
// is drawn with 0.1 % errors. So is a + b ln k: with a small against b ln k it is close to a power
// of ln k with beta near 1, and at 1 % errors the two 2-parameter forms tie (about half the
// repetitions each). A power of ln k is the power law with log at alpha = 0, so it wins like the
// other simple truths (at least 85 %).
TEST(AsymptoticForms, EachGeneratingFormIsRecognised) {
  EXPECT_GE(picked(kPower, AsymptoticForm::PowerLaw, 200, 11), 170);
  EXPECT_GE(picked(kLog, AsymptoticForm::Logarithm, 200, 12, 0.001), 170);
  EXPECT_GE(picked(kLogSquared, AsymptoticForm::LogSquared, 200, 13, 0.001), 190);
  EXPECT_GE(picked(kPowerLog, AsymptoticForm::PowerLawLog, 200, 14), 190);
  EXPECT_GE(picked(kPowerOfLog, AsymptoticForm::PowerOfLog, 200, 15), 170);
}

// The true form's chi^2 has mean dof = 8 and variance 16 (for the power law, fitted in ln y, up to
// terms of order the 1 % errors); the mean of 400 is within 4 standard errors (4 * 0.2) of 8. The
// exponent's pull (alpha - 0.2) / error is standard normal: its mean within 4/sqrt(400), its
// standard deviation within 1 +- 0.15.
TEST(AsymptoticForms, ChiSquareAndExponentPullsFollowTheirDistributions) {
  Rng rng(21);
  PullStats st;
  for (int r = 0; r < 400; ++r) {
    const FormFit f = compare_asymptotic_forms(synthetic(kPower, 0.01, rng)).fits[0];
    ASSERT_EQ(f.form, AsymptoticForm::PowerLaw);
    st.add(f, 0.2);
  }
  EXPECT_NEAR(st.mean_chi2(), 8.0, 0.8);
  EXPECT_NEAR(st.mean_pull(), 0.0, 0.2);
  EXPECT_NEAR(st.pull_spread(), 1.0, 0.15);
}

// Points that share a random part (the same launches at every k): y_i = y(k_i)(1 + 0.01 z_i +
// 0.01 u) with one u for the whole curve. With the full covariance the true form's chi^2 keeps
// mean dof; the exponent's pull stays standard normal.
TEST(AsymptoticForms, CorrelatedPointsAreFittedWithTheirCovariance) {
  Rng rng(31);
  const std::vector<double> k = k_grid();
  const auto n = static_cast<Eigen::Index>(k.size());
  PullStats st;
  for (int r = 0; r < 400; ++r) {
    const double u = rng.normal();
    std::vector<double> y;
    Eigen::MatrixXd C(n, n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const double yi = kPower(k[static_cast<std::size_t>(i)]);
      y.push_back(yi * (1 + 0.01 * rng.normal() + 0.01 * u));
      for (Eigen::Index j = 0; j < n; ++j)
        C(i, j) = 1e-4 * yi * kPower(k[static_cast<std::size_t>(j)]) * (i == j ? 2.0 : 1.0);
    }
    st.add(compare_asymptotic_forms(k, y, C).fits[0], 0.2);
  }
  EXPECT_NEAR(st.mean_chi2(), 8.0, 0.8);
  EXPECT_NEAR(st.mean_pull(), 0.0, 0.2);
  EXPECT_NEAR(st.pull_spread(), 1.0, 0.15);
}

TEST(AsymptoticForms, AkaikeWeightsSumToOneAndBadInputIsRefused) {
  Rng rng(41);
  const FormComparison c = compare_asymptotic_forms(synthetic(kLog, 0.01, rng));
  double sum = 0;
  for (const auto& f : c.fits) sum += f.akaike_weight;
  EXPECT_NEAR(sum, 1.0, 1e-12);
  EXPECT_EQ(c.fits.size(), 5u);
  EXPECT_THROW(compare_asymptotic_forms(std::vector<DataPoint>{{1e4, 1, 0.1}, {1e5, 2, 0.1}, {1e6, 3, 0.1}}), std::invalid_argument);
  EXPECT_THROW(compare_asymptotic_forms(std::vector<DataPoint>{{1e4, 1, 0.1}, {1e5, -2, 0.1}, {1e6, 3, 0.1}, {1e7, 4, 0.1}}),
               std::invalid_argument);
}

// Local exponents alpha_j = 0.25 - 0.012 log10 k_j with errors 0.004: the trend's slope is found
// within 4 of its errors, and the constant fit is rejected (chi^2 deviate above 3); exponents
// without drift give a slope within 4 errors of zero and a deviate below 4.
TEST(AsymptoticForms, SlopeTrendFindsAPlantedDrift) {
  Rng rng(51);
  std::vector<LocalExponent> drift, flat;
  for (int d = 4; d < 13; ++d) {
    const double k1 = std::pow(10.0, d), k2 = 10 * k1, x = d + 0.5;
    drift.push_back({k1, k2, 0.25 - 0.012 * x + 0.004 * rng.normal(), 0.004});
    flat.push_back({k1, k2, 0.2 + 0.004 * rng.normal(), 0.004});
  }
  const SlopeTrend t = slope_trend(drift), u = slope_trend(flat);
  EXPECT_NEAR(t.slope, -0.012, 4 * t.slope_error);
  EXPECT_LT(t.slope_error, 0.003);
  EXPECT_GT(t.constant_z, 3.0);
  EXPECT_NEAR(u.slope, 0.0, 4 * u.slope_error);
  EXPECT_LT(u.constant_z, 4.0);
  EXPECT_NEAR(u.mean, 0.2, 4 * u.mean_error);
}

// trend() on values y(x) with independent errors (Table 1 against log10 T0): exact values on a line
// give its slope with the error of a weighted line fit, sigma / sqrt(sum (x - mean x)^2), and a
// constant set a chi^2 of zero and a slope of zero.
TEST(AsymptoticForms, TrendOfValuesAgainstX) {
  const std::vector<double> x = {0.0, std::log10(2.0), std::log10(4.0), 1.0};
  std::vector<DataPoint> line, flat;
  for (double xi : x) {
    line.push_back({xi, 0.9 - 0.02 * xi, 0.004});
    flat.push_back({xi, 0.2, 0.01});
  }
  const SlopeTrend l = trend(line), f = trend(flat);
  double mx = 0, sxx = 0;
  for (double xi : x) mx += xi / x.size();
  for (double xi : x) sxx += (xi - mx) * (xi - mx);
  EXPECT_NEAR(l.slope, -0.02, 1e-12);
  EXPECT_NEAR(l.slope_error, 0.004 / std::sqrt(sxx), 1e-12);
  EXPECT_EQ(l.constant_dof, 3);
  EXPECT_GT(l.constant_chi2, 10.0);  // the line is far from a constant at these errors
  EXPECT_NEAR(f.mean, 0.2, 1e-15);
  EXPECT_NEAR(f.mean_error, 0.01 / 2, 1e-15);
  EXPECT_NEAR(f.constant_chi2, 0.0, 1e-20);
  EXPECT_NEAR(f.slope, 0.0, 1e-12);
  // Two values: a mean and its chi^2, no line.
  EXPECT_TRUE(std::isnan(trend({{0.0, 1.0, 0.1}, {1.0, 1.2, 0.1}}).slope));
}

// A quartic in ln k over k = 1e4 ... 1e20 with 0.5 % independent errors (as the free-space counts
// have): the quartic's chi^2 has mean dof (12 +- 0.28 over 300 curves), the pull of its leading
// coefficient is standard normal, a cubic is rejected (the counts of docs/beyond.md are told apart
// from a lower degree the same way), and too few points are refused.
TEST(AsymptoticForms, LogPolynomialOfTheTrueDegreeFitsAndLowerDegreesDoNot) {
  Rng rng(41);
  std::vector<double> k;
  for (int d = 4; d <= 20; ++d) k.push_back(std::pow(10.0, d));
  const auto quartic = [](double kk) {
    const double L = std::log(kk);
    return 5.0 + 2.0 * L + 0.3 * L * L + 0.05 * L * L * L + 0.01 * std::pow(L, 4);
  };
  const auto n = static_cast<Eigen::Index>(k.size());
  double chi2_sum = 0, pull_sum = 0, pull_sq = 0, cubic_z_min = 1e300;
  const int R = 300;
  for (int r = 0; r < R; ++r) {
    std::vector<double> y;
    Eigen::MatrixXd C = Eigen::MatrixXd::Zero(n, n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const double yi = quartic(k[static_cast<std::size_t>(i)]), s = 0.005 * yi;
      y.push_back(yi + s * rng.normal());
      C(i, i) = s * s;
    }
    const LogPolynomialFit f4 = fit_log_polynomial(k, y, C, 4);
    ASSERT_EQ(f4.dof, 12);
    chi2_sum += f4.chi2;
    const double pull = (f4.leading - 0.01) / f4.leading_error;
    pull_sum += pull, pull_sq += pull * pull;
    cubic_z_min = std::min(cubic_z_min, fit_log_polynomial(k, y, C, 3).chi2_z);
  }
  EXPECT_NEAR(chi2_sum / R, 12.0, 1.0);
  EXPECT_NEAR(pull_sum / R, 0.0, 0.2);
  EXPECT_NEAR(std::sqrt(pull_sq / R - std::pow(pull_sum / R, 2)), 1.0, 0.15);
  EXPECT_GT(cubic_z_min, 5.0);
  EXPECT_THROW(fit_log_polynomial({1e4, 1e5, 1e6}, {1, 2, 3}, Eigen::MatrixXd::Identity(3, 3), 2), std::invalid_argument);
}
