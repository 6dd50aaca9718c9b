#pragma once
// Weighted linear least squares y ~ X c with weights 1/err^2, shared by the fits of the analysis
// layer (collapse_regimes, asymptotic_forms).
#include <Eigen/Dense>

namespace granchain::analysis {

// The coefficients from a column-pivoting QR of the weighted design matrix (stable for nearly
// collinear columns such as 1, x, x^2 with x = log10 k), their covariance (X^T W X)^-1 and chi^2.
// Throws std::invalid_argument when the points do not determine c.
struct LeastSquares {
  Eigen::VectorXd coef;
  Eigen::MatrixXd covariance;
  double chi2 = 0;
};
LeastSquares weighted_least_squares(const Eigen::MatrixXd& X, const Eigen::VectorXd& y, const Eigen::VectorXd& err);

}  // namespace granchain::analysis
