#include "engines/hard_sphere_engine.hpp"

#include "engines/free_flight.hpp"
#include "engines/plate_flight.hpp"
#include "model/state_archive.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace granchain {

namespace {
constexpr double kNever = free_flight::kInf;
// Initial overlaps smaller than this (relative to d) are round-off of a touching start.
constexpr double kTouchTolerance = 1e-12;
}  // namespace

HardSphereEngine::HardSphereEngine(const ChainParameters& p, const ChainState& initial, FloorDrive* floor,
                                   HardSphereOptions options)
    : n_(p.N), d_(p.d), g_(p.g), e_(p.e), floor_(floor), options_(options) {
  if (n_ < 1 || static_cast<int>(initial.z.size()) != n_ || static_cast<int>(initial.v.size()) != n_) {
    throw std::invalid_argument("HardSphereEngine: the initial state must hold N positions and velocities");
  }
  if (!(e_ > 0 && e_ <= 1)) throw std::invalid_argument("HardSphereEngine: e must lie in (0, 1]");
  if (!(options_.tc >= 0) || options_.collapse_collisions < 2 || !(options_.collapse_time > 0)) {
    throw std::invalid_argument("HardSphereEngine: tc >= 0, collapse_collisions >= 2, collapse_time > 0");
  }
  const double t = initial.t;
  now_ = t;
  for (int i = 0; i < n_; ++i) {
    if (!std::isfinite(initial.z[i]) || !std::isfinite(initial.v[i])) {
      throw UnphysicalStateError(t, i + 1, i + 1, fmt::format("non-finite initial state of particle {}", i + 1));
    }
  }
  u_ = initial.v;
  tu_.assign(n_, t);
  gaps_.reset(n_, t);
  for (int i = 0; i + 1 < n_; ++i) {
    double s = initial.z[i + 1] - initial.z[i] - d_;
    if (s < 0) {
      if (s < -kTouchTolerance * d_) {
        throw UnphysicalStateError(t, i + 1, i + 2,
                                   fmt::format("hard spheres {} and {} overlap in the initial state by {:.3g} d",
                                               i + 1, i + 2, -s / d_));
      }
      s = 0;
    }
    gaps_.s[i] = s;
    gaps_.c[i] = initial.v[i + 1] - initial.v[i];
  }
  floor_h_ = initial.z[0] - 0.5 * d_;
  floor_t_ = t;
  plate_ = floor_ != nullptr ? floor_->plate() : nullptr;
  const double surface = plate_ != nullptr ? plate_flight::piece_state(*plate_, t).z : 0.0;
  if (floor_ != nullptr && floor_h_ < surface) {
    if (floor_h_ < surface - kTouchTolerance * d_) {
      throw UnphysicalStateError(t, 1, 1, plate_ ? "particle 1 starts below the plate" : "particle 1 starts below the floor");
    }
    floor_h_ = surface;
  }
  last_collision_.assign(n_, -std::numeric_limits<double>::infinity());
  ring_t_.assign(options_.collapse_collisions, 0.0);
  ring_pair_.assign(options_.collapse_collisions, 0);
  schedule_.reset(n_, false);
  for (int i = 0; i + 1 < n_; ++i) predict_gap(i);
  predict_floor();
}

void HardSphereEngine::save(StateArchive& out) const {
  out["now"] = now_;
  out["u"] = pack_array(u_);
  out["tu"] = pack_array(tu_);
  out["gap_t"] = pack_array(gaps_.t);
  out["gap_s"] = pack_array(gaps_.s);
  out["gap_c"] = pack_array(gaps_.c);
  out["floor_h"] = floor_h_;
  out["floor_t"] = floor_t_;
  out["floor_switch"] = floor_switch_;
  out["last_collision"] = pack_array(last_collision_);
  out["tc_elastic"] = tc_elastic_;
  out["ring_t"] = pack_array(ring_t_);
  out["ring_pair"] = pack_array(ring_pair_);
  out["ring_next"] = ring_next_;
  out["collisions"] = collisions_;
  out["slot_time"] = pack_array(schedule_.times());
  out["steps"] = counters_.steps;
  out["contact_ends"] = counters_.contact_ends;
  out["floor_hits"] = counters_.floor_hits;
}

