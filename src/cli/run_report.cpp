#include "cli/run_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "cli/text_wrap.hpp"
#include "simulation/run_verdicts.hpp"

namespace granchain {

std::string run_summary(const RunResult& r, const std::string& stored) {
  const RunSpec& s = r.spec;
  const ChainParameters& p = s.params;
  std::string out;
  out += fmt::format("granchain run: driven column, engine {}", engine_name(s.engine.kind));
  if (r.time_step > 0) out += fmt::format(" (dt = tau_c/{:g} = {:.4g})", s.engine.dt_factor, r.time_step);
  out += "\n";
  out += fmt::format("  N = {}, e = {:g}, k = {:g}, kT0 = {:g}   (m = {:g}, d = {:g}, g = {:g})\n", p.N, p.e, p.k, p.kT0, p.m, p.d, p.g);
  if (s.drive.plate()) {
    const double period = 2.0 * std::numbers::pi / s.drive.omega;
    out += fmt::format("  drive: {} plate, A = {:.6g}, omega = {:.6g} (period {:.6g}", drive_name(s.drive.kind), s.drive.A,
                       s.drive.omega, period);
    if (s.drive.kind != DriveKind::Sawtooth)
      out += fmt::format(", Gamma = {:.6g}", gamma_factor(s.drive.kind) * s.drive.A * s.drive.omega * s.drive.omega / p.g);
    out += "), random phase\n";
  }
  out += fmt::format("  D = {:.6g}, tau_c = {:.6g}; transient {:g}, measuring window T = {:g}, seed {}\n", r.law.D,
                     r.law.tau_c, s.transient, s.T, s.seed);
  out += "\n";
  out += fmt::format("  n_coll      = {}   collisions per particle per unit time ({} blocks)\n", format_estimate(r.n_coll), r.n_coll.blocks);
  out += fmt::format("  floor rate  = {}   floor hits per unit time\n", format_estimate(r.floor_rate));
  out += fmt::format("  pair rate   = {}   particle-particle collisions per unit time\n", format_estimate(r.pp_rate));
  out += fmt::format("  in window: {} particle-particle collisions, {} floor hits; {} profile samples every {:.4g}\n",
                     r.particle_collisions, r.floor_hits, r.samples, r.sample_interval);
  for (const std::string& w : run_warnings(r)) out += wrap_words(w, 88, "  warning: ", std::string(11, ' ')) + "\n";
  // Beside particle i, its contact with i + 1 (soft spheres): the mean and longest duration in units
  // of tau_c and the fraction of the window the pair spends in contact.
  const bool contacts = !r.contacts.empty();
  out += fmt::format("\n     i  <z_i>                 sigma_i               K_i{}\n",
                     contacts ? "                   contact (i, i+1): mean, longest / tau_c, time in contact" : "");
  const auto contact_text = [&](std::size_t slot) -> std::string {
    if (slot >= r.contacts.size()) return "";
    const PairContacts& c = r.contacts[slot];
    if (c.contacts == 0 && c.open_at_end == 0) return "  —";
    return fmt::format("  {:<7.3g} {:<9.3g} {:.3g}", c.mean, c.longest, c.contact_fraction);
  };
  if (contacts && s.drive.plate()) out += fmt::format("  plate {:<65}{}\n", "", contact_text(0));
  for (std::size_t i = 0; i < r.profiles.size(); ++i) {
    const ParticleProfile& q = r.profiles[i];
    out += fmt::format("  {:4d}  {:<21} {:<21} {:<21}{}\n", i + 1, format_estimate(q.z_mean), format_estimate(q.z_std),
                       format_estimate(q.kinetic), contact_text(i + 1));
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
