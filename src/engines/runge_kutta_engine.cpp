#include "engines/runge_kutta_engine.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "model/state_archive.hpp"

namespace granchain {

UnphysicalStateError::UnphysicalStateError(double t, int particle_a, int particle_b,
                                           const std::string& what)
    : std::runtime_error(what), t_(t), a_(particle_a), b_(particle_b) {}

void Engine::save(StateArchive&) const { throw std::logic_error("this engine cannot save its state"); }
void Engine::restore(const StateArchive&) { throw std::logic_error("this engine cannot restore a saved state"); }

RungeKuttaEngine::RungeKuttaEngine(const ChainParameters& p, const ChainState& initial,
                                   FloorDrive* floor, RungeKuttaOptions options)
    : n_(p.N),
      d_(p.d),
      g_(p.g),
      floor_z_(0.5 * p.d),
      floor_(floor),
      state_(initial),
      locate_(options.locate_switches),
      a_(p.N),
      zm_(p.N),
      vm_(p.N),
      am_(p.N),
      z_old_(p.N),
      z_save_(p.N),
      v_save_(p.N),
      touching_(p.N > 1 ? p.N - 1 : 0, 0) {
  const ContactLaw law = contact_law(p);
  k_over_m_ = law.k_over_m;
  D_ = law.D;
  dt_ = law.tau_c / options.dt_factor;
  plate_ = floor_ != nullptr ? floor_->plate() : nullptr;
  plate_k_ = 2.0 * k_over_m_;  // the mirror image's contact (plate_motion.hpp)
  plate_D_ = 2.0 * D_;
  for (int i = 0; i + 1 < n_; ++i) touching_[i] = (d_ - (state_.z[i + 1] - state_.z[i])) > 0.0;
  if (plate_ != nullptr) on_plate_ = plate_overlap(state_.t, state_.z[0]) > 0.0;
  check_state(state_.t);
}

void RungeKuttaEngine::save(StateArchive& out) const {
  out["t"] = state_.t;
  out["z"] = pack_array(state_.z);
  out["v"] = pack_array(state_.v);
  out["touching"] = pack_array(touching_);
  out["on_plate"] = on_plate_;
  out["steps"] = counters_.steps;
  out["contact_ends"] = counters_.contact_ends;
  out["floor_hits"] = counters_.floor_hits;
}

void RungeKuttaEngine::restore(const StateArchive& in) {
  const auto n = static_cast<std::size_t>(n_);
  state_.t = saved_value<double>(in, "t");
  state_.z = unpack_array<double>(in, "z", n);
  state_.v = unpack_array<double>(in, "v", n);
  touching_ = unpack_array<unsigned char>(in, "touching", touching_.size());
  on_plate_ = saved_value<bool>(in, "on_plate");
  counters_.steps = saved_value<std::uint64_t>(in, "steps");
  counters_.contact_ends = saved_value<std::uint64_t>(in, "contact_ends");
  counters_.floor_hits = saved_value<std::uint64_t>(in, "floor_hits");
  check_state(state_.t);
}

void RungeKuttaEngine::accelerations(double t, const double* z, const double* v, double* a) const {
  for (int i = 0; i < n_; ++i) a[i] = -g_;
  if (plate_ != nullptr) {
    // The plate pushes particle 1 up while it overlaps: (2k/m) x_w + 2D x_w' (plate_motion.hpp).
    const double xw = plate_overlap(t, z[0]);
    if (xw > 0.0) a[0] += plate_k_ * xw + plate_D_ * (plate_->v(t) - v[0]);
  }
  for (int i = 0; i + 1 < n_; ++i) {
    const double x = d_ - (z[i + 1] - z[i]);  // overlap x_{i,i+1}
    if (x > 0.0) {
      // f_{i,i+1}/m = -(k/m) x - D v_{i,i+1}, Eq. (force-0); zero when not overlapping.
      const double f = -k_over_m_ * x - D_ * (v[i] - v[i + 1]);
      a[i] += f;
      a[i + 1] -= f;
    }
  }
}

void RungeKuttaEngine::check_state(double t) const {
  for (int i = 0; i < n_; ++i) {
    if (!std::isfinite(state_.z[i]) || !std::isfinite(state_.v[i])) {
      throw UnphysicalStateError(t, i + 1, i + 1,
                                 fmt::format("non-finite state of particle {} at t = {:.10g}", i + 1, t));
    }
  }
  if (plate_ != nullptr && plate_overlap(t, state_.z[0]) >= d_) {
    throw UnphysicalStateError(t, 1, 1, fmt::format("particle 1 passed through the plate at t = {:.10g} (overlap {:.6g} d)", t,
                                                    plate_overlap(t, state_.z[0]) / d_));
  }
  for (int i = 0; i + 1 < n_; ++i) {
    const double x = d_ - (state_.z[i + 1] - state_.z[i]);
    if (x >= d_) {
      throw UnphysicalStateError(
          t, i + 1, i + 2,
          fmt::format("particles {} and {} passed through each other at t = {:.10g} (overlap {:.6g} d)",
                      i + 1, i + 2, t, x / d_));
    }
  }
}

void RungeKuttaEngine::integrate(double t, double h) {
  double* z = state_.z.data();
  double* v = state_.v.data();
  // Midpoint rule: y(t+h) = y + h f(t + h/2, y + h/2 f(t, y)).
  accelerations(t, z, v, a_.data());
  for (int i = 0; i < n_; ++i) {
    z_old_[i] = z[i];
    zm_[i] = z[i] + 0.5 * h * v[i];
    vm_[i] = v[i] + 0.5 * h * a_[i];
  }
  accelerations(t + 0.5 * h, zm_.data(), vm_.data(), am_.data());
  for (int i = 0; i < n_; ++i) {
    z[i] += h * vm_[i];
    v[i] += h * am_[i];
  }
  ++counters_.steps;
}

bool RungeKuttaEngine::switches(double t) const {
  const double* z = state_.z.data();
  if (plate_ != nullptr) {
    if ((plate_overlap(t, z[0]) > 0.0) != on_plate_) return true;
  } else if (floor_ != nullptr && z[0] < floor_z_) {
    return true;
  }
  for (int i = 0; i + 1 < n_; ++i) {
    if ((d_ - (z[i + 1] - z[i]) > 0.0) != static_cast<bool>(touching_[i])) return true;
  }
  return false;
}

void RungeKuttaEngine::step(double t0, double h, EventSink& sink) {
  if (!locate_) {
    integrate(t0, h);
    report_switches(t0, h, sink);
    return;
  }
  // A piecewise plate motion is smooth only between its switching instants: end steps there.
  double done = 0.0;
  if (plate_ != nullptr) {
    for (double ts = plate_->next_switch(t0); ts < t0 + h; ts = plate_->next_switch(ts)) {
      if (ts - t0 > done) located_step(t0 + done, ts - t0 - done, sink);
      done = ts - t0;
    }
  }
  located_step(t0 + done, h - done, sink);
}

void RungeKuttaEngine::located_step(double t0, double h, EventSink& sink) {
  // Cut the step at the first switch: bisect on the size s of a step from the saved state for
  // the smallest s after which a contact has switched or particle 1 is below the floor.
  double done = 0.0;
  while (done < h) {
    const double rest = h - done;
    z_save_ = state_.z;
    v_save_ = state_.v;
    integrate(t0 + done, rest);
    if (!switches(t0 + done + rest)) {
      report_switches(t0 + done, rest, sink);
      return;
    }
    double lo = 0.0, hi = rest;
    while (hi - lo > 1e-15 * hi) {
      const double mid = 0.5 * (lo + hi);
      if (mid <= lo || mid >= hi) break;
      state_.z = z_save_;
      state_.v = v_save_;
      integrate(t0 + done, mid);
      (switches(t0 + done + mid) ? hi : lo) = mid;
    }
    state_.z = z_save_;
    state_.v = v_save_;
    integrate(t0 + done, hi);
    report_switches(t0 + done, hi, sink);
    done += hi;
  }
}

// Reports what switched during the step of size h that began at t0 (z_old_ holds the positions
// before it) and applies the floor.
void RungeKuttaEngine::report_switches(double t0, double h, EventSink& sink) {
  double* z = state_.z.data();
  double* v = state_.v.data();
  pending_.clear();

  // Thermal floor: particle 1 crossing z = d/2 is sent back up with a fresh floor speed. The hit
  // time is interpolated linearly inside the step, and the particle flies freely (under gravity)
  // for the rest of it.
  if (plate_ != nullptr) {
    // The plate's contact begins or ends where its overlap x_w changes sign, interpolated linearly
    // in the step; its end is the floor hit (one collision, as the thermal floor's).
    const double xw = plate_overlap(t0 + h, z[0]);
    if ((xw > 0.0) != on_plate_) {
      const double xo = plate_overlap(t0, z_old_[0]);
      const double frac = xo != xw ? std::clamp(xo / (xo - xw), 0.0, 1.0) : 1.0;
      const double speed = std::abs(v[0] - plate_->v(t0 + h));
      on_plate_ = xw > 0.0;
      pending_.push_back({on_plate_ ? EventKind::FloorContact : EventKind::FloorHit, t0 + frac * h, 0, speed});
      if (!on_plate_) ++counters_.floor_hits;
    }
  } else if (floor_ != nullptr && z[0] < floor_z_) {
    const double zo = z_old_[0];
    const double frac = zo > floor_z_ ? std::clamp((zo - floor_z_) / (zo - z[0]), 0.0, 1.0) : 0.0;
    const double r = (1.0 - frac) * h;
    const double speed = floor_->bounce(-(v[0] + g_ * r));  // arriving speed, back-dated by free fall
    v[0] = speed - g_ * r;
    z[0] = floor_z_ + speed * r - 0.5 * g_ * r * r;
    pending_.push_back({EventKind::FloorHit, t0 + frac * h, 0, speed});
    ++counters_.floor_hits;
  }

  double sum = 0.0;
  for (int i = 0; i < n_; ++i) sum += z[i] + v[i];
  bool bad = !std::isfinite(sum);
  bad = bad || (plate_ != nullptr && plate_overlap(t0 + h, z[0]) >= d_);
  for (int i = 0; i + 1 < n_; ++i) {
    const double x = d_ - (z[i + 1] - z[i]);
    const bool now = x > 0.0;
    if (now != static_cast<bool>(touching_[i])) {
      const double x_old = d_ - (z_old_[i + 1] - z_old_[i]);
      const double frac = x_old != x ? std::clamp(x_old / (x_old - x), 0.0, 1.0) : 1.0;
      const double speed = std::abs(v[i] - v[i + 1]);
      if (now) {
        pending_.push_back({EventKind::ContactBegin, t0 + frac * h, i, speed});
      } else {
        pending_.push_back({EventKind::ContactEnd, t0 + frac * h, i, speed});
        ++counters_.contact_ends;
      }
      touching_[i] = now;
    }
    bad = bad || x >= d_;
  }
  if (bad) check_state(t0 + h);

  if (pending_.size() > 1) {
    std::stable_sort(pending_.begin(), pending_.end(),
                     [](const Event& a, const Event& b) { return a.t < b.t; });
  }
  for (const Event& ev : pending_) sink.on_event(ev);
}

void RungeKuttaEngine::advance_to(double t, EventSink& sink) {
  const double t_start = state_.t;
  if (!(t >= t_start)) throw std::logic_error("RungeKuttaEngine::advance_to: time must not go back");
  // Whole steps of dt, with time recomputed as t_start + j dt (no accumulated round-off), then
  // one shortened step to land exactly on t if it is not a multiple of dt.
  const double span = t - t_start;
  const auto n_full = static_cast<std::uint64_t>(std::floor(span / dt_ + 1e-9));
  for (std::uint64_t j = 0; j < n_full; ++j) {
    const double t0 = t_start + static_cast<double>(j) * dt_;
    step(t0, dt_, sink);
    if (sink.stop_requested()) {
      state_.t = t0 + dt_;
      return;
    }
  }
  const double t_done = t_start + static_cast<double>(n_full) * dt_;
  const double rest = t - t_done;
  if (rest > 1e-9 * dt_) step(t_done, rest, sink);
  state_.t = t;
}

}  // namespace granchain
