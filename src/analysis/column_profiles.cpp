#include "analysis/column_profiles.hpp"

#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>

namespace granchain::analysis {

namespace {

// Sums per (block, bin): sums[(block * bins + bin) * width + c].
struct BlockSums {
  int blocks, bins, width;
  std::vector<double> sums;
  BlockSums(int blocks_, int bins_, int width_)
      : blocks(blocks_), bins(bins_), width(width_), sums(static_cast<std::size_t>(blocks_) * bins_ * width_, 0.0) {}
  double* at(int block, int bin) { return &sums[(static_cast<std::size_t>(block) * bins + bin) * width]; }
  const double* at(int block, int bin) const { return &sums[(static_cast<std::size_t>(block) * bins + bin) * width]; }
};

// The value of bin `bin` from all blocks' sums together, and the batch-means error of the
// blocks' own values; unmeasured where `usable` refuses some block's sums.
BinnedValue batch_estimate(const BlockSums& s, int bin, const std::function<double(const double*, int block)>& value,
                           const std::function<bool(const double*)>& usable) {
  BinnedValue out;
  std::vector<double> total(s.width, 0.0);
  double sum = 0, sum2 = 0;
  bool all = true;
  for (int b = 0; b < s.blocks; ++b) {
    const double* x = s.at(b, bin);
    for (int c = 0; c < s.width; ++c) total[c] += x[c];
    if (!usable(x)) {
      all = false;
      continue;
    }
    const double y = value(x, b);
    sum += y;
    sum2 += y * y;
  }
  if (!usable(total.data())) return out;
  out.value = value(total.data(), -1);
  if (!all) return out;
  const double n = s.blocks;
  const double mean = sum / n;
  out.error = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / (n - 1));
  out.measured = true;
  return out;
}

void check(std::size_t samples, int bins, int blocks) {
  if (blocks < 2) throw std::invalid_argument("profiles: at least two blocks");
  if (bins < 1) throw std::invalid_argument("profiles: at least one bin");
  if (samples < static_cast<std::size_t>(blocks)) throw std::invalid_argument("profiles: fewer samples than blocks");
}

// The block of sample s: consecutive blocks of equal size (the last takes the remainder).
int block_of(std::size_t s, std::size_t samples, int blocks) {
  return static_cast<int>(std::min<std::size_t>(blocks - 1, s * blocks / samples));
}

}  // namespace

BinnedValue batch_mean(const std::vector<double>& x, int blocks) {
  check(x.size(), 1, blocks);
  BlockSums sums(blocks, 1, 2);
  for (std::size_t s = 0; s < x.size(); ++s) {
    double* acc = sums.at(block_of(s, x.size(), blocks), 0);
    acc[0] += 1;
    acc[1] += x[s];
  }
  return batch_estimate(sums, 0, [](const double* v, int) { return v[1] / v[0]; }, [](const double* v) { return v[0] >= 1; });
}

Harmonic first_harmonic(const std::vector<double>& theta, const std::vector<BinnedValue>& f) {
  Harmonic h;
  if (theta.size() != f.size() || theta.empty()) return h;
  const double n = static_cast<double>(theta.size());
  double a = 0, b = 0, va = 0, vb = 0;
  for (std::size_t i = 0; i < theta.size(); ++i) {
    if (!f[i].measured) return h;
    const double c = std::cos(theta[i]), s = std::sin(theta[i]);
    a += 2 / n * f[i].value * c;
    b += 2 / n * f[i].value * s;
    va += (2 / n * c * f[i].error) * (2 / n * c * f[i].error);
    vb += (2 / n * s * f[i].error) * (2 / n * s * f[i].error);
  }
  h.amplitude = std::hypot(a, b);
  h.phase = std::atan2(b, a);
  if (h.amplitude > 0) {
    h.amplitude_error = std::sqrt(a * a * va + b * b * vb) / h.amplitude;
    h.phase_error = std::sqrt(b * b * va + a * a * vb) / (h.amplitude * h.amplitude);
  }
  h.measured = true;
  return h;
}