void HardSphereEngine::restore(const StateArchive& in) {
  const auto n = static_cast<std::size_t>(n_);
  now_ = saved_value<double>(in, "now");
  if (!std::isfinite(now_)) throw StateArchiveError("saved state: the hard engine's time is not finite");
  u_ = unpack_array<double>(in, "u", n);
  tu_ = unpack_array<double>(in, "tu", n);
  gaps_.t = unpack_array<double>(in, "gap_t", gaps_.t.size());
  gaps_.s = unpack_array<double>(in, "gap_s", gaps_.s.size());
  gaps_.c = unpack_array<double>(in, "gap_c", gaps_.c.size());
  floor_h_ = saved_value<double>(in, "floor_h");
  floor_t_ = saved_value<double>(in, "floor_t");
  floor_switch_ = saved_value<bool>(in, "floor_switch");
  last_collision_ = unpack_array<double>(in, "last_collision", n);
  tc_elastic_ = saved_value<std::uint64_t>(in, "tc_elastic");
  ring_t_ = unpack_array<double>(in, "ring_t", ring_t_.size());
  ring_pair_ = unpack_array<int>(in, "ring_pair", ring_pair_.size());
  ring_next_ = saved_value<std::size_t>(in, "ring_next");
  collisions_ = saved_value<std::uint64_t>(in, "collisions");
  if (ring_next_ >= ring_t_.size() && !ring_t_.empty())
    throw StateArchiveError("saved state: the collapse watch's place is out of its ring");
  schedule_.reset(n_, false);
  const std::vector<double> slot_time = unpack_array<double>(in, "slot_time", static_cast<std::size_t>(schedule_.slots()));
  // Pending times are +inf or not before now, a floor event needs a floor, the collapse watch names
  // pairs of this chain (-1: the floor): a corrupted state must not send the engine out of its arrays.
  for (int slot = 0; slot < schedule_.slots(); ++slot) {
    const double t = slot_time[slot];
    if (std::isnan(t) || t < now_) throw StateArchiveError("saved state: an event at no time or before the engine's time");
    if (slot == schedule_.floor() && floor_ == nullptr && t != std::numeric_limits<double>::infinity())
      throw StateArchiveError("saved state: a floor event without a floor");
    schedule_.set(slot, t);
  }
  for (int pair : ring_pair_)
    if (pair < -1 || pair >= n_ - 1) throw StateArchiveError("saved state: the collapse watch names a pair outside the chain");
  counters_.steps = saved_value<std::uint64_t>(in, "steps");
  counters_.contact_ends = saved_value<std::uint64_t>(in, "contact_ends");
  counters_.floor_hits = saved_value<std::uint64_t>(in, "floor_hits");
  state_valid_ = false;
}

// ----------------------------------------------------------------------------------------------
// Gaps and the floor: values at reference times, moved forward only when a velocity changes.

void HardSphereEngine::sync_gap(int i, double t) {
  gaps_.s[i] = std::max(0.0, gap_at(i, t));
  gaps_.t[i] = t;
}

void HardSphereEngine::sync_floor(double t) {
  const double tau = t - floor_t_;
  floor_h_ += tau * (velocity(0, floor_t_) - 0.5 * g_ * tau);
  if (plate_ != nullptr) floor_h_ = std::max(plate_flight::piece_state(*plate_, t).z, floor_h_);
  else if (floor_ != nullptr) floor_h_ = std::max(0.0, floor_h_);
  floor_t_ = t;
}

// Gap i closes when s + r (t - t_i) = 0 with r = v_{i+1} - v_i < 0 (free_flight.hpp).
void HardSphereEngine::predict_gap(int i) {
  const double s = gaps_.closing(i);
  schedule_.set(schedule_.interaction(i), s == kNever ? kNever : std::max(now_, gaps_.t[i] + s));
}

