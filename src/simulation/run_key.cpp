#include "simulation/run_key.hpp"

#include <fmt/format.h>

namespace granchain {

namespace {
std::string number_text(double x) { return fmt::format("{}", x); }  // shortest exact form
}  // namespace

std::string point_key_without_seed(const RunSpec& s) {
  std::string key = fmt::format("driven_column engine={} N={} e={} k={} T0={} m={} d={} g={} T={} transient={} "
                                "sample_interval={} bins={}",
                                s.engine.name, s.params.N, number_text(s.params.e), number_text(s.params.k),
                                number_text(s.params.kT0), number_text(s.params.m), number_text(s.params.d),
                                number_text(s.params.g), number_text(s.T), number_text(s.transient),
                                number_text(s.sample_interval), s.bins);
  if (is_hard_sphere_engine(s.engine.name)) key += " tc=" + number_text(s.engine.hard.tc);
  else if (s.engine.name != "exact") key += " dt_factor=" + number_text(s.engine.dt_factor);
  return key;
}

std::string point_key(const RunSpec& spec) { return point_key_without_seed(spec) + fmt::format(" seed={}", spec.seed); }

}  // namespace granchain
