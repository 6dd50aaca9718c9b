#pragma once
// One fixed step h of a touching cluster in overlap coordinates, without sine modes: the building
// block of fixed-step contact searches for large clusters (its cost per step grows like n b, not
// like n modes' exp and sincos plus sine transforms).
//
// The n-1 overlaps of an n-particle cluster obey x'' = -(k/m) L x - D L x' (cluster_modes.hpp,
// from Eq. force-0), so z = (x, x') advances by z(t + h) = Phi_h(L) z(t), where Phi_h(lambda) is
// the fundamental matrix at time h of the damped oscillator y'' + D lambda y' + (k/m) lambda y = 0:
//   Phi_11 = E (C + beta h Sc),  Phi_12 = E h Sc,  Phi_21 = -omega0^2 E h Sc,  Phi_22 = E (C - beta h Sc),
// with beta = D lambda / 2, omega0^2 = (k/m) lambda, E = exp(-beta h), z = (omega0^2 - beta^2) h^2,
// C = cos sqrt z and Sc = sin sqrt z / sqrt z (cosh and sinh for z < 0): entire in lambda, so under-
// and overdamped modes need no separate case. For the infinite chain (L with symbol
// 2 - 2 cos theta) Phi_h(L) is Toeplitz with the kernel
//   K_ab(l) = (1/pi) int_0^pi Phi_ab(2 - 2 cos theta) cos(l theta) d theta,
// and for a cluster (no overlap beyond either end: L with Dirichlet ends at sites 0 and n) odd
// reflections at both ends give the exact finite propagator
//   P_ab(i, j) = sum over integers m of [K_ab(i - j + 2mn) - K_ab(i + j + 2mn)],   i, j = 1 .. n-1,
// which is the sine-mode (DST-I) solution term by term (the sine sum is the trapezoidal rule of
// the kernel's integral, whose aliases are these images). K is the Fourier coefficient of an
// entire function of cos theta, so it decays faster than exponentially: beyond a band b (about 10
// at e = 1 and 20 at e = 0.1 for h = tau_c / 2) it is below 2^-60 of its largest entry and is
// dropped. The kernel depends on e and h / tau_c only, not on n or k.
#include <array>
#include <memory>
#include <vector>

namespace granchain {

class ChainPropagator {
 public:
  // k_over_m = k/m, D = gamma/m (contact_law), h > 0 the step.
  ChainPropagator(double k_over_m, double D, double h);

  double step() const { return h_; }
  int band() const { return b_; }
  // K_ab(l), a, b in {0, 1} (0: x, 1: x'), |l| <= band(); 0 beyond.
  double kernel(int a, int b, int l) const;

  // Overlaps x and rates xd of an n-particle cluster (n - 1 values each, n >= 2) one step h
  // later, into x_out and xd_out (which must not alias the inputs). Rows farther than b from both
  // ends use the Toeplitz kernel; the b rows at each end add their image terms (tables built once
  // per run, and per cluster size for clusters of at most 2b + 2 particles).
  void advance(int n, const double* x, const double* xd, double* x_out, double* xd_out) const;

 private:
  // P_ab(i, j) for rows i in [row0, row1) and columns j = i + c - b, c = 0 .. 2b, stored by
  // diagonal (entry c * rows + (i - row0)), zero outside the cluster.
  struct Block {
    int row0 = 0, row1 = 0;
    std::array<std::vector<double>, 4> p;
  };
  Block block(int n, int row0, int row1) const;
  const Block& small_cluster(int n) const;  // every row of a cluster of n <= 2b + 2
  // Rows first_row .. first_row + rows - 1 of an n-particle cluster from blk, one diagonal at a
  // time (unit stride over the rows).
  void sweep(const Block& blk, int n, int first_row, const double* x, const double* xd, double* x_out,
             double* xd_out) const;

  double h_;
  int b_ = 0;
  std::array<std::vector<double>, 4> K_;  // K_[2a + b][l], l = 0 .. b_
  Block bottom_, top_;  // the b rows at either end of a cluster larger than 2b + 2
  mutable std::vector<std::unique_ptr<Block>> small_;
};

}  // namespace granchain
