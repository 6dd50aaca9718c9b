#pragma once
// Closed-form motion of a cluster of n consecutive particles that all touch their neighbours
// (building block of the exact event-driven engine, issue 3). With every contact of the cluster
// closed, the n-1 overlaps x_i = d - (z_{i+1} - z_i) obey (from Eq. force-0)
//     x'' = -(k/m) L x - D L x',   L = tridiag(-1, 2, -1),
// and gravity moves only the centre of mass. L = S diag(lambda) S^T with the sine vectors
// S_ij = sqrt(2/n) sin(i j pi / n) and lambda_j = 4 sin^2(j pi / (2n)), j = 1..n-1, so each mode
// y_j = (S^T x)_j is an independent damped oscillator y'' + D lambda_j y' + (k/m) lambda_j y = 0:
// underdamped for D^2 lambda_j < 4 k/m, overdamped above (only for e < exp(-pi)).
#include <vector>

namespace granchain {

// y'' + 2 beta y' + omega0^2 y = 0 solved exactly from y(0), y'(0).
class DampedMode {
 public:
  DampedMode(double beta, double omega0_squared, double y0, double v0);
  double value(double t) const;
  double rate(double t) const;  // dy/dt

 private:
  void basis(double t, double& C, double& S) const;
  enum class Kind { Under, Critical, Over } kind_;
  double beta_, omega0_sq_, w_;  // w = sqrt(|omega0^2 - beta^2|)
  double y0_, v0_;
};

class ClusterMotion {
 public:
  // z, v: positions and velocities of the n >= 1 particles of the cluster, bottom first.
  ClusterMotion(const std::vector<double>& z, const std::vector<double>& v, double d, double k_over_m,
                double D, double g);
  // Positions and velocities at time t after the start, assuming all contacts stay closed.
  void state_at(double t, std::vector<double>& z, std::vector<double>& v) const;

 private:
  int n_;
  double d_, g_;
  double z_com_, v_com_;
  std::vector<std::vector<double>> S_;  // S_[i][j], i, j = 0..n-2
  std::vector<DampedMode> modes_;
};

}  // namespace granchain
