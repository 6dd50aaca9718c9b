#include "analysis/asymptotic_forms.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "analysis/blocking.hpp"
#include "analysis/least_squares.hpp"

namespace granchain::analysis {

const char* form_name(AsymptoticForm f) {
  switch (f) {
    case AsymptoticForm::PowerLaw: return "power law";
    case AsymptoticForm::Logarithm: return "a + b ln k";
    case AsymptoticForm::LogSquared: return "a + b ln k + c (ln k)^2";
    case AsymptoticForm::PowerLawLog: return "power law with log";
    case AsymptoticForm::PowerOfLog: return "power of ln k";
  }
  return "?";
}

const char* form_formula(AsymptoticForm f) {
  switch (f) {
    case AsymptoticForm::PowerLaw: return "y = c k^alpha";
    case AsymptoticForm::Logarithm: return "y = a + b ln k";
    case AsymptoticForm::LogSquared: return "y = a + b ln k + c (ln k)^2";
    case AsymptoticForm::PowerLawLog: return "y = c k^alpha (ln k)^beta";
    case AsymptoticForm::PowerOfLog: return "y = c (ln k)^beta";
  }
  return "?";
}

namespace {

bool in_log_space(AsymptoticForm f) {
  return f == AsymptoticForm::PowerLaw || f == AsymptoticForm::PowerLawLog || f == AsymptoticForm::PowerOfLog;
}

// The design row of a form at k (its columns multiply the parameters).
std::vector<double> design_row(AsymptoticForm f, double k) {
  const double L = std::log(k);
  switch (f) {
    case AsymptoticForm::PowerLaw: return {1.0, L};
    case AsymptoticForm::Logarithm: return {1.0, L};
    case AsymptoticForm::LogSquared: return {1.0, L, L * L};
    case AsymptoticForm::PowerLawLog: return {1.0, L, std::log(L)};
    case AsymptoticForm::PowerOfLog: return {1.0, std::log(L)};
  }
  return {};
}

// Generalised least squares: whitened by the Cholesky factor of the covariance, then the weighted
// solver with unit errors.
LeastSquares generalised_least_squares(const Eigen::MatrixXd& X, const Eigen::VectorXd& y, const Eigen::MatrixXd& C) {
  const Eigen::LLT<Eigen::MatrixXd> llt(C);
  if (llt.info() != Eigen::Success) throw std::invalid_argument("fit: the covariance of the points is not positive definite");
  const Eigen::MatrixXd Xw = llt.matrixL().solve(X);
  const Eigen::VectorXd yw = llt.matrixL().solve(y);
  return weighted_least_squares(Xw, yw, Eigen::VectorXd::Ones(y.size()));
}

FormFit fit_form(AsymptoticForm f, const std::vector<double>& k, const Eigen::VectorXd& y, const Eigen::MatrixXd& C,
                 const Eigen::LLT<Eigen::MatrixXd>& whiten) {
  const auto n = static_cast<Eigen::Index>(k.size());
  const auto p = static_cast<Eigen::Index>(design_row(f, k[0]).size());
  Eigen::MatrixXd X(n, p);
  for (Eigen::Index i = 0; i < n; ++i) {
    const std::vector<double> row = design_row(f, k[static_cast<std::size_t>(i)]);
    for (Eigen::Index j = 0; j < p; ++j) X(i, j) = row[static_cast<std::size_t>(j)];
  }
  LeastSquares ls;
  if (in_log_space(f)) {
    const Eigen::VectorXd inv_y = y.cwiseInverse();
    ls = generalised_least_squares(X, y.array().log().matrix(), inv_y.asDiagonal() * C * inv_y.asDiagonal());
  } else {
    ls = generalised_least_squares(X, y, C);
  }
  FormFit out;
  out.form = f;
  for (Eigen::Index j = 0; j < p; ++j) {
    out.param.push_back(ls.coef(j));
    out.error.push_back(std::sqrt(ls.covariance(j, j)));
  }
  Eigen::VectorXd model = X * ls.coef;
  if (in_log_space(f)) model = model.array().exp().matrix();
  const Eigen::VectorXd r = y - model;
  out.chi2 = whiten.matrixL().solve(r).squaredNorm();  // on y for every form
  out.dof = static_cast<int>(n - p);
  out.chi2_z = chi2_normal_deviate(out.chi2, out.dof);
  const double pp = static_cast<double>(p), nn = static_cast<double>(n);
  out.aicc = out.chi2 + 2 * pp + (nn - pp - 1 > 0 ? 2 * pp * (pp + 1) / (nn - pp - 1) : std::numeric_limits<double>::infinity());
  out.bic = out.chi2 + pp * std::log(nn);
  for (Eigen::Index i = 0; i < n; ++i) {
    out.model.push_back(model(i));
    out.pulls.push_back(r(i) / std::sqrt(C(i, i)));
  }
  return out;
}

}  // namespace

FormComparison compare_asymptotic_forms(const std::vector<double>& k, const std::vector<double>& y, const Eigen::MatrixXd& C) {
  const std::size_t n = k.size();
  if (y.size() != n || static_cast<std::size_t>(C.rows()) != n || static_cast<std::size_t>(C.cols()) != n)
    throw std::invalid_argument("asymptotic forms: k, y and the covariance must have the same size");
  if (n < 4) throw std::invalid_argument("asymptotic forms: at least 4 points are needed");
  for (std::size_t i = 0; i < n; ++i) {
    if (!(k[i] > 1.0)) throw std::invalid_argument("asymptotic forms: every k must be above 1 (ln ln k)");
    if (!(y[i] > 0)) throw std::invalid_argument("asymptotic forms: every y must be positive");
  }
  const Eigen::LLT<Eigen::MatrixXd> whiten(C);
  if (whiten.info() != Eigen::Success) throw std::invalid_argument("asymptotic forms: the covariance is not positive definite");
  const Eigen::VectorXd yv = Eigen::Map<const Eigen::VectorXd>(y.data(), static_cast<Eigen::Index>(n));
  FormComparison out;
  for (AsymptoticForm f : kAsymptoticForms) out.fits.push_back(fit_form(f, k, yv, C, whiten));
  double best_a = std::numeric_limits<double>::infinity(), best_b = best_a;
  for (std::size_t i = 0; i < out.fits.size(); ++i) {
    if (out.fits[i].aicc < best_a) best_a = out.fits[i].aicc, out.best_aicc = static_cast<int>(i);
    if (out.fits[i].bic < best_b) best_b = out.fits[i].bic, out.best_bic = static_cast<int>(i);
  }
  double sum = 0;
  for (auto& f : out.fits) sum += f.akaike_weight = std::exp(-0.5 * (f.aicc - best_a));
  for (auto& f : out.fits) f.akaike_weight /= sum;
  return out;
}

FormComparison compare_asymptotic_forms(const std::vector<DataPoint>& pts) {
  std::vector<double> k, y;
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(pts.size()), static_cast<Eigen::Index>(pts.size()));
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (!(pts[i].error > 0)) throw std::invalid_argument("asymptotic forms: every point needs a positive error");
    k.push_back(pts[i].x);
    y.push_back(pts[i].y);
    C(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i)) = pts[i].error * pts[i].error;
  }
  return compare_asymptotic_forms(k, y, C);
}

