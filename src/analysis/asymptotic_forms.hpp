#pragma once
// Which asymptotic form does a count y(k) follow as k grows? (n_coll or n_tot against k: the
// paper's question whether n ~ k^alpha is a power law, Sec. III.C and Summary.) Five candidate
// forms, each linear in its parameters after a transformation, fitted by generalised least squares
// with the full covariance of the points (counts of the same free-space launches at every k are
// correlated; independent runs have a diagonal covariance):
//   power law            y = c k^alpha                   (ln y = a + alpha ln k)
//   logarithm            y = a + b ln k
//   log squared          y = a + b ln k + c (ln k)^2
//   power law with log   y = c k^alpha (ln k)^beta       (ln y = a + alpha ln k + beta ln ln k)
//   power of log         y = c (ln k)^beta               (ln y = a + beta ln ln k: the same with alpha = 0)
// The power forms are fitted in ln y with the covariance propagated (C_ij / (y_i y_j)); every
// form's chi^2 is then evaluated on y itself, r^T C^-1 r with r = y - model, so the five are
// compared on the same footing: AICc = chi^2 + 2p + 2p(p+1)/(n-p-1) and BIC = chi^2 + p ln n
// (Gaussian likelihood with known errors, constants dropped), and Akaike weights exp(-dAICc/2).
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "analysis/collapse_regimes.hpp"

namespace granchain::analysis {

enum class AsymptoticForm { PowerLaw, Logarithm, LogSquared, PowerLawLog, PowerOfLog };
const char* form_name(AsymptoticForm f);     // "power law", "a + b ln k", ...
const char* form_formula(AsymptoticForm f);  // "y = c k^alpha", ...
inline constexpr AsymptoticForm kAsymptoticForms[] = {AsymptoticForm::PowerLaw, AsymptoticForm::Logarithm,
                                                      AsymptoticForm::LogSquared, AsymptoticForm::PowerLawLog,
                                                      AsymptoticForm::PowerOfLog};

struct FormFit {
  AsymptoticForm form = AsymptoticForm::PowerLaw;
  // Parameters in the order of the formula: (ln c, alpha), (a, b), (a, b, c), (ln c, alpha, beta),
  // (ln c, beta);
  // standard errors from the covariance (not rescaled by chi^2: the comparison needs them raw).
  std::vector<double> param, error;
  double chi2 = 0;
  int dof = 0;
  double chi2_z = 0;  // normal deviate of chi^2 with dof degrees of freedom (Wilson-Hilferty)
  double aicc = 0, bic = 0, akaike_weight = 0;
  std::vector<double> model;  // the fitted y at each point
  std::vector<double> pulls;  // (y - model) / sigma_y at each point
};

struct FormComparison {
  std::vector<FormFit> fits;  // in kAsymptoticForms order; a form with too few points is absent
  int best_aicc = -1, best_bic = -1;  // indices into fits
};

// x = k (> 0), y (> 0) and the covariance of y (positive definite). At least 4 points (a form
// needs one point more than it has parameters). Throws std::invalid_argument.
FormComparison compare_asymptotic_forms(const std::vector<double>& k, const std::vector<double>& y,
                                        const Eigen::MatrixXd& covariance);
// Independent points (diagonal covariance from the errors).
FormComparison compare_asymptotic_forms(const std::vector<DataPoint>& y_of_k);

// A polynomial in ln k of the given degree, y = sum_j c_j (ln k)^j, j = 0 .. degree, fitted with the
// covariance of the points (generalised least squares): the count of a hierarchy of collapses nested
// `degree` deep (docs/beyond.md) grows so, with no power of k. leading = c_degree and its error;
// chi2, dof, its normal deviate, AICc and BIC as for the forms above. Needs degree + 2 points.
// Throws std::invalid_argument.
struct LogPolynomialFit {
  int degree = 0;
  double leading = 0, leading_error = 0;
  double chi2 = 0;
  int dof = 0;
  double chi2_z = 0, aicc = 0, bic = 0;
};
LogPolynomialFit fit_log_polynomial(const std::vector<double>& k, const std::vector<double>& y, const Eigen::MatrixXd& covariance, int degree);

// The covariance of the means of several quantities measured on the same samples (the counts of
// the same launches at every k): samples[r][i] is quantity i in sample r; C_ij = cov_r(x_i, x_j) / R
// (sample covariance, R - 1 in its denominator). At least 2 samples, all of one length.
Eigen::MatrixXd covariance_of_means(const std::vector<std::vector<double>>& samples);
// The means of those quantities.
std::vector<double> means(const std::vector<std::vector<double>>& samples);

// Local exponents ln(y2/y1) / ln(k2/k1) between successive points whose means share random parts:
// the error from the covariance, var = C11/y1^2 + C22/y2^2 - 2 C12/(y1 y2), over ln(k2/k1)^2.
std::vector<LocalExponent> local_exponents(const std::vector<double>& k, const std::vector<double>& y, const Eigen::MatrixXd& C);

// The local exponents' trend: alpha_j = a + s log10 k_j (k_j the geometric middle of each
// interval), weighted by their errors; and the constant fit (one power law): its weighted mean and
// the chi^2 deviate of the exponents about it. A slope s below zero by several errors is a drift.
struct SlopeTrend {
  double mean = 0, mean_error = 0, constant_chi2 = 0, constant_z = 0;
  int constant_dof = 0;
  double slope = 0, slope_error = 0;  // per decade of k; NaN with fewer than 3 exponents
};
SlopeTrend slope_trend(const std::vector<LocalExponent>& local);
// The same for any values y(x) with independent errors (x = log10 k_B T0 for Table 1's critical
// values and exponents): the constant's mean and chi^2, the line's slope per unit x.
SlopeTrend trend(const std::vector<DataPoint>& points);

}  // namespace granchain::analysis
