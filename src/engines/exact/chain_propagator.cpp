#include "engines/exact/chain_propagator.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace granchain {

namespace {

// Phi_h(lambda) (chain_propagator.hpp) in long double, entries 11, 12, 21, 22.
std::array<long double, 4> fundamental_matrix(long double k_over_m, long double D, long double h, long double lambda) {
  const long double beta = 0.5L * D * lambda, omega0_sq = k_over_m * lambda;
  const long double z = (omega0_sq - beta * beta) * h * h;
  long double C, Sc;
  if (std::fabs(z) < 1e-3L) {  // the series of cos sqrt z and sin sqrt z / sqrt z (error < z^6 / 12!)
    C = 1 - z / 2 * (1 - z / 12 * (1 - z / 30 * (1 - z / 56 * (1 - z / 90))));
    Sc = 1 - z / 6 * (1 - z / 20 * (1 - z / 42 * (1 - z / 72 * (1 - z / 110))));
  } else if (z > 0) {
    const long double r = std::sqrt(z);
    C = std::cos(r);
    Sc = std::sin(r) / r;
  } else {
    const long double r = std::sqrt(-z);
    C = std::cosh(r);
    Sc = std::sinh(r) / r;
  }
  const long double E = std::exp(-beta * h);
  return {E * (C + beta * h * Sc), E * h * Sc, -omega0_sq * E * h * Sc, E * (C - beta * h * Sc)};
}

constexpr int kMaxBand = 64;        // kernels wider than this are refused
constexpr int kQuadrature = 1024;   // trapezoidal points on the circle (exponentially accurate)

}  // namespace

ChainPropagator::ChainPropagator(double k_over_m, double D, double h) : h_(h) {
  if (!(k_over_m > 0) || !(D >= 0) || !(h > 0)) throw std::invalid_argument("ChainPropagator: k/m > 0, D >= 0, h > 0");
  // K_ab(l) = (1/Q) sum_q Phi_ab(2 - 2 cos theta_q) cos(l theta_q), theta_q = 2 pi q / Q: the
  // trapezoidal rule of the kernel's integral, exact up to aliases K(l +- Q), far below round-off.
  std::array<std::vector<long double>, 4> K;
  for (auto& k : K) k.assign(kMaxBand + 1, 0.0L);
  for (int q = 0; q < kQuadrature; ++q) {
    const long double theta = 2 * std::numbers::pi_v<long double> * q / kQuadrature;
    const auto phi = fundamental_matrix(k_over_m, D, h, 2 - 2 * std::cos(theta));
    for (int l = 0; l <= kMaxBand; ++l) {
      const long double c = std::cos(l * theta);
      for (int a = 0; a < 4; ++a) K[a][l] += phi[a] * c;
    }
  }
  // x and h x' on one scale: entry 12 times 1/h, entry 21 times h.
  auto scaled = [&](int a, int l) {
    const long double scale = a == 1 ? 1 / static_cast<long double>(h) : a == 2 ? h : 1;
    return std::fabs(K[a][l] * scale);
  };
  long double largest = 0;
  for (int a = 0; a < 4; ++a) {
    for (int l = 0; l <= kMaxBand; ++l) {
      K[a][l] /= kQuadrature;
      largest = std::max(largest, scaled(a, l));
    }
  }
  // The band: the last l at which some scaled entry is above 2^-60 of the largest.
  b_ = 0;
  for (int l = 0; l <= kMaxBand; ++l) {
    for (int a = 0; a < 4; ++a) {
      if (scaled(a, l) > std::ldexp(largest, -60)) b_ = l;
    }
  }
  if (b_ >= kMaxBand) throw std::invalid_argument("ChainPropagator: the kernel does not decay within 64 sites (step too long)");
  for (int a = 0; a < 4; ++a) {
    K_[a].resize(b_ + 1);
    for (int l = 0; l <= b_; ++l) K_[a][l] = static_cast<double>(K[a][l]);
  }
  // Rows 1 .. b and n - b .. n - 1 of any cluster larger than 2b + 2 (the same for every such n,
  // rows and columns counted from the nearer end).
  const int large = 4 * b_ + 8;
  bottom_ = block(large, 1, b_ + 1);
  top_ = block(large, large - b_, large);
}

double ChainPropagator::kernel(int a, int b, int l) const {
  l = std::abs(l);
  return l <= b_ ? K_[2 * a + b][l] : 0.0;
}

