#include "engines/cluster_modes.hpp"

#include <cmath>
#include <numbers>

namespace granchain {

DampedMode::DampedMode(double beta, double omega0_squared, double y0, double v0)
    : beta_(beta), omega0_sq_(omega0_squared), y0_(y0), v0_(v0) {
  const double disc = omega0_squared - beta * beta;
  // Within round-off of critical damping, use the critical form (its limit from both sides).
  const double tol = 1e-12 * omega0_squared;
  if (disc > tol) {
    kind_ = Kind::Under;
    w_ = std::sqrt(disc);
  } else if (disc < -tol) {
    kind_ = Kind::Over;
    w_ = std::sqrt(-disc);
  } else {
    kind_ = Kind::Critical;
    w_ = 0.0;
  }
}

// C = cos, cosh or 1 and S = sin(w t)/w, sinh(w t)/w or t for under-, over- and critical
// damping: the two solutions of the undamped-frame equation, C(0) = 1, S(0) = 0, S'(0) = 1.
void DampedMode::basis(double t, double& C, double& S) const {
  switch (kind_) {
    case Kind::Under: C = std::cos(w_ * t); S = std::sin(w_ * t) / w_; break;
    case Kind::Over: C = std::cosh(w_ * t); S = std::sinh(w_ * t) / w_; break;
    case Kind::Critical: C = 1.0; S = t; break;
  }
}

// y(t) = e^{-beta t} [ y0 C(t) + (v0 + beta y0) S(t) ]
double DampedMode::value(double t) const {
  double C, S;
  basis(t, C, S);
  return std::exp(-beta_ * t) * (y0_ * C + (v0_ + beta_ * y0_) * S);
}

// y'(t) = e^{-beta t} [ v0 C(t) - (beta v0 + omega0^2 y0) S(t) ]
double DampedMode::rate(double t) const {
  double C, S;
  basis(t, C, S);
  return std::exp(-beta_ * t) * (v0_ * C - (beta_ * v0_ + omega0_sq_ * y0_) * S);
}

ClusterMotion::ClusterMotion(const std::vector<double>& z, const std::vector<double>& v, double d,
                             double k_over_m, double D, double g)
    : n_(static_cast<int>(z.size())), d_(d), g_(g), z_com_(0), v_com_(0) {
  for (int i = 0; i < n_; ++i) {
    z_com_ += z[i] / n_;
    v_com_ += v[i] / n_;
  }
  const int M = n_ - 1;
  std::vector<double> lambda(M);
  S_.assign(M, std::vector<double>(M));
  const double norm = std::sqrt(2.0 / n_);
  for (int j = 0; j < M; ++j) {
    const double s = std::sin((j + 1) * std::numbers::pi / (2.0 * n_));
    lambda[j] = 4.0 * s * s;
    for (int i = 0; i < M; ++i) S_[i][j] = norm * std::sin((i + 1) * (j + 1) * std::numbers::pi / n_);
  }
  for (int j = 0; j < M; ++j) {
    double y0 = 0, y1 = 0;
    for (int i = 0; i < M; ++i) {
      y0 += S_[i][j] * (d - (z[i + 1] - z[i]));
      y1 += S_[i][j] * (v[i] - v[i + 1]);
    }
    modes_.emplace_back(0.5 * D * lambda[j], k_over_m * lambda[j], y0, y1);
  }
}

void ClusterMotion::state_at(double t, std::vector<double>& z, std::vector<double>& v) const {
  const int M = n_ - 1;
  std::vector<double> x(M, 0.0), xd(M, 0.0);
  for (int j = 0; j < M; ++j) {
    const double y = modes_[j].value(t), yd = modes_[j].rate(t);
    for (int i = 0; i < M; ++i) {
      x[i] += S_[i][j] * y;
      xd[i] += S_[i][j] * yd;
    }
  }
  // Positions relative to particle 1 from the overlaps, then shifted so the centre of mass
  // follows its free fall.
  z.assign(n_, 0.0);
  v.assign(n_, 0.0);
  for (int i = 0; i < M; ++i) {
    z[i + 1] = z[i] + d_ - x[i];
    v[i + 1] = v[i] - xd[i];
  }
  double zc = 0, vc = 0;
  for (int i = 0; i < n_; ++i) {
    zc += z[i] / n_;
    vc += v[i] / n_;
  }
  const double z_com = z_com_ + v_com_ * t - 0.5 * g_ * t * t;
  const double v_com = v_com_ - g_ * t;
  for (int i = 0; i < n_; ++i) {
    z[i] += z_com - zc;
    v[i] += v_com - vc;
  }
}

}  // namespace granchain
