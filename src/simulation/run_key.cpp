#include "simulation/run_key.hpp"

#include <fmt/format.h>

namespace granchain {

std::string exact_decimal(double x) { return fmt::format("{}", x); }

namespace {

// "driven_column engine=exact N=25 e=0.88 k=100000000 T0=1 m=1 d=1 g=1": what sets the dynamics.
std::string physics_text(const RunSpec& s) {
  return fmt::format("driven_column engine={} N={} e={} k={} T0={} m={} d={} g={}", engine_name(s.engine.kind), s.params.N,
                     exact_decimal(s.params.e), exact_decimal(s.params.k), exact_decimal(s.params.kT0),
                     exact_decimal(s.params.m), exact_decimal(s.params.d), exact_decimal(s.params.g));
}

// The engine options that act: tc for the hard engine, dt_factor for the time-stepped ones.
std::string engine_options_text(const RunSpec& s) {
  const EngineInfo& engine = engine_info(s.engine.kind);
  if (engine.hard_spheres) return " tc=" + exact_decimal(s.engine.hard.tc);
  if (engine.time_stepped) return " dt_factor=" + exact_decimal(s.engine.dt_factor);
  return "";
}

}  // namespace

std::string point_key_without_seed(const RunSpec& s) {
  return physics_text(s) +
         fmt::format(" T={} transient={} sample_interval={} bins={}", exact_decimal(s.T), exact_decimal(s.transient),
                     exact_decimal(s.sample_interval), s.bins) +
         engine_options_text(s);
}

std::string trajectory_key(const RunSpec& s) { return physics_text(s) + engine_options_text(s) + fmt::format(" seed={}", s.seed); }

std::string point_key(const RunSpec& spec) { return point_key_without_seed(spec) + fmt::format(" seed={}", spec.seed); }

}  // namespace granchain
