#include "observables/profile_sampler.hpp"

#include <algorithm>

#include "model/state_archive.hpp"
#include <cmath>

namespace granchain {

ProfileSampler::ProfileSampler(int N, double m, std::int64_t expected_samples, int bins)
    : n_(N), m_(m), expected_(std::max<std::int64_t>(1, expected_samples)), z_ref_(N, 0.0), sums_(bins, 1 + 3 * N) {}

void ProfileSampler::sample(const ChainState& s) {
  if (taken_ == 0) z_ref_ = s.z;
  const auto b = static_cast<int>(std::min<std::int64_t>(sums_.bins() - 1, taken_ * sums_.bins() / expected_));
  double* acc = sums_.bin(b);
  acc[0] += 1.0;
  for (int i = 0; i < n_; ++i) {
    const double dz = s.z[i] - z_ref_[i];
    acc[1 + 3 * i] += dz;
    acc[2 + 3 * i] += dz * dz;
    acc[3 + 3 * i] += s.v[i] * s.v[i];
  }
  ++taken_;
}

Estimator ProfileSampler::mean_height() const {
  const int n = n_;
  double ref = 0.0;
  for (double z : z_ref_) ref += z / n;
  return [n, ref](std::span<const double> s) {
    double dz = 0.0;
    for (int i = 0; i < n; ++i) dz += s[1 + 3 * i];
    return ref + dz / (n * s[0]);
  };
}

StationarityCheck ProfileSampler::height_stationarity() const { return halves_check(sums_, mean_height()); }

std::vector<BlockingLevel> ProfileSampler::height_blocking() const { return blocking_curve(sums_, mean_height()); }

std::vector<ParticleProfile> ProfileSampler::profiles() const {
  std::vector<ParticleProfile> out(n_);
  const double half_m = 0.5 * m_;
  BinnedSums one(sums_.bins(), 4);  // count, sum dz, sum dz^2, sum v^2 of one particle
  for (int i = 0; i < n_; ++i) {
    for (int b = 0; b < sums_.bins(); ++b) {
      const double* src = sums_.bin(b);
      double* dst = one.bin(b);
      dst[0] = src[0];
      dst[1] = src[1 + 3 * i];
      dst[2] = src[2 + 3 * i];
      dst[3] = src[3 + 3 * i];
    }
    const double ref = z_ref_[i];
    out[i].z_mean = blocked_estimate(one, [ref](std::span<const double> s) { return ref + s[1] / s[0]; });
    out[i].z_std = blocked_estimate(one, [](std::span<const double> s) {
      const double mean = s[1] / s[0];
      return std::sqrt(std::max(0.0, s[2] / s[0] - mean * mean));
    });
    out[i].kinetic = blocked_estimate(one, [half_m](std::span<const double> s) { return half_m * s[3] / s[0]; });
  }
  return out;
}

void ProfileSampler::save(StateArchive& out) const {
  out["taken"] = taken_;
  out["z_ref"] = pack_array(z_ref_);
  sums_.save(out["bins"]);
}

void ProfileSampler::restore(const StateArchive& in) {
  taken_ = saved_value<std::int64_t>(in, "taken");
  z_ref_ = unpack_array<double>(in, "z_ref", static_cast<std::size_t>(n_));
  if (!in.contains("bins")) throw StateArchiveError("saved state: the profile sampler has no bins");
  sums_.restore(in.at("bins"));
}

}  // namespace granchain
