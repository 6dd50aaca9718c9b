#include "cli/run_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace granchain {

std::string format_with_error(double value, double error) {
  if (!std::isfinite(error) || error <= 0) return fmt::format("{:.6g}", value);
  const int exponent = static_cast<int>(std::floor(std::log10(error)));
  const int decimals = std::max(0, 1 - exponent);
  if (decimals > 12 || std::abs(value) >= 1e7 || (value != 0 && std::abs(value) < 1e-4))
    return fmt::format("{:.6g} ± {:.2g}", value, error);
  return fmt::format("{:.{}f} ± {:.{}f}", value, decimals, error, decimals);
}

std::string format_estimate(const Estimate& e) { return format_with_error(e.value, e.error); }

std::string run_summary(const RunResult& r, const std::string& stored) {
  const RunSpec& s = r.spec;
  const ChainParameters& p = s.params;
  std::string out;
  out += fmt::format("granchain run: driven column, engine {}", engine_name(s.engine.kind));
  if (r.time_step > 0) out += fmt::format(" (dt = tau_c/{:g} = {:.4g})", s.engine.dt_factor, r.time_step);
  out += "\n";
  out += fmt::format("  N = {}, e = {:g}, k = {:g}, kT0 = {:g}   (m = {:g}, d = {:g}, g = {:g})\n", p.N, p.e, p.k, p.kT0, p.m, p.d, p.g);
  out += fmt::format("  D = {:.6g}, tau_c = {:.6g}; transient {:g}, measuring window T = {:g}, seed {}\n", r.law.D,
                     r.law.tau_c, s.transient, s.T, s.seed);
  out += "\n";
  out += fmt::format("  n_coll      = {}   collisions per particle per unit time ({} blocks)\n", format_estimate(r.n_coll), r.n_coll.blocks);
  out += fmt::format("  floor rate  = {}   floor hits per unit time\n", format_estimate(r.floor_rate));
  out += fmt::format("  pair rate   = {}   particle-particle collisions per unit time\n", format_estimate(r.pp_rate));
  out += fmt::format("  in window: {} particle-particle collisions, {} floor hits; {} profile samples every {:.4g}\n",
                     r.particle_collisions, r.floor_hits, r.samples, r.sample_interval);
  if (!r.n_coll.converged)
    out += "  warning: the blocking analysis of n_coll found no plateau; T may be short compared with the\n"
           "           correlation time, so its error bar may be too small\n";
  if (!r.stationary()) {
    auto line = [](const char* what, const StationarityCheck& c) {
      return fmt::format("           {}: first half {}, second half {} (z = {:.1f})\n", what,
                         format_estimate(c.first), format_estimate(c.second), c.z);
    };
    out += "  warning: the measuring window is not stationary (the halves differ by more than 3 standard\n"
           "           errors): the column had not settled, or drifts; the errors are not to be trusted\n";
    if (!r.n_coll_halves.stationary) out += line("n_coll", r.n_coll_halves);
    if (!r.height_halves.stationary) out += line("mean height", r.height_halves);
  }
  int unconverged = 0;
  for (const ParticleProfile& q : r.profiles)
    unconverged += !q.z_mean.converged + !q.z_std.converged + !q.kinetic.converged;
  if (unconverged > 0)
    out += fmt::format("  warning: {} of {} profile error bars found no blocking plateau (lower bounds; run longer)\n",
                       unconverged, 3 * r.profiles.size());
  out += "\n     i  <z_i>                 sigma_i               K_i\n";
  for (std::size_t i = 0; i < r.profiles.size(); ++i) {
    const ParticleProfile& q = r.profiles[i];
    out += fmt::format("  {:4d}  {:<21} {:<21} {:<21}\n", i + 1, format_estimate(q.z_mean), format_estimate(q.z_std),
                       format_estimate(q.kinetic));
  }
  out += "\n";
  out += fmt::format("  cost: {} steps, {} events, {:.3g} s wall, {:.3g} s CPU\n", r.steps, r.events, r.wall_seconds, r.cpu_seconds);
  if (r.spec.engine.audit)
    out += fmt::format("  audit: {} values at {} instants between events, none of the wrong sign\n", r.audit_values,
                       r.audit_instants);
  if (!stored.empty()) out += fmt::format("  stored: {}\n", stored);
  return out;
}

}  // namespace granchain
