#pragma once
// Reference engine: the paper's second-order Runge-Kutta (midpoint) scheme with a fixed step
// dt = tau_c / dt_factor (Sec. III.A uses dt_factor = 100). Above a vibrating plate
// (model/plate_motion.hpp) particle 1 feels the plate's spring-dashpot force while it touches it,
// evaluated at the time of each stage.
#include <vector>

#include "engines/engine.hpp"
#include "model/chain_parameters.hpp"
#include "model/floor.hpp"

namespace granchain {

struct RungeKuttaOptions {
  double dt_factor = 100.0;  // dt = tau_c / dt_factor
  // false: the paper's scheme; a contact that opens or closes inside a step switches its force
  // at a step boundary, a first-order error in dt (largest at small e, where the dashpot force
  // jumps most). true: such a step is cut, by bisection to round-off, at the instant the first
  // contact switches or particle 1 reaches the floor, so the scheme stays second order; steps are
  // also cut where a piecewise plate motion switches (the sawtooth's drop, the quadratic's a_p).
  bool locate_switches = false;
};

class RungeKuttaEngine final : public Engine {
 public:
  // floor == nullptr: no floor (free space). The chain feels gravity p.g (set 0 for free space).
  RungeKuttaEngine(const ChainParameters& p, const ChainState& initial, FloorDrive* floor,
                   RungeKuttaOptions options = {});

  void advance_to(double t, EventSink& sink) override;
  const ChainState& state() const override { return state_; }
  double time() const override { return state_.t; }
  EngineCounters counters() const override { return counters_; }
  double time_quantum() const override { return dt_; }
  // The state (t, z, v), the contact set, the plate contact and the counts: all a step reads.
  void save(StateArchive& out) const override;
  void restore(const StateArchive& in) override;

 private:
  // a_i = -g + (f_{i,i+1} - f_{i-1,i}) / m with f from Eq. (force-0), plus the plate's force on
  // particle 1 at time t.
  void accelerations(double t, const double* z, const double* v, double* a) const;
  void step(double t0, double h, EventSink& sink);
  void located_step(double t0, double h, EventSink& sink);  // locate_switches: cut at the first switch
  void integrate(double t, double h);  // one midpoint step of size h from the state at time t
  // Has the contact set changed (the plate's contact included) by time t, or particle 1 gone below
  // the floor?
  bool switches(double t) const;
  void report_switches(double t0, double h, EventSink& sink);  // events of the step just taken
  void check_state(double t_end) const;
  // Overlap of particle 1 with the plate's surface at time t (positive: touching).
  double plate_overlap(double t, double z1) const { return plate_->z(t) + floor_z_ - z1; }

  int n_;
  double d_, g_, k_over_m_, D_, dt_;
  double floor_z_;  // centre height of particle 1 at a floor hit (d/2)
  FloorDrive* floor_;
  const PlateMotion* plate_;     // floor_'s plate, or nullptr for a floor at rest
  double plate_k_, plate_D_;     // the plate's contact: twice a pair's k/m and D
  bool on_plate_ = false;        // particle 1 touches the plate
  ChainState state_;
  bool locate_;
  std::vector<double> a_, zm_, vm_, am_, z_old_, z_save_, v_save_;
  std::vector<unsigned char> touching_;
  std::vector<Event> pending_;
  EngineCounters counters_;
};

}  // namespace granchain
