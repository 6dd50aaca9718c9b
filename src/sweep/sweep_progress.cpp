#include "sweep/sweep_progress.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdio>

namespace granchain {

std::string format_duration(double s) {
  if (!std::isfinite(s)) return "?";
  if (s < 10) return fmt::format("{:.1f} s", s);
  if (s < 120) return fmt::format("{:.0f} s", s);
  if (s < 7200) return fmt::format("{:.1f} min", s / 60);
  return fmt::format("{:.1f} h", s / 3600);
}

void SweepProgressPrinter::operator()(const SweepProgress& p) const {
  const std::string line = fmt::format("{}: {}/{} {}{}, elapsed {}, ETA {}, {:.3g} collisions/s", label_, p.done, p.total, unit_,
                                       p.failed ? fmt::format(" ({} failed{})", p.failed, p.collapsed ? fmt::format(", {} of them hard spheres' collapse", p.collapsed) : "") : "", format_duration(p.elapsed),
                                       p.final ? "0 s" : format_duration(p.eta), p.collisions_per_second);
  if (tty_) {
    fmt::print(stderr, "\r{:<100}{}", line, p.final ? "\n" : "");
  } else {
    fmt::print(stderr, "{}\n", line);
  }
  std::fflush(stderr);
}

}  // namespace granchain
