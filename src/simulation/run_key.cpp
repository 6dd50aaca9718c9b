#include "simulation/run_key.hpp"

#include <fmt/format.h>

namespace granchain {

std::string exact_decimal(double x) { return fmt::format("{}", x); }

std::string point_key_without_seed(const RunSpec& s) {
  std::string key = fmt::format("driven_column engine={} N={} e={} k={} T0={} m={} d={} g={} T={} transient={} "
                                "sample_interval={} bins={}",
                                s.engine.name, s.params.N, exact_decimal(s.params.e), exact_decimal(s.params.k),
                                exact_decimal(s.params.kT0), exact_decimal(s.params.m), exact_decimal(s.params.d),
                                exact_decimal(s.params.g), exact_decimal(s.T), exact_decimal(s.transient),
                                exact_decimal(s.sample_interval), s.bins);
  if (is_hard_sphere_engine(s.engine.name)) key += " tc=" + exact_decimal(s.engine.hard.tc);
  else if (s.engine.name != "exact") key += " dt_factor=" + exact_decimal(s.engine.dt_factor);
  return key;
}

std::string trajectory_key(const RunSpec& s) {
  std::string key = fmt::format("driven_column engine={} N={} e={} k={} T0={} m={} d={} g={}", s.engine.name, s.params.N,
                                exact_decimal(s.params.e), exact_decimal(s.params.k), exact_decimal(s.params.kT0),
                                exact_decimal(s.params.m), exact_decimal(s.params.d), exact_decimal(s.params.g));
  if (is_hard_sphere_engine(s.engine.name)) key += " tc=" + exact_decimal(s.engine.hard.tc);
  else if (s.engine.name != "exact") key += " dt_factor=" + exact_decimal(s.engine.dt_factor);
  return key + fmt::format(" seed={}", s.seed);
}

std::string point_key(const RunSpec& spec) { return point_key_without_seed(spec) + fmt::format(" seed={}", spec.seed); }

}  // namespace granchain
