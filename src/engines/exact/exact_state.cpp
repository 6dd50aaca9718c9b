// The exact engine's observables: the state at the current time (heights from the floor height and
// the gaps, velocities from the centres of mass and the modes), the overlaps at full precision and
// the mechanical energy.
#include "engines/exact/exact_engine.hpp"

namespace granchain {

const ChainState& ExactEngine::state() const {
  if (state_valid_) return state_;
  state_.t = now_.value();
  state_.z.resize(n_);
  state_.v.resize(n_);
  double* x = sx_.data();
  double* m_top = sxd_.data();  // mode part of each cluster's top particle, at lo
  for (int lo = 0; lo < n_; lo = hi_[lo] + 1) {
    double m_bottom = 0.0;
    if (lo == 0 && grounded_) {  // on the plate: z_1 = z_p + d/2 - X/2, pairs from the mirror modes
      double* xr = gxr_.data();
      grounded_state(now_ - gt0_, now_, xr, gxdr_.data(), &state_.v[0]);
      for (int q = 1; q < gn_; ++q) x[q - 1] = xr[q];
      state_.z[0] = plate_z(now_) + 0.5 * d_ - 0.5 * xr[0];
      m_top[0] = grounded_edge_top(now_);
      continue;
    }
    if (hi_[lo] == lo) {  // a free particle (the common case, written out)
      state_.v[lo] = com_velocity(lo, now_);
      m_top[lo] = 0.0;
    } else {
      cluster_state(lo, now_, x + lo, sv2_.data(), &state_.v[lo]);
      m_bottom = edge_mode(lo, false, now_);  // modes come from the cache
      m_top[lo] = edge_mode(lo, true, now_);
    }
    if (lo == 0) {
      state_.z[0] = 0.5 * d_ + floor_s_ + bottom_u(now_) - floor_u_;
    } else {
      const int i = lo - 1;  // open pair below this cluster
      x[i] = -gap_from_edges(i, now_, m_top[lo_of_[i]], m_bottom);
    }
  }
  for (int i = 0; i + 1 < n_; ++i) state_.z[i + 1] = state_.z[i] + d_ - x[i];
  state_valid_ = true;
  return state_;
}

std::vector<double> ExactEngine::overlaps() const {
  std::vector<double> x(n_, 0.0), xd(n_, 0.0), v(n_, 0.0);
  for (int lo = 0; lo < n_; lo = hi_[lo] + 1) {
    if (lo == 0 && grounded_) {
      grounded_state(now_ - gt0_, now_, gxr_.data(), gxdr_.data(), nullptr);
      for (int q = 1; q < gn_; ++q) x[q - 1] = gxr_[q];
      continue;
    }
    cluster_state(lo, now_, &x[lo], &xd[lo], &v[lo]);
  }
  for (int i = 0; i + 1 < n_; ++i) {
    if (lo_of_[i] != lo_of_[i + 1]) x[i] = -gap_at(i, now_);
  }
  x.pop_back();
  return x;
}

double ExactEngine::mechanical_energy_per_mass() const {
  const ChainState& s = state();
  const std::vector<double> x = overlaps();
  double e = 0.0;
  for (int i = 0; i < n_; ++i) e += 0.5 * s.v[i] * s.v[i] + g_ * (s.z[i] - 0.5 * d_);
  for (double xi : x) {
    if (xi > 0) e += 0.5 * k_over_m_ * xi * xi;
  }
  if (grounded_) {  // the plate's spring, 2k: (2k/m) x_w^2 / 2 = (k/m) X^2 / 4
    grounded_state(now_ - gt0_, now_, gxr_.data(), gxdr_.data(), nullptr);
    e += 0.25 * k_over_m_ * gxr_[0] * gxr_[0];
  }
  return e;
}

}  // namespace granchain