ChainPropagator::Block ChainPropagator::block(int n, int row0, int row1) const {
  const int w = 2 * b_ + 1, R = row1 - row0;
  Block out;
  out.row0 = row0;
  out.row1 = row1;
  for (auto& p : out.p) p.assign(static_cast<std::size_t>(R) * w, 0.0);
  for (int i = row0; i < row1; ++i) {
    for (int j = std::max(1, i - b_); j <= std::min(n - 1, i + b_); ++j) {
      // Images at distance 2 m n; only |l| <= b contributes.
      for (int a = 0; a < 4; ++a) {
        long double s = 0;  // summed from the rounded kernel, in a fixed order
        for (int m = -(b_ / n + 2); m <= b_ / n + 2; ++m) {
          const int direct = i - j + 2 * m * n, image = i + j + 2 * m * n;
          if (std::abs(direct) <= b_) s += K_[a][std::abs(direct)];
          if (std::abs(image) <= b_) s -= K_[a][std::abs(image)];
        }
        out.p[a][static_cast<std::size_t>(j - i + b_) * R + (i - row0)] = static_cast<double>(s);
      }
    }
  }
  return out;
}

const ChainPropagator::Block& ChainPropagator::small_cluster(int n) const {
  if (static_cast<int>(small_.size()) <= n) small_.resize(n + 1);
  if (!small_[n]) small_[n] = std::make_unique<Block>(block(n, 1, n));
  return *small_[n];
}

void ChainPropagator::sweep(const Block& blk, int n, int first_row, const double* x, const double* xd, double* x_out,
                            double* xd_out) const {
  const int M = n - 1, R = blk.row1 - blk.row0, b = b_;
  double* xo = x_out + (first_row - 1);  // row first_row + r of the cluster is xo[r]
  double* vo = xd_out + (first_row - 1);
  for (int r = 0; r < R; ++r) xo[r] = vo[r] = 0.0;
  for (int c = 0; c <= 2 * b; ++c) {
    const int off = c - b;  // column j = row i + off
    const int r_lo = std::max(0, 1 - off - first_row), r_hi = std::min(R, M + 1 - off - first_row);
    const double *p11 = &blk.p[0][static_cast<std::size_t>(c) * R], *p12 = &blk.p[1][static_cast<std::size_t>(c) * R];
    const double *p21 = &blk.p[2][static_cast<std::size_t>(c) * R], *p22 = &blk.p[3][static_cast<std::size_t>(c) * R];
    const int shift = first_row - 1 + off;  // x[shift + r] is column j of row first_row + r
    for (int r = r_lo; r < r_hi; ++r) {
      xo[r] += p11[r] * x[shift + r] + p12[r] * xd[shift + r];
      vo[r] += p21[r] * x[shift + r] + p22[r] * xd[shift + r];
    }
  }
}

void ChainPropagator::advance(int n, const double* x, const double* xd, double* x_out, double* xd_out) const {
  const int b = b_;
  if (n <= 2 * b + 2) {  // a small cluster: every entry of its n - 1 rows, row by row
    const Block& blk = small_cluster(n);
    const int M = n - 1;
    for (int i = 1; i <= M; ++i) {
      double sx = 0.0, sv = 0.0;
      for (int j = std::max(1, i - b); j <= std::min(M, i + b); ++j) {  // P is zero beyond the band
        const std::size_t q = static_cast<std::size_t>(j - i + b) * M + (i - 1);
        sx += blk.p[0][q] * x[j - 1] + blk.p[1][q] * xd[j - 1];
        sv += blk.p[2][q] * x[j - 1] + blk.p[3][q] * xd[j - 1];
      }
      x_out[i - 1] = sx;
      xd_out[i - 1] = sv;
    }
    return;
  }
  sweep(bottom_, n, 1, x, xd, x_out, xd_out);
  const double *k11 = K_[0].data(), *k12 = K_[1].data(), *k21 = K_[2].data(), *k22 = K_[3].data();
  // Toeplitz rows b + 1 .. n - b - 1 (0-based r0 .. r1 - 1), one diagonal pair at a time: the
  // inner loops run over independent rows with unit stride, so they vectorise.
  const int r0 = b, r1 = n - b - 1;
  for (int r = r0; r < r1; ++r) {
    x_out[r] = k11[0] * x[r] + k12[0] * xd[r];
    xd_out[r] = k21[0] * x[r] + k22[0] * xd[r];
  }
  for (int l = 1; l <= b; ++l) {
    const double a11 = k11[l], a12 = k12[l], a21 = k21[l], a22 = k22[l];
    for (int r = r0; r < r1; ++r) {
      const double xs = x[r - l] + x[r + l], vs = xd[r - l] + xd[r + l];
      x_out[r] += a11 * xs + a12 * vs;
      xd_out[r] += a21 * xs + a22 * vs;
    }
  }
  sweep(top_, n, n - b, x, xd, x_out, xd_out);
}

}  // namespace granchain
