#include "analysis/blocking.hpp"

#include <algorithm>
#include <limits>

#include <cmath>
#include <stdexcept>

#include "model/state_archive.hpp"

namespace granchain {

BinnedSums::BinnedSums(int bins, int components)
    : bins_(bins), components_(components), data_(static_cast<std::size_t>(bins) * components, 0.0) {
  if (bins < 1 || (bins & (bins - 1)) != 0) throw std::invalid_argument("BinnedSums: bins must be a power of two");
}

void BinnedSums::save(StateArchive& out) const {
  out["bins"] = bins_;
  out["components"] = components_;
  out["sums"] = pack_array(data_);
}

void BinnedSums::restore(const StateArchive& in) {
  if (saved_value<int>(in, "bins") != bins_ || saved_value<int>(in, "components") != components_) {
    throw StateArchiveError("saved state: binned sums of another shape");
  }
  data_ = unpack_array<double>(in, "sums", data_.size());
}

std::vector<double> BinnedSums::totals() const {
  std::vector<double> t(components_, 0.0);
  for (int b = 0; b < bins_; ++b)
    for (int c = 0; c < components_; ++c) t[c] += bin(b)[c];
  return t;
}

int power_of_two_bins(long long n, int limit) {
  long long b = 1;
  while (b * 2 <= n && b * 2 <= limit) b *= 2;
  return static_cast<int>(b);
}

namespace {

// Jackknife standard error over `blocks` equal blocks of the fine bins, and the lag-1
// autocorrelation of the leave-one-out values (which equals that of the block values).
BlockingLevel jackknife_level(const BinnedSums& sums, const std::vector<double>& total, int blocks,
                              const Estimator& f) {
  const int per_block = sums.bins() / blocks;
  const int nc = sums.components();
  std::vector<double> rest(nc);
  std::vector<double> theta(blocks);
  double mean = 0.0;
  for (int b = 0; b < blocks; ++b) {
    rest = total;
    for (int j = b * per_block; j < (b + 1) * per_block; ++j)
      for (int c = 0; c < nc; ++c) rest[c] -= sums.bin(j)[c];
    theta[b] = f(rest);
    mean += theta[b];
  }
  mean /= blocks;
  double ss = 0.0, lag1 = 0.0;
  for (int b = 0; b < blocks; ++b) {
    ss += (theta[b] - mean) * (theta[b] - mean);
    if (b + 1 < blocks) lag1 += (theta[b] - mean) * (theta[b + 1] - mean);
  }
  return {blocks, std::sqrt(ss * (blocks - 1) / blocks), ss > 0 ? lag1 / ss : 0.0};
}

}  // namespace

std::vector<BlockingLevel> blocking_curve(const BinnedSums& sums, const Estimator& f, int min_blocks) {
  const std::vector<double> total = sums.totals();
  std::vector<BlockingLevel> curve;
  for (int blocks = sums.bins(); blocks >= 2; blocks /= 2) {
    if (blocks < min_blocks && !curve.empty()) break;
    curve.push_back(jackknife_level(sums, total, blocks, f));
    if (blocks < min_blocks) break;
  }
  return curve;
}

Estimate blocked_estimate(const BinnedSums& sums, const Estimator& f, int min_blocks) {
  Estimate est;
  est.value = f(sums.totals());
  if (sums.bins() < 2) {
    est.error = std::nan("");
    return est;
  }
  const std::vector<BlockingLevel> curve = blocking_curve(sums, f, min_blocks);
  const std::size_t last = curve.size() - 1;
  std::size_t chosen = last;
  for (std::size_t l = 0; l < last; ++l) {
    // Blocks must look independent: lag-1 autocorrelation within 2 standard errors of zero, of
    // either sign (bins of a quasi-periodic series are anticorrelated, and stopping there would
    // overstate the error).
    bool plateau = std::abs(curve[l].lag1) < 2.0 / std::sqrt(double(curve[l].blocks));
    for (std::size_t h = l + 1; plateau && h <= last; ++h) {
      const double sigma_h = curve[h].error / std::sqrt(2.0 * (curve[h].blocks - 1));
      if (curve[h].error > curve[l].error + 2.0 * sigma_h) {
        plateau = false;
        break;
      }
    }
    if (plateau) {
      chosen = l;
      break;
    }
  }
  est.error = curve[chosen].error;
  est.blocks = curve[chosen].blocks;
  est.converged = chosen < last && curve[last].blocks >= min_blocks;
  return est;
}

StationarityCheck halves_check(const BinnedSums& sums, const Estimator& f, double z_max) {
  const int half = sums.bins() / 2, c = sums.components();
  BinnedSums a(std::max(half, 1), c), b(std::max(half, 1), c);
  for (int i = 0; i < half; ++i) {
    std::copy_n(sums.bin(i), c, a.bin(i));
    std::copy_n(sums.bin(half + i), c, b.bin(i));
  }
  // Halves of 8 bins or more: at least 4 blocks at the top level of each blocking curve.
  return judge_halves(blocked_estimate(a, f, std::min(16, std::max(2, half / 2))),
                      blocked_estimate(b, f, std::min(16, std::max(2, half / 2))), z_max);
}

StationarityCheck judge_halves(const Estimate& first, const Estimate& second, double z_max) {
  StationarityCheck out;
  out.first = first;
  out.second = second;
  const double diff = second.value - first.value;
  // The difference over an error; with no spread at all only equal halves pass.
  const auto distance = [diff](double err) {
    if (err > 0 && std::isfinite(err)) return diff / err;
    return diff == 0 ? 0.0 : std::copysign(std::numeric_limits<double>::infinity(), diff);
  };
  out.z = distance(std::hypot(first.error, second.error));
  out.z_settled = distance(std::sqrt(2.0) * second.error);
  out.stationary = std::abs(out.z) <= z_max && std::abs(out.z_settled) <= z_max;
  return out;
}

std::pair<double, double> mean_and_error(const std::vector<double>& x) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (x.empty()) return {nan, nan};
  double sum = 0;
  for (double v : x) sum += v;
  const double mean = sum / static_cast<double>(x.size());
  if (x.size() < 2) return {mean, nan};
  double ss = 0;
  for (double v : x) ss += (v - mean) * (v - mean);
  const double n = static_cast<double>(x.size());
  return {mean, std::sqrt(ss / (n - 1) / n)};
}

