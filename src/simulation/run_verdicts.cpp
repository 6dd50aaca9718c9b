#include "simulation/run_verdicts.hpp"

#include <fmt/format.h>

#include "analysis/estimate_format.hpp"

namespace granchain {

std::vector<std::string> run_warnings(const RunResult& r) {
  std::vector<std::string> out;
  if (!r.n_coll.converged)
    out.push_back("the blocking analysis of n_coll found no plateau; T may be short compared with the correlation time, so "
                  "its error bar may be too small");
  if (!r.stationary()) {
    std::string w = "the measuring window is not stationary (the halves differ by more than 3 standard errors, of both halves or of "
                    "the settled second half alone): the column "
                    "had not settled, or drifts; the errors are not to be trusted";
    const auto halves = [&w](const char* what, const StationarityCheck& c) {
      if (!c.stationary)
        w += fmt::format("; {}: first half {}, second half {} (z = {:.1f}, z_settled = {:.1f})", what, format_estimate(c.first),
                         format_estimate(c.second), c.z, c.z_settled);
    };
    halves("n_coll", r.n_coll_halves);
    halves("mean height", r.height_halves);
    out.push_back(w);
  }
  int unconverged = 0;
  for (const ParticleProfile& q : r.profiles) unconverged += !q.z_mean.converged + !q.z_std.converged + !q.kinetic.converged;
  if (unconverged > 0)
    out.push_back(fmt::format("{} of {} profile error bars found no blocking plateau (lower bounds; run longer)", unconverged,
                              3 * r.profiles.size()));
  return out;
}

}  // namespace granchain
