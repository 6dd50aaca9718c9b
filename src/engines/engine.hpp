#pragma once
// One interface for every way of advancing time (the OpenMM "platform" idea). The reference
// engine is the paper's fixed-step Runge-Kutta; every faster engine must agree with it.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

#include "engines/events.hpp"
#include "model/chain_state.hpp"
#include "model/state_archive_fwd.hpp"

namespace granchain {

// What every engine counts.
struct EngineCounters {
  std::uint64_t steps = 0;         // integration steps (time-stepped engines) or event updates
  std::uint64_t contact_ends = 0;  // all contact ends since the start, transient included
  std::uint64_t floor_hits = 0;    // all floor hits since the start, transient included
};

// Contacts below an engine's resolution: contacts that began with an approach speed below 1e-13
// of the particles' speeds, those of them held in contact longer because their pair kept grazing,
// and steps of 1e-6 tau_c taken over a function touching zero within round-off (all occur only
// where relative motion has decayed below round-off). Zero for an engine that reports none.
struct ResolutionCounters {
  std::uint64_t grazing_contacts = 0, held_contacts = 0, resolution_skips = 0;
};

// An engine's audit of its own state between events (EngineChoice::audit, for the engines whose
// registry entry has one): instants checked, watched values evaluated there, and those found with
// the wrong sign beyond round-off. Zero when there is none or it is off.
struct AuditCounters {
  std::uint64_t instants = 0, values = 0, violations = 0;
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
  virtual ResolutionCounters below_resolution() const { return {}; }
  virtual AuditCounters audit() const { return {}; }
  // Smallest natural time increment (the step of a time-stepped engine), 0 if none.
  virtual double time_quantum() const { return 0.0; }
  // A checkpoint (model/state_archive.hpp), for the engines whose registry entry says resumable:
  // save writes everything the engine's future depends on, between two advance_to calls; an engine
  // made for the same run and restored from it goes on bit for bit as the saved one would have.
  // The others throw std::logic_error.
  virtual void save(StateArchive& out) const;
  virtual void restore(const StateArchive& in);
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
