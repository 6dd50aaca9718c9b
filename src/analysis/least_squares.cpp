#include "analysis/least_squares.hpp"

#include <stdexcept>

namespace granchain::analysis {

LeastSquares weighted_least_squares(const Eigen::MatrixXd& X, const Eigen::VectorXd& y, const Eigen::VectorXd& err) {
  const Eigen::VectorXd w_sqrt = err.cwiseInverse();
  const Eigen::MatrixXd Xw = w_sqrt.asDiagonal() * X;
  const Eigen::VectorXd yw = w_sqrt.cwiseProduct(y);
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Xw);
  if (qr.rank() < X.cols()) throw std::invalid_argument("fit: the points do not determine the coefficients");
  LeastSquares out;
  out.coef = qr.solve(yw);
  out.covariance = (Xw.transpose() * Xw).ldlt().solve(Eigen::MatrixXd::Identity(X.cols(), X.cols()));
  out.chi2 = (Xw * out.coef - yw).squaredNorm();
  return out;
}

}  // namespace granchain::analysis
