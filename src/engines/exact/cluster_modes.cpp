#include "engines/exact/cluster_modes.hpp"

#include <cmath>
#include <numbers>

namespace granchain {

ModeConstants::ModeConstants(double beta_, double omega0_squared)
    : beta(beta_), omega0_sq(omega0_squared) {
  const double disc = omega0_squared - beta * beta;
  // Within round-off of critical damping, use the critical form (its limit from both sides).
  const double tol = 1e-12 * omega0_squared;
  if (disc > tol) {
    kind = ModeKind::Under;
    w = std::sqrt(disc);
  } else if (disc < -tol) {
    kind = ModeKind::Over;
    w = std::sqrt(-disc);
  } else {
    kind = ModeKind::Critical;
    w = 0.0;
  }
  const double omega0 = std::sqrt(omega0_squared);
  if (kind == ModeKind::Under) {
    bound[0] = 1.0;
    for (int n = 1; n <= kTaylorOrder; ++n) bound[n] = bound[n - 1] * omega0;
  } else {
    bound[0] = 1.0 / omega0;
    bound[1] = 1.0;
    for (int n = 1; n < kTaylorOrder; ++n) bound[n + 1] = 2.0 * beta * bound[n] + omega0_squared * bound[n - 1];
  }
}

// With C(t), S(t) the solutions of the undamped-frame equation (C(0) = 1, S(0) = 0, S'(0) = 1:
// cos and sin(wt)/w, cosh and sinh(wt)/w, or 1 and t):
//   y(t)  = e^{-beta t} [ y0 C + (v0 + beta y0) S ]
//   y'(t) = e^{-beta t} [ v0 C - (beta v0 + omega0^2 y0) S ]
void ModeConstants::evolve(double y0, double v0, double t, double& y, double& yd) const {
  if (t == 0.0) {  // no transcendental calls for the state at formation
    y = y0;
    yd = v0;
    return;
  }
  double eC = 0.0, eS = 0.0;  // e^{-beta t} C(t), e^{-beta t} S(t)
  switch (kind) {
    case ModeKind::Under: {
      const double damp = std::exp(-beta * t);
      eC = damp * std::cos(w * t);
      eS = damp * std::sin(w * t) / w;
      break;
    }
    case ModeKind::Critical: {
      const double damp = std::exp(-beta * t);
      eC = damp;
      eS = damp * t;
      break;
    }
    case ModeKind::Over: {
      // e^{-beta t} cosh(wt) and e^{-beta t} sinh(wt)/w without overflow or cancellation.
      if (2.0 * w * t < 600.0) {
        const double em = std::exp(-(beta + w) * t);
        const double x = std::expm1(2.0 * w * t);
        eC = em * (0.5 * x + 1.0);
        eS = em * (0.5 * x / w);
      } else {
        const double ep = 0.5 * std::exp((w - beta) * t);
        eC = ep;
        eS = ep / w;
      }
      break;
    }
  }
  y = y0 * eC + (v0 + beta * y0) * eS;
  yd = v0 * eC - (beta * v0 + omega0_sq * y0) * eS;
}

double DampedMode::value(double t) const {
  double y, yd;
  c_.evolve(y0_, v0_, t, y, yd);
  return y;
}

double DampedMode::rate(double t) const {
  double y, yd;
  c_.evolve(y0_, v0_, t, y, yd);
  return yd;
}

ClusterModeTable::ClusterModeTable(int n_, double k_over_m, double D) : n(n_), M(n_ - 1) {
  S.assign(static_cast<std::size_t>(M) * M, 0.0);
  bottom.assign(M, 0.0);
  top.assign(M, 0.0);
  s_max = std::sqrt(2.0 / n);
  for (int j = 0; j < M; ++j) {
    const double s = std::sin((j + 1) * std::numbers::pi / (2.0 * n));
    const double lambda = 4.0 * s * s;
    modes.emplace_back(0.5 * D * lambda, k_over_m * lambda);
    for (int i = 0; i < M; ++i) S[i * M + j] = s_max * std::sin((i + 1) * (j + 1) * std::numbers::pi / n);
  }
  if (SineTransform::pays_off(M)) transform = std::make_unique<SineTransform>(M);
  abs_S.resize(S.size());
  for (std::size_t q = 0; q < S.size(); ++q) abs_S[q] = std::abs(S[q]);
  // z_p - z_com = const + sum_i x_i [ (n-1-i)/n - [i < p] ]  (z_{i+1} = z_i + d - x_i).
  for (int j = 0; j < M; ++j) {
    for (int i = 0; i < M; ++i) {
      bottom[j] += (static_cast<double>(n - 1 - i) / n) * S[i * M + j];
      top[j] += (-static_cast<double>(i + 1) / n) * S[i * M + j];
    }
  }
}

// x = S y column by column (S is symmetric, so column j is row j): each x_i still sums
// S_i0 y_0 + S_i1 y_1 + ... in that order, but the additions into different x_i are independent,
// so the product runs at the adder's throughput instead of the latency of one chain per row.
void ClusterModeTable::to_overlaps(const double* __restrict y, double* __restrict x) const {
  if (transform) {
    transform->apply(y, x);
    return;
  }
  const double* __restrict s = S.data();
  for (int i = 0; i < M; ++i) x[i] = 0.0;
  for (int j = 0; j < M; ++j) {
    const double yj = y[j];
    const double* __restrict col = s + static_cast<std::size_t>(j) * M;
    for (int i = 0; i < M; ++i) x[i] += col[i] * yj;
  }
}

void ClusterModeTable::to_modes(const double* x, double* y) const { to_overlaps(x, y); }  // S = S^T = S^-1

ClusterModeTables::ClusterModeTables(int N, double k_over_m, double D)
    : k_over_m_(k_over_m), D_(D), tables_(static_cast<std::size_t>(N) + 1) {}

const ClusterModeTable& ClusterModeTables::build(int n) const {
  auto& slot = tables_[static_cast<std::size_t>(n)];
  slot = std::make_unique<ClusterModeTable>(n, k_over_m_, D_);
  return *slot;
}

ClusterMotion::ClusterMotion(const std::vector<double>& z, const std::vector<double>& v, double d,
                             double k_over_m, double D, double g)
    : table_(static_cast<int>(z.size()), k_over_m, D), d_(d), g_(g), z_com_(0), v_com_(0) {
  const int n = table_.n, M = table_.M;
  for (int i = 0; i < n; ++i) {
    z_com_ += z[i] / n;
    v_com_ += v[i] / n;
  }
  std::vector<double> x(M), xd(M);
  for (int i = 0; i < M; ++i) {
    x[i] = d - (z[i + 1] - z[i]);
    xd[i] = v[i] - v[i + 1];
  }
  y0_.resize(M);
  v0_.resize(M);
  table_.to_modes(x.data(), y0_.data());
  table_.to_modes(xd.data(), v0_.data());
}

void ClusterMotion::state_at(double t, std::vector<double>& z, std::vector<double>& v) const {
  const int n = table_.n, M = table_.M;
  std::vector<double> y(M), yd(M), x(M), xd(M);
  for (int j = 0; j < M; ++j) table_.modes[j].evolve(y0_[j], v0_[j], t, y[j], yd[j]);
  table_.to_overlaps(y.data(), x.data());
  table_.to_overlaps(yd.data(), xd.data());
  // Positions relative to particle 1 from the overlaps, then shifted so the centre of mass
  // follows its free fall.
  z.assign(n, 0.0);
  v.assign(n, 0.0);
  for (int i = 0; i < M; ++i) {
    z[i + 1] = z[i] + d_ - x[i];
    v[i + 1] = v[i] - xd[i];
  }
  double zc = 0, vc = 0;
  for (int i = 0; i < n; ++i) {
    zc += z[i] / n;
    vc += v[i] / n;
  }
  const double z_com = z_com_ + v_com_ * t - 0.5 * g_ * t * t;
  const double v_com = v_com_ - g_ * t;
  for (int i = 0; i < n; ++i) {
    z[i] += z_com - zc;
    v[i] += v_com - vc;
  }
}

}  // namespace granchain
