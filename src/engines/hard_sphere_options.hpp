#pragma once
// The options of the hard-sphere engine (hard_sphere_engine.hpp): the TC model of Luding and
// McNamara and the collapse watch. Apart, so that choosing an engine (engine_registry.hpp) does
// not pull in the engine itself.
#include <cstdint>

namespace granchain {

struct HardSphereOptions {
  // TC model: a collision within tc of the previous collision of either particle is elastic.
  // 0 switches it off.
  double tc = 0.0;
  // Collapse: `collapse_collisions` consecutive collisions (floor and wall hits included)
  // inside a time span shorter than `collapse_time`.
  std::uint64_t collapse_collisions = 1000;
  double collapse_time = 1e-9;
};

}  // namespace granchain
