#pragma once
#include <memory>
#include <string>
#include <vector>

#include "engines/engine.hpp"
#include "engines/hard_sphere_engine.hpp"
#include "model/chain_parameters.hpp"
#include "model/floor.hpp"

namespace granchain {

struct EngineChoice {
  std::string name = "exact";  // one of engine_names(); the first is the default
  double dt_factor = 100.0;        // time-stepped engines: dt = tau_c / dt_factor
  HardSphereOptions hard;          // the hard-sphere engine (k = infinity): TC model, collapse watch
  bool audit = false;              // exact engine: check every overlap and gap between events (slow)
};

// True for engines that treat the spheres as hard (k = infinity, instantaneous collisions).
inline bool is_hard_sphere_engine(const std::string& name) { return name == "hard"; }

// True for engines whose clock is a FineTime (fine_time.hpp), which resolves 2^-53 ulp(t) at
// time t; the others step or schedule in plain doubles, which resolve ulp(t).
inline bool has_fine_clock(const std::string& name) { return name == "exact"; }

// Names accepted by make_engine, the default first.
const std::vector<std::string>& engine_names();

std::unique_ptr<Engine> make_engine(const EngineChoice& choice, const ChainParameters& p,
                                    const ChainState& initial, FloorDrive* floor);

}  // namespace granchain
