#pragma once
// Closed-form motion of a cluster of n consecutive particles that all touch their neighbours
// (building block of the exact event-driven engine). With every contact of the cluster closed,
// the n-1 overlaps x_i = d - (z_{i+1} - z_i) obey (from Eq. force-0)
//     x'' = -(k/m) L x - D L x',   L = tridiag(-1, 2, -1),
// and gravity moves only the centre of mass. L = S diag(lambda) S^T with the sine vectors
// S_ij = sqrt(2/n) sin(i j pi / n) and lambda_j = 4 sin^2(j pi / (2n)), j = 1..n-1, so each mode
// y_j = (S^T x)_j is an independent damped oscillator y'' + D lambda_j y' + (k/m) lambda_j y = 0:
// underdamped for D^2 lambda_j < 4 k/m, overdamped above (only for e < exp(-pi)).
#include <cmath>
#include <memory>
#include <vector>

#include "engines/exact/sine_transform.hpp"

namespace granchain {

enum class ModeKind : unsigned char { Under, Critical, Over };

// Order of the Taylor bounds of the exact engine's event searches: derivatives 0 .. kTaylorOrder-1
// are used exactly and the kTaylorOrder-th is bounded.
constexpr int kTaylorOrder = 6;

// One damped oscillator y'' + 2 beta y' + omega0^2 y = 0 and the bounds the root finder needs.
// Every derivative obeys the same equation, so bounds on |y^(n)| at all later times follow from
// one amplitude of the state now:
//  - underdamped: y = Re(C e^{z t}) with z = -beta + i w, |z| = omega0, so
//      |y^(n)(t')| <= omega0^n |C(t)| for all t' >= t,  |C|^2 = y^2 + ((y' + beta y) / w)^2;
//  - otherwise: the energy E = y'^2 + omega0^2 y^2 never grows (dE/dt = -4 beta y'^2) and
//      |y^(n)| <= b_n sqrt(E),  b_0 = 1/omega0, b_1 = 1, b_(n+1) = 2 beta b_n + omega0^2 b_(n-1).
// bound[n] holds omega0^n or b_n, amplitude() |C| or sqrt(E).
struct ModeConstants {
  ModeConstants() = default;
  ModeConstants(double beta, double omega0_squared);
  double beta = 0, omega0_sq = 0, w = 0;  // w = sqrt(|omega0^2 - beta^2|)
  double bound[kTaylorOrder + 1] = {};
  ModeKind kind = ModeKind::Under;

  // y(t), y'(t) from y(0) = y0, y'(0) = v0, exactly.
  void evolve(double y0, double v0, double t, double& y, double& yd) const;
  double acceleration(double y, double yd) const { return -2.0 * beta * yd - omega0_sq * y; }
  // The amplitude A of the state (y, y'): |y^(n)| <= bound[n] A from now on. The sum of squares
  // underflows for amplitudes below ~1e-154 (a chain come to rest within round-off): there the
  // slower std::hypot keeps A > 0 whenever the state is not exactly zero.
  double amplitude(double y, double yd) const {
    if (kind == ModeKind::Under) {
      const double q = (yd + beta * y) / w;
      const double s = y * y + q * q;
      return s >= kNoUnderflow ? std::sqrt(s) : std::hypot(y, q);
    }
    const double s = yd * yd + omega0_sq * y * y;
    return s >= kNoUnderflow ? std::sqrt(s) : std::hypot(yd, std::sqrt(omega0_sq) * y);
  }
  // sqrt(E) / omega0 = sqrt(y^2 + (y' / omega0)^2): it bounds |y| at all later times (the energy
  // E = y'^2 + omega0^2 y^2 never grows).
  double energy_amplitude(double y, double yd) const {
    const double s = yd * yd + omega0_sq * y * y;  // underflows for a cluster at rest within round-off
    return s >= kNoUnderflow ? std::sqrt(s / omega0_sq) : std::hypot(yd / std::sqrt(omega0_sq), y);
  }
  static constexpr double kNoUnderflow = 1e-290;  // sums of squares above it lost nothing to underflow
};

// y'' + 2 beta y' + omega0^2 y = 0 solved exactly from y(0), y'(0).
class DampedMode {
 public:
  DampedMode(double beta, double omega0_squared, double y0, double v0)
      : c_(beta, omega0_squared), y0_(y0), v0_(v0) {}
  double value(double t) const;
  double rate(double t) const;  // dy/dt

 private:
  ModeConstants c_;
  double y0_, v0_;
};

// Everything about the modes of an n-particle cluster that depends only on n, k/m and D.
struct ClusterModeTable {
  ClusterModeTable(int n, double k_over_m, double D);
  int n;                             // particles
  int M;                             // modes = contacts = n - 1
  std::vector<double> S;             // S[i * M + j]: overlap i in mode j (orthogonal, symmetric)
  std::vector<double> abs_S;         // |S[i * M + j]|
  std::vector<ModeConstants> modes;  // mode j
  std::vector<double> bottom, top;   // z_1 - z_com and z_n - z_com per unit y_j (constant part aside)
  double s_max = 0;                  // sqrt(2/n) >= |S_ij|

  // FFTW's sine transform for large clusters (SineTransform::pays_off), else null.
  std::unique_ptr<SineTransform> transform;

  // Overlaps and their rates from modes (x = S y) and modes from overlaps (y = S^T x = S x):
  // the sine transform where it pays off, else the dense product in a fixed order.
  void to_overlaps(const double* y, double* x) const;
  void to_modes(const double* x, double* y) const;
};

// Tables for every cluster size up to N, built on first use.
class ClusterModeTables {
 public:
  ClusterModeTables(int N, double k_over_m, double D);
  const ClusterModeTable& operator[](int n) const {
    const auto& slot = tables_[static_cast<std::size_t>(n)];
    return slot ? *slot : build(n);
  }

 private:
  const ClusterModeTable& build(int n) const;
  double k_over_m_, D_;
  mutable std::vector<std::unique_ptr<ClusterModeTable>> tables_;
};

class ClusterMotion {
 public:
  // z, v: positions and velocities of the n >= 1 particles of the cluster, bottom first.
  ClusterMotion(const std::vector<double>& z, const std::vector<double>& v, double d, double k_over_m,
                double D, double g);
  // Positions and velocities at time t after the start, assuming all contacts stay closed.
  void state_at(double t, std::vector<double>& z, std::vector<double>& v) const;

 private:
  ClusterModeTable table_;
  double d_, g_;
  double z_com_, v_com_;
  std::vector<double> y0_, v0_;  // mode amplitudes and rates at t = 0
};

}  // namespace granchain