HeightProfiles height_profiles(const std::vector<std::vector<double>>& z, const std::vector<std::vector<double>>& v, double m,
                               double z_min, double width, int bins, int blocks) {
  check(z.size(), bins, blocks);
  if (!(width > 0)) throw std::invalid_argument("profiles: the bin width must be positive");
  if (v.size() != z.size()) throw std::invalid_argument("profiles: heights and velocities differ in length");
  HeightProfiles out;
  out.z_min = z_min;
  out.width = width;
  // Per bin: particle samples, sum v, sum v^2; per block the number of states sampled.
  BlockSums sums(blocks, bins, 3);
  std::vector<double> states(blocks, 0.0);
  double outside = 0, all = 0;
  for (std::size_t s = 0; s < z.size(); ++s) {
    const int b = block_of(s, z.size(), blocks);
    states[b] += 1;
    for (std::size_t i = 0; i < z[s].size(); ++i) {
      all += 1;
      const double x = std::floor((z[s][i] - z_min) / width);
      if (!(x >= 0 && x < bins)) {
        outside += 1;
        continue;
      }
      double* acc = sums.at(b, static_cast<int>(x));
      acc[0] += 1;
      acc[1] += v[s][i];
      acc[2] += v[s][i] * v[s][i];
    }
  }
  out.outside = all > 0 ? outside / all : 0.0;
  const double total_states = static_cast<double>(z.size());
  for (int bin = 0; bin < bins; ++bin) {
    out.z.push_back(z_min + (bin + 0.5) * width);
    // n = particle samples / (states sampled x bin width), per block or over all (block -1).
    out.density.push_back(batch_estimate(
        sums, bin, [&](const double* x, int b) { return x[0] / ((b < 0 ? total_states : states[b]) * width); },
        [](const double*) { return true; }));
    out.temperature.push_back(batch_estimate(
        sums, bin,
        [m](const double* x, int) {
          const double u = x[1] / x[0];
          return m * std::max(0.0, x[2] / x[0] - u * u);
        },
        [](const double* x) { return x[0] >= 2; }));
  }
  return out;
}

PhaseProfiles phase_profiles(const std::vector<std::vector<double>>& z, const std::vector<std::vector<double>>& v,
                             const std::vector<double>& phase, const std::vector<double>& plate_z, const std::vector<double>& plate_v,
                             int bins, int blocks) {
  check(z.size(), bins, blocks);
  const std::size_t S = z.size();
  if (v.size() != S || phase.size() != S || plate_z.size() != S || plate_v.size() != S)
    throw std::invalid_argument("profiles: the samples and the plate's phase differ in length");
  constexpr double two_pi = 2 * std::numbers::pi;
  // Per bin: samples, sum z_cm, sum v_cm, sum z_p, sum v_p.
  BlockSums sums(blocks, bins, 5);
  for (std::size_t s = 0; s < S; ++s) {
    const int b = block_of(s, S, blocks);
    const int bin = std::min(bins - 1, std::max(0, static_cast<int>(std::floor(phase[s] / two_pi * bins))));
    double zc = 0, vc = 0;
    for (std::size_t i = 0; i < z[s].size(); ++i) {
      zc += z[s][i];
      vc += v[s][i];
    }
    const double n = static_cast<double>(z[s].size());
    double* acc = sums.at(b, bin);
    acc[0] += 1;
    acc[1] += zc / n;
    acc[2] += vc / n;
    acc[3] += plate_z[s];
    acc[4] += plate_v[s];
  }
  PhaseProfiles out;
  const auto has = [](const double* x) { return x[0] >= 1; };
  for (int bin = 0; bin < bins; ++bin) {
    out.theta.push_back((bin + 0.5) * two_pi / bins);
    out.z_cm.push_back(batch_estimate(sums, bin, [](const double* x, int) { return x[1] / x[0]; }, has));
    out.v_cm.push_back(batch_estimate(sums, bin, [](const double* x, int) { return x[2] / x[0]; }, has));
    out.z_plate.push_back(batch_estimate(sums, bin, [](const double* x, int) { return x[3] / x[0]; }, has));
    out.v_plate.push_back(batch_estimate(sums, bin, [](const double* x, int) { return x[4] / x[0]; }, has));
  }
  return out;
}

}  // namespace granchain::analysis