LogPolynomialFit fit_log_polynomial(const std::vector<double>& k, const std::vector<double>& y, const Eigen::MatrixXd& C, int degree) {
  const auto n = static_cast<Eigen::Index>(k.size());
  if (degree < 0 || y.size() != k.size() || C.rows() != n || C.cols() != n || n < degree + 2)
    throw std::invalid_argument("log polynomial: k, y and the covariance must have one size, at least degree + 2");
  // In x = ln k / ln k_max, so the columns stay of order one; c_degree = b_degree / ln(k_max)^degree.
  double L_max = 0;
  for (double kk : k) {
    if (!(kk > 1.0)) throw std::invalid_argument("log polynomial: every k must be above 1");
    L_max = std::max(L_max, std::log(kk));
  }
  Eigen::MatrixXd X(n, degree + 1);
  for (Eigen::Index i = 0; i < n; ++i)
    for (int j = 0; j <= degree; ++j) X(i, j) = std::pow(std::log(k[static_cast<std::size_t>(i)]) / L_max, j);
  const Eigen::VectorXd yv = Eigen::Map<const Eigen::VectorXd>(y.data(), n);
  const LeastSquares ls = generalised_least_squares(X, yv, C);
  const Eigen::LLT<Eigen::MatrixXd> whiten(C);
  LogPolynomialFit out;
  out.degree = degree;
  const double scale = std::pow(L_max, degree);
  out.leading = ls.coef(degree) / scale;
  out.leading_error = std::sqrt(ls.covariance(degree, degree)) / scale;
  out.chi2 = whiten.matrixL().solve(yv - X * ls.coef).squaredNorm();
  out.dof = static_cast<int>(n) - degree - 1;
  out.chi2_z = chi2_normal_deviate(out.chi2, out.dof);
  const double pp = degree + 1.0, nn = static_cast<double>(n);
  out.aicc = out.chi2 + 2 * pp + (nn - pp - 1 > 0 ? 2 * pp * (pp + 1) / (nn - pp - 1) : std::numeric_limits<double>::infinity());
  out.bic = out.chi2 + pp * std::log(nn);
  return out;
}