// Particle 1 reaches the floor when h + w tau - g tau^2 / 2 = 0 (w its velocity at floor_t_).
void HardSphereEngine::predict_floor() {
  if (floor_ == nullptr) return;
  if (plate_ != nullptr) {
    const plate_flight::Contact c = plate_flight::first_contact(*plate_, floor_t_, floor_h_, velocity(0, floor_t_), g_);
    floor_switch_ = c.kind == plate_flight::Contact::Switch;
    schedule_.set(schedule_.floor(), c.kind == plate_flight::Contact::None ? kNever : std::max(now_, c.t));
    return;
  }
  const double tau = free_flight::first_root(floor_h_, velocity(0, floor_t_), -g_);
  schedule_.set(schedule_.floor(), tau == kNever ? kNever : std::max(now_, floor_t_ + tau));
}

// ----------------------------------------------------------------------------------------------
// Events

// Binary collision of pair (i, i+1): momentum conserved, v'_{i+1} - v'_i = -e (v_{i+1} - v_i)
// (the restitution law that the soft contact produces after tau_c, paper Sec. II.B).
void HardSphereEngine::collide(int i, double t, EventSink& sink) {
  if (i > 0) sync_gap(i - 1, t);
  if (i + 2 < n_) sync_gap(i + 1, t);
  if (i == 0) sync_floor(t);
  const double r = gaps_.c[i];  // < 0: approaching
  double e = e_;
  if (options_.tc > 0 && (t - last_collision_[i] < options_.tc || t - last_collision_[i + 1] < options_.tc)) {
    e = 1.0;  // TC model
    ++tc_elastic_;
  }
  const double delta = -0.5 * (1.0 + e) * r;  // impulse per unit mass, > 0
  const double vi = velocity(i, t) - delta;
  const double vj = velocity(i + 1, t) + delta;
  u_[i] = vi;
  u_[i + 1] = vj;
  tu_[i] = tu_[i + 1] = t;
  gaps_.s[i] = 0.0;
  gaps_.t[i] = t;
  gaps_.c[i] = -e * r;
  if (i > 0) gaps_.c[i - 1] -= delta;      // v_i went down by delta
  if (i + 2 < n_) gaps_.c[i + 1] -= delta;  // v_{i+1} went up by delta
  last_collision_[i] = last_collision_[i + 1] = t;
  if (!std::isfinite(vi) || !std::isfinite(vj)) {
    throw UnphysicalStateError(t, i + 1, i + 2, fmt::format("non-finite velocities after a collision at t = {:.10g}", t));
  }
  ++counters_.contact_ends;
  sink.on_event({EventKind::ContactBegin, t, i, -r});
  sink.on_event({EventKind::ContactEnd, t, i, -e * r});
  if (i > 0) predict_gap(i - 1);
  predict_gap(i);
  if (i + 2 < n_) predict_gap(i + 1);
  if (i == 0) predict_floor();
  watch_collapse(t, i);
}

void HardSphereEngine::floor_hit(double t, EventSink& sink) {
  if (plate_ != nullptr && floor_switch_) {  // the plate's formula changes: no physics, a new prediction
    sync_floor(t);
    predict_floor();
    return;
  }
  if (n_ > 1) sync_gap(0, t);
  const double v_in = velocity(0, t);
  double v_out = 0.0, speed = 0.0, surface = 0.0;
  if (plate_ != nullptr) {
    // Speeds relative to the plate; the TC model makes a hit within tc of particle 1's last
    // collision elastic, as it does a pair's.
    const plate_flight::PieceState p = plate_flight::piece_state(*plate_, t);
    const double u_in = std::max(0.0, p.v - v_in);
    const bool elastic = options_.tc > 0 && t - last_collision_[0] < options_.tc;
    if (elastic) ++tc_elastic_;
    speed = elastic ? u_in : floor_->bounce(u_in);
    v_out = p.v + speed;
    surface = p.z;
    sink.on_event({EventKind::FloorContact, t, 0, u_in});
  } else {
    speed = floor_->bounce(std::max(0.0, -v_in));
    v_out = speed;
  }
  if (!std::isfinite(speed) || speed < 0) {
    throw UnphysicalStateError(t, 1, 1, fmt::format("the floor returned speed {} at t = {:.10g}", speed, t));
  }
  u_[0] = v_out;
  tu_[0] = t;
  if (n_ > 1) gaps_.c[0] -= v_out - v_in;
  floor_h_ = surface;
  floor_t_ = t;
  last_collision_[0] = t;
  ++counters_.floor_hits;
  sink.on_event({EventKind::FloorHit, t, 0, speed});
  if (n_ > 1) predict_gap(0);
  predict_floor();
  watch_collapse(t, -1);
}

