#pragma once
// Hard-sphere engine: the k -> infinity limit at fixed e (paper Sec. II.B). Collisions are
// instantaneous and conserve momentum; the relative velocity of the pair reverses and shrinks by
// e, v'_{i+1} - v'_i = -e (v_{i+1} - v_i). Between collisions every particle falls freely, so
// gaps change linearly in time (gravity cancels in differences) and particle 1 flies on a
// parabola above the floor. Each collision is reported as a ContactBegin and a ContactEnd at the
// same instant, so the observers of the soft engines count the same things.
//
// Inelastic collapse — infinitely many collisions in a finite time (Sec. II.C) — is a real
// property of this model, not a numerical accident; the engine detects it and stops with an
// InelasticCollapseError that says when, where and after how many collisions. The TC model of
// Luding and McNamara continues past it: a collision of a particle whose previous collision (a
// floor or wall hit included) lies less than t_c ago is elastic (e = 1).
//
// Above a vibrating plate (model/plate_motion.hpp) particle 1 meets the moving surface as a hard
// plate of restitution e (the hard-sphere limit of the soft engines' plate contact): its velocity
// relative to the plate reverses and shrinks by e (by 1 under the TC model). Contact times are the
// first roots of plate_flight.hpp; a piecewise drive's switching instants are floor events too.
//
// Precision: gaps and relative velocities are stored as such, each gap with its own reference
// time, and a collision updates the relative velocities from relative velocities only
// (-e r for the pair, r - Delta for the neighbours), so a collapsing cluster whose gaps and
// relative speeds shrink geometrically keeps full relative precision until time itself stops
// resolving the intervals.
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "engines/chain_schedule.hpp"
#include "engines/engine.hpp"
#include "engines/hard_sphere_options.hpp"
#include "model/chain_parameters.hpp"
#include "model/floor.hpp"

namespace granchain {


class HardSphereEngine final : public Engine {
 public:
  // floor == nullptr: no floor (free space). The chain feels gravity p.g (set 0 for free space).
  // p.k is not used. Neighbours must not overlap in `initial` (touching is allowed).
  HardSphereEngine(const ChainParameters& p, const ChainState& initial, FloorDrive* floor,
                   HardSphereOptions options = {});

  void advance_to(double t, EventSink& sink) override;
  const ChainState& state() const override;
  double time() const override { return now_; }
  EngineCounters counters() const override { return counters_; }

  // A checkpoint: velocities, gaps, the floor height, the schedule, the TC model's and the
  // collapse watch's memory and the counts, as stored.
  void save(StateArchive& out) const override;
  void restore(const StateArchive& in) override;

  // Kinetic + gravitational energy per unit mass at time(), z measured from the floor level of
  // the centres (d/2). For conservation tests.
  double mechanical_energy_per_mass() const;
  // Collisions that the TC model made elastic.
  std::uint64_t elastic_by_tc() const { return tc_elastic_; }

 private:
  double velocity(int p, double t) const { return u_[p] - g_ * (t - tu_[p]); }
  double gap_at(int i, double t) const { return gaps_.line_at(i, t); }
  void sync_gap(int i, double t);
  void sync_floor(double t);
  void predict_gap(int i);
  void predict_floor();
  void collide(int i, double t, EventSink& sink);
  void floor_hit(double t, EventSink& sink);
  void watch_collapse(double t, int pair);  // pair -1: the floor

  int n_;
  double d_, g_, e_;
  FloorDrive* floor_;
  HardSphereOptions options_;

  std::vector<double> u_, tu_;                 // velocity of each particle at its reference time
  GapLines<double> gaps_;                      // gap i: s at t, and the rate c = v_{i+1} - v_i (constant)
  double floor_h_ = 0, floor_t_ = 0;           // z_1 - d/2 at floor_t_
  const PlateMotion* plate_ = nullptr;         // floor_'s plate, or nullptr for a floor at rest
  bool floor_switch_ = false;                  // the floor slot holds a plate's switching instant, not a hit
  std::vector<double> last_collision_;         // TC model: time of each particle's last collision
  std::uint64_t tc_elastic_ = 0;

  // Collapse watch: times and pairs of the last collapse_collisions collisions (a ring).
  std::vector<double> ring_t_;
  std::vector<int> ring_pair_;
  std::size_t ring_next_ = 0;
  std::uint64_t collisions_ = 0;

  struct NoDetail {};  // every interaction event is a collision, every floor event a floor hit
  ChainSchedule<double, NoDetail> schedule_;  // interaction and floor families (chain_schedule.hpp)
  double now_ = 0;
  EngineCounters counters_;
  mutable ChainState state_;
  mutable bool state_valid_ = false;
};

}  // namespace granchain