std::vector<double> means(const std::vector<std::vector<double>>& samples) {
  if (samples.empty()) throw std::invalid_argument("means: no samples");
  std::vector<double> m(samples[0].size(), 0.0);
  for (const auto& s : samples) {
    if (s.size() != m.size()) throw std::invalid_argument("means: samples of different lengths");
    for (std::size_t i = 0; i < m.size(); ++i) m[i] += s[i];
  }
  for (double& x : m) x /= static_cast<double>(samples.size());
  return m;
}

Eigen::MatrixXd covariance_of_means(const std::vector<std::vector<double>>& samples) {
  if (samples.size() < 2) throw std::invalid_argument("covariance of means: at least 2 samples are needed");
  const std::vector<double> m = means(samples);
  const auto n = static_cast<Eigen::Index>(m.size());
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(n, n);
  for (const auto& s : samples) {
    const Eigen::VectorXd d = Eigen::Map<const Eigen::VectorXd>(s.data(), n) - Eigen::Map<const Eigen::VectorXd>(m.data(), n);
    C += d * d.transpose();
  }
  const double R = static_cast<double>(samples.size());
  return C / ((R - 1) * R);
}

std::vector<LocalExponent> local_exponents(const std::vector<double>& k, const std::vector<double>& y, const Eigen::MatrixXd& C) {
  std::vector<LocalExponent> out;
  for (std::size_t i = 0; i + 1 < k.size(); ++i) {
    const auto a = static_cast<Eigen::Index>(i), b = a + 1;
    const double span = std::log(k[i + 1] / k[i]);
    const double var = C(a, a) / (y[i] * y[i]) + C(b, b) / (y[i + 1] * y[i + 1]) - 2 * C(a, b) / (y[i] * y[i + 1]);
    out.push_back({k[i], k[i + 1], std::log(y[i + 1] / y[i]) / span, std::sqrt(std::max(0.0, var)) / span});
  }
  return out;
}

SlopeTrend slope_trend(const std::vector<LocalExponent>& local) {
  std::vector<DataPoint> pts;
  for (const auto& l : local) pts.push_back({0.5 * std::log10(l.k1 * l.k2), l.alpha, l.error});
  return trend(pts);
}

SlopeTrend trend(const std::vector<DataPoint>& points) {
  SlopeTrend t;
  t.slope = t.slope_error = std::numeric_limits<double>::quiet_NaN();
  std::vector<DataPoint> pts;
  for (const auto& p : points)
    if (std::isfinite(p.y) && p.error > 0) pts.push_back(p);
  if (pts.empty()) {
    t.mean = t.mean_error = std::numeric_limits<double>::quiet_NaN();
    return t;
  }
  double w = 0, wy = 0;
  for (const auto& p : pts) w += 1 / (p.error * p.error), wy += p.y / (p.error * p.error);
  t.mean = wy / w;
  t.mean_error = 1 / std::sqrt(w);
  for (const auto& p : pts) t.constant_chi2 += std::pow((p.y - t.mean) / p.error, 2);
  t.constant_dof = static_cast<int>(pts.size()) - 1;
  t.constant_z = chi2_normal_deviate(t.constant_chi2, t.constant_dof);
  if (pts.size() >= 3) {
    const PolynomialFit line = fit_polynomial(pts, 1);
    t.slope = line.coef[1];
    t.slope_error = line.error[1];
  }
  return t;
}

}  // namespace granchain::analysis