double chi2_normal_deviate(double chi2, int dof) {
  if (dof <= 0) return 0.0;
  const double v = 2.0 / (9.0 * dof);
  return (std::cbrt(chi2 / dof) - (1.0 - v)) / std::sqrt(v);
}

CurveScatter replica_scatter_by_level(const std::vector<std::vector<ReplicaRun>>& groups) {
  // The error of run r at `blocks` blocks (0 where its curve lacks the level: replica_scatter then
  // skips the point, so only levels every run has are compared).
  const auto error_at = [](const ReplicaRun& r, int blocks) {
    for (const BlockingLevel& l : r.curve)
      if (l.blocks == blocks) return l.error;
    return 0.0;
  };
  // As (value, error) groups, with the reported errors (blocks = 0) or those of one level.
  const auto as_pairs = [&](int blocks) {
    std::vector<std::vector<std::pair<double, double>>> pairs;
    for (const auto& g : groups) {
      pairs.emplace_back();
      for (const ReplicaRun& r : g) pairs.back().push_back({r.value, blocks == 0 ? r.error : error_at(r, blocks)});
    }
    return pairs;
  };
  const ReplicaScatter reported = replica_scatter(as_pairs(0));
  CurveScatter out{reported.groups, reported.runs, reported.dof, reported.chi2, {}};
  // The levels of the first replicated run's curve, longest blocks last; a level kept only if
  // every point that enters with its reported errors enters with it too.
  for (const auto& g : groups) {
    if (g.size() < 2) continue;
    for (const BlockingLevel& l : g.front().curve) {
      const ReplicaScatter s = replica_scatter(as_pairs(l.blocks));
      if (s.groups == reported.groups && s.dof == reported.dof) out.levels.push_back({l.blocks, s.chi2});
    }
    break;
  }
  return out;
}

ReplicaScatter replica_scatter(const std::vector<std::vector<std::pair<double, double>>>& groups) {
  ReplicaScatter out;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const auto& runs = groups[g];
    if (runs.size() < 2 || std::any_of(runs.begin(), runs.end(), [](const auto& r) { return !(r.second > 0); })) continue;
    double w = 0, wx = 0;
    for (const auto& [x, err] : runs) {
      w += 1 / (err * err);
      wx += x / (err * err);
    }
    const double mean = wx / w;
    double chi2 = 0;
    for (const auto& [x, err] : runs) chi2 += (x - mean) * (x - mean) / (err * err);
    const int dof = static_cast<int>(runs.size()) - 1;
    ++out.groups;
    out.runs += static_cast<int>(runs.size());
    out.dof += dof;
    out.chi2 += chi2;
    if (out.worst < 0 || chi2 / dof > out.worst_ratio) {
      out.worst = static_cast<int>(g);
      out.worst_ratio = chi2 / dof;
    }
  }
  out.chi2_z = chi2_normal_deviate(out.chi2, out.dof);
  return out;
}

}  // namespace granchain
