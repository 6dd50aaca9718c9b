#include "observables/collision_counter.hpp"

#include <algorithm>

#include "model/state_archive.hpp"

namespace granchain {

CollisionCounter::CollisionCounter(double t_begin, double t_end, int bins)
    : t_begin_(t_begin), t_end_(t_end), bin_width_((t_end - t_begin) / bins), sums_(bins, kComponents) {
  for (int b = 0; b < bins; ++b) sums_.bin(b)[kTime] = bin_width_;
}

void CollisionCounter::on_event(const Event& event) {
  if (event.t < t_begin_ || event.t >= t_end_) return;
  const int b = std::min(sums_.bins() - 1, static_cast<int>((event.t - t_begin_) / bin_width_));
  switch (event.kind) {
    case EventKind::ContactEnd:
      sums_.bin(b)[kPP] += 1.0;
      ++pp_;
      break;
    case EventKind::FloorHit:
      sums_.bin(b)[kFloor] += 1.0;
      ++floor_;
      break;
    case EventKind::ContactBegin:
    case EventKind::FloorContact:  // counted when it ends (FloorHit)
      break;
  }
}

Estimator CollisionCounter::n_coll(int N) {
  return [N](std::span<const double> s) { return (s[kPP] + s[kFloor]) / (N * s[kTime]); };
}

Estimate CollisionCounter::collision_rate_per_particle(int N) const { return blocked_estimate(sums_, n_coll(N)); }

StationarityCheck CollisionCounter::collision_rate_stationarity(int N) const { return halves_check(sums_, n_coll(N)); }

std::vector<BlockingLevel> CollisionCounter::collision_rate_blocking(int N) const { return blocking_curve(sums_, n_coll(N)); }

Estimate CollisionCounter::floor_hit_rate() const {
  return blocked_estimate(sums_, [](std::span<const double> s) { return s[kFloor] / s[kTime]; });
}

Estimate CollisionCounter::particle_collision_rate() const {
  return blocked_estimate(sums_, [](std::span<const double> s) { return s[kPP] / s[kTime]; });
}

void CollisionCounter::save(StateArchive& out) const {
  out["pp"] = pp_;
  out["floor"] = floor_;
  sums_.save(out["bins"]);
}

void CollisionCounter::restore(const StateArchive& in) {
  pp_ = saved_value<std::uint64_t>(in, "pp");
  floor_ = saved_value<std::uint64_t>(in, "floor");
  if (!in.contains("bins")) throw StateArchiveError("saved state: the collision counter has no bins");
  sums_.restore(in.at("bins"));
}

}  // namespace granchain
