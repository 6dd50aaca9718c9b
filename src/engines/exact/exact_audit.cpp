// The exact engine's audit: an independent check that no event was missed. Between two events
// every closed pair's overlap must stay in (0, d), every open pair's gap and the floor height must
// stay >= 0. After each event the audit evaluates all of them straight from the closed forms at
// random instants before the next event and counts the values on the wrong side of zero beyond
// round-off (EngineCounters::audit_violations). It only reads the state (the mode cache holds
// values computed by the same expressions), so the trajectory is the same with and without it.
#include <algorithm>
#include <cmath>

#include "engines/exact/exact_engine.hpp"

namespace granchain {

namespace {
// splitmix64: the audit's own instants, independent of the physics' random streams.
double uniform01(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  z ^= z >> 31;
  return (static_cast<double>(z >> 11) + 0.5) * 0x1.0p-53;  // in (0, 1)
}
}  // namespace

void ExactEngine::audit_interval(Time a, Time b) {
  if (!(b > a) || !b.finite()) return;
  // A missed root leaves its function on the wrong side by a fraction of the amplitude of the
  // modes that drive it; round-off near a root is ~1e-16 of that. The tolerance, 1e-9 of the
  // amplitude (overlap_reach), sits far between the two.
  for (int q = 0; q < kAuditInstants; ++q) {
    const Time s = a + (b - a) * uniform01(audit_draws_);
    if (!(s > a && s < b)) continue;
    ++counters_.audit_instants;
    double* x = sx_.data();
    double* xd = sxd_.data();
    double* v = sv_.data();
    for (int lo = 0; lo < n_; lo = hi_[lo] + 1) {
      const int hi = hi_[lo];
      const double tol = 1e-9 * overlap_reach(lo);
      if (hi > lo) {
        cluster_state(lo, s, x, xd, v);
        for (int i = lo; i < hi; ++i) {
          ++counters_.audit_values;
          const double xi = x[i - lo];
          const bool held = hold_until_[i] > s;  // a held pair may sit at zero within round-off
          if ((!held && !(xi > -tol)) || !(xi < d_)) ++counters_.audit_violations;
        }
      }
      if (hi + 1 < n_) {  // the open pair above this cluster
        ++counters_.audit_values;
        const double tol_gap = 1e-12 * d_ + tol + 1e-9 * overlap_reach(hi + 1);
        if (!(gap_at(hi, s) > -tol_gap)) ++counters_.audit_violations;
      }
    }
    if (floor_ != nullptr) {
      ++counters_.audit_values;
      const double height = floor_s_ + (bottom_u(s) - floor_u_);
      if (!(height > -(1e-12 * d_ + 1e-9 * overlap_reach(0)))) ++counters_.audit_violations;
    }
  }
}

}  // namespace granchain
