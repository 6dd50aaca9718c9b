#include "store/collapse_json.hpp"

#include <cmath>

#include "version.hpp"
#include "provenance.hpp"

namespace granchain {

nlohmann::json number_or_null(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

nlohmann::json collapse_result_to_json(const CollapseResult& r) {
  const CollapseSpec& s = r.spec;
  std::uint64_t pp = 0, wall = 0;
  double launch_seconds = 0;
  for (const RealizationOutcome& o : r.outcomes) {
    pp += o.particle_collisions;
    wall += o.wall_hits;
    launch_seconds += o.seconds;
  }
  return {{"code_version", code_version()},
          {"provenance", provenance_json()},
          {"parameters",
           {{"setup", setup_name(s.setup)},
            {"N", s.params.N},
            {"e", s.params.e},
            {"k", number_or_null(s.params.k)},
            {"m", s.params.m},
            {"d", s.params.d},
            {"a", s.launch.a},
            {"v0", s.launch.v0},
            {"dv0", s.launch.dv0},
            {"stop", rule_name(s.rule)},
            {"realizations", s.realizations},
            {"seed", s.seed},
            {"engine", engine_name(s.engine.kind)},
            {"dt_factor", s.engine.dt_factor},
            {"tc", s.engine.hard.tc}}},
          {"derived", {{"D", number_or_null(r.law.D)}, {"tau_c", r.law.tau_c}}},
          {"observables",
           {{"n_tot", number_or_null(r.n_tot_mean)},
            {"n_tot_err", number_or_null(r.n_tot_error)},
            {"n_tot_min", r.n_tot_min},
            {"n_tot_max", r.n_tot_max},
            {"collapsed", r.collapsed},
            {"particle_collisions", pp},
            {"wall_hits", wall},
            {"grazing_contacts", r.grazing_contacts},
            {"held_contacts", r.held_contacts},
            {"one_body", r.one_body}}},
          // wall_seconds: over every sitting of a count carried over sittings; launch_seconds: the
          // launches' own times on their threads, summed (the count's CPU time, whatever the threads).
          {"cost", {{"wall_seconds", r.wall_seconds}, {"threads", s.threads}, {"launch_seconds", launch_seconds}}}};
}

}  // namespace granchain
