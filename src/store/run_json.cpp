#include "store/run_json.hpp"

#include "version.hpp"

namespace granchain {

using nlohmann::json;

json to_json(const Estimate& e) {
  return json{{"value", e.value}, {"error", e.error}, {"blocks", e.blocks}, {"converged", e.converged}};
}

json run_spec_to_json(const RunSpec& s) {
  return json{{"setup", "driven_column"},
              {"N", s.params.N},
              {"e", s.params.e},
              {"k", s.params.k},
              {"T0", s.params.kT0},
              {"m", s.params.m},
              {"d", s.params.d},
              {"g", s.params.g},
              {"T", s.T},
              {"transient", s.transient},
              {"seed", s.seed},
              {"engine", s.engine.name},
              {"dt_factor", s.engine.dt_factor},
              {"sample_interval", s.sample_interval},
              {"bins", s.bins}};
}

json run_result_to_json(const RunResult& r) {
  json profiles = json::array();
  for (std::size_t i = 0; i < r.profiles.size(); ++i) {
    const ParticleProfile& p = r.profiles[i];
    profiles.push_back({{"i", i + 1},
                        {"z_mean", p.z_mean.value},
                        {"z_mean_err", p.z_mean.error},
                        {"z_std", p.z_std.value},
                        {"z_std_err", p.z_std.error},
                        {"K", p.kinetic.value},
                        {"K_err", p.kinetic.error}});
  }
  return json{{"code_version", code_version()},
              {"parameters", run_spec_to_json(r.spec)},
              {"derived", {{"D", r.law.D}, {"tau_c", r.law.tau_c}, {"dt", r.time_step},
                           {"sample_interval", r.sample_interval}, {"samples", r.samples}}},
              {"observables", {{"n_coll", to_json(r.n_coll)},
                               {"floor_rate", to_json(r.floor_rate)},
                               {"pp_rate", to_json(r.pp_rate)},
                               {"particle_collisions", r.particle_collisions},
                               {"floor_hits", r.floor_hits}}},
              {"profiles", profiles},
              {"cost", {{"steps", r.steps}, {"events", r.events}, {"wall_seconds", r.wall_seconds}}}};
}

}  // namespace granchain
