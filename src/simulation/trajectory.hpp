#pragma once
// Space-time diagrams: the heights z_i(t) of every particle sampled on a regular grid of times in a
// window, and the events inside it, for the driven column (the same trajectory as `granchain run`
// with the same seed) or a free-space launch (the same as `granchain collapse`'s launch r).
#include <string>
#include <vector>

#include "engines/events.hpp"
#include "model/collapse_setups.hpp"
#include "simulation/cancellation.hpp"
#include "simulation/driven_run.hpp"

namespace granchain {

struct TraceSpec {
  RunSpec run;                  // parameters, engine and seed (T and transient unused)
  bool free_space = false;      // false: driven column (gravity, thermal floor)
  LaunchParameters launch;      // free space: the launch of Sec. III.D
  int realization = 0;          // free space: launch number (seed derive_seed(seed, realization))
  double t_from = 0, t_to = 1, dt = 1e-3;  // window and sampling interval
};

struct Trajectory {
  std::vector<double> t;                // sample times
  std::vector<std::vector<double>> z;   // z[s][i]: height of particle i + 1 at t[s]
  std::vector<std::vector<double>> v;   // v[s][i]: its velocity
  // Above a vibrating plate (all empty under the thermal floor): its surface's height and velocity
  // and its phase theta = omega t + phi reduced to [0, 2 pi) at t[s].
  std::vector<double> plate, plate_v, plate_phase;
  std::vector<Event> events;            // contact begins and ends, floor hits (and plate contacts) in [t_from, t_to]
  bool interrupted = false;             // cancelled: the samples and events up to t.back() only
};

// Throws UnphysicalStateError if the dynamics turns unphysical. cancel
// (simulation/cancellation.hpp): when set, recording stops and what was recorded is returned.
Trajectory record_trajectory(const TraceSpec& spec, const CancelFlag* cancel = nullptr);

// As CSV: the samples (t, z1, ..., zN and z_plate above a plate; 17 significant digits) and the
// events (t, kind, i, j, speed; kind as event_kind_name, particles numbered from 1, the floor as 0).
std::string samples_csv(const Trajectory& tr);
std::string events_csv(const Trajectory& tr);

}  // namespace granchain
