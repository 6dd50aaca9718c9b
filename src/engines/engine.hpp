#pragma once
// One interface for every way of advancing time (the OpenMM "platform" idea). The reference
// engine is the paper's fixed-step Runge-Kutta; every faster engine must agree with it.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

#include "engines/events.hpp"
#include "model/chain_state.hpp"

namespace granchain {

struct EngineCounters {
  std::uint64_t steps = 0;         // integration steps (time-stepped engines) or event updates
  std::uint64_t contact_ends = 0;  // all contact ends since the start, transient included
  std::uint64_t floor_hits = 0;    // all floor hits since the start, transient included
  std::uint64_t search_steps = 0;  // event-driven engines: root-free steps of the event searches
  // Exact engine, where the prediction work goes: event predictions solved in closed form (a pair's
  // contact end, two free particles, a free particle over the floor), those a lower bound ruled
  // out with no step (a gap or floor height next to a cluster, first_root), and those searched
  // step by step: a cluster's contact ends (their steps counted apart) or a gap or floor height.
  std::uint64_t closed_form_predictions = 0;
  std::uint64_t bound_exclusions = 0;
  std::uint64_t cluster_searches = 0;
  std::uint64_t cluster_search_steps = 0;
  std::uint64_t edge_searches = 0;
  // Exact engine, events below its resolution: contacts that began with an approach speed below
  // 1e-13 of the particles' speeds, and steps of 1e-6 tau_c taken over a function touching zero
  // within round-off (both occur only where relative motion has decayed below round-off).
  std::uint64_t grazing_contacts = 0;
  std::uint64_t resolution_skips = 0;
  // Exact engine: grazing contacts held in contact longer because their pair keeps grazing.
  std::uint64_t held_contacts = 0;
  // Exact engine with its audit on (EngineChoice::audit): instants checked between events, the
  // watched values evaluated there, and those found with the wrong sign beyond round-off (an
  // overlap of a closed pair at or below zero or at d, a gap or the floor height below zero).
  std::uint64_t audit_instants = 0, audit_values = 0, audit_violations = 0;
};

class Engine {
 public:
  virtual ~Engine() = default;
  // Advances the system to exactly time t >= time(), reporting every event on the way in
  // time order. Throws UnphysicalStateError when the state stops making physical sense.
  virtual void advance_to(double t, EventSink& sink) = 0;
  // State at time(); valid until the next advance_to.
  virtual const ChainState& state() const = 0;
  virtual double time() const = 0;
  virtual EngineCounters counters() const = 0;
  // Smallest natural time increment (the step of a time-stepped engine), 0 if none.
  virtual double time_quantum() const { return 0.0; }
};

// Raised when the simulation turns unphysical (particles pass through each other, a non-finite
// state). It names the time and the particles (1-based, as in the paper) so a run can stop with
// an error instead of printing a number.
class UnphysicalStateError : public std::runtime_error {
 public:
  UnphysicalStateError(double t, int particle_a, int particle_b, const std::string& what);
  double time() const { return t_; }
  int particle_a() const { return a_; }
  int particle_b() const { return b_; }

 private:
  double t_;
  int a_;
  int b_;
};

// An engine that cannot advance past an inelastic collapse (hard spheres: collisions accumulate
// in a vanishing time) reports it through the interface with this error, a kind of
// UnphysicalStateError that a driver counting collapses may catch.
class InelasticCollapseError : public UnphysicalStateError {
 public:
  InelasticCollapseError(double t, int first_particle, int last_particle, std::uint64_t collisions,
                         const std::string& what)
      : UnphysicalStateError(t, first_particle, last_particle, what), collisions_(collisions) {}
  // Collisions (floor and wall hits included) since the engine started, the collapse included.
  std::uint64_t collisions() const { return collisions_; }

 private:
  std::uint64_t collisions_;
};

}  // namespace granchain
