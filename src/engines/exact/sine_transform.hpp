#pragma once
// x = S y for the sine vectors of an n-particle cluster, S_ij = sqrt(2/n) sin(i j pi / n),
// i, j = 1 .. n-1, in O(n log n): S is a type-I discrete sine transform (FFTW's RODFT00, which
// computes Y_k = 2 sum_j X_j sin(pi (j+1)(k+1) / n) for arrays of n - 1 values), scaled by
// sqrt(2/n) / 2. S is its own inverse, so the same transform projects overlaps onto modes.
//
// Plans are made with FFTW_ESTIMATE | FFTW_NO_SIMD: the algorithm is then chosen by FFTW's
// fixed heuristics rather than by timing or by the CPU's vector units, so a given build gives
// the same bits on every run and every x86-64 machine (a seed reproduces a trajectory exactly).
#include <memory>

namespace granchain {

class SineTransform {
 public:
  explicit SineTransform(int M);  // vectors of M = n - 1 values
  ~SineTransform();
  SineTransform(const SineTransform&) = delete;
  SineTransform& operator=(const SineTransform&) = delete;

  // out_i = sum_j S_ij in_j; in and out may be the same array.
  void apply(const double* in, double* out) const;

  // Does the engine use the transform for clusters with M modes? A rule in M alone, so that a
  // trajectory never depends on timing: from n = 32 particles (M = 31) on. There the transform
  // is 2-6x faster than the dense product when n has only small prime factors and about as fast
  // when n has a large prime factor (FFTW's slowest case); bench/transform_speed measures both.
  static bool pays_off(int M);

 private:
  struct Plan;
  int M_;
  std::unique_ptr<Plan> plan_;
};

}  // namespace granchain