void HardSphereEngine::watch_collapse(double t, int pair) {
  const std::size_t m = ring_t_.size();
  ring_t_[ring_next_] = t;
  ring_pair_[ring_next_] = pair;
  ring_next_ = (ring_next_ + 1) % m;
  ++collisions_;
  if (collisions_ < m) return;
  const double span = t - ring_t_[ring_next_];  // ring_next_ now holds the oldest of the last m
  if (span >= options_.collapse_time) return;
  const auto [lo, hi] = std::minmax_element(ring_pair_.begin(), ring_pair_.end());
  const bool floor_involved = *lo < 0;
  const int first = floor_involved ? 1 : *lo + 1;
  const int last = floor_involved && *hi < 0 ? 1 : *hi + 2;
  // With the TC model on, the collisions inside the span stayed inelastic because tc is shorter
  // than the intervals between a particle's collisions there; a tc of at least collapse_time makes
  // every further collision of a particle inside the span elastic.
  // With tc >= collapse_time every collision inside the span was elastic: what still collides
  // without end is a stack at rest (on the floor or a plate) whose relative speeds have decayed
  // below round-off, which hard spheres hold up only by infinitely many collisions.
  const std::string remedy =
      options_.tc >= options_.collapse_time
          ? fmt::format("the TC model (tc = {:g}) made them elastic, but particles resting on each other{} at relative speeds "
                        "of round-off still collide without end; use a soft engine",
                        options_.tc, floor_involved ? " or on the floor" : "")
      : options_.tc > 0
          ? fmt::format("the TC model did not prevent it: tc = {:g} is shorter than the span the engine watches ({} "
                        "collisions within {:g}); use tc >= {:g} or a soft engine",
                        options_.tc, m, options_.collapse_time, options_.collapse_time)
          : fmt::format("hard spheres collide infinitely often here. Use the TC model (tc >= {:g}) or a soft engine to continue",
                        options_.collapse_time);
  throw InelasticCollapseError(t, first, last, collisions_,
                               fmt::format("inelastic collapse at t = {:.12g}: {} collisions of particles {}..{}{} within {:.3g} "
                                           "(after {} collisions in all); {}",
                                           t, m, first, last, floor_involved ? " and the floor" : "", span, collisions_, remedy));
}

void HardSphereEngine::advance_to(double t, EventSink& sink) {
  if (!(t >= now_)) throw std::logic_error("HardSphereEngine::advance_to: time must not go back");
  now_ = run_events(schedule_, t, sink, [&](int slot, double t_event) {
    now_ = t_event;
    ++counters_.steps;
    const auto [family, pair] = schedule_.slot_of(slot);
    if (family == EventFamily::Floor) {
      floor_hit(t_event, sink);
    } else {
      collide(pair, t_event, sink);
    }
  });
  state_valid_ = false;
}

// ----------------------------------------------------------------------------------------------
// Observables

const ChainState& HardSphereEngine::state() const {
  if (state_valid_) return state_;
  state_.t = now_;
  state_.z.resize(n_);
  state_.v.resize(n_);
  const double tau = now_ - floor_t_;
  state_.z[0] = 0.5 * d_ + floor_h_ + tau * (velocity(0, floor_t_) - 0.5 * g_ * tau);
  for (int i = 0; i < n_; ++i) state_.v[i] = velocity(i, now_);
  for (int i = 0; i + 1 < n_; ++i) state_.z[i + 1] = state_.z[i] + d_ + gap_at(i, now_);
  state_valid_ = true;
  return state_;
}

double HardSphereEngine::mechanical_energy_per_mass() const {
  const ChainState& s = state();
  double E = 0;
  for (int i = 0; i < n_; ++i) E += 0.5 * s.v[i] * s.v[i] + g_ * (s.z[i] - 0.5 * d_);
  return E;
}

}  // namespace granchain
