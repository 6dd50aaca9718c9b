#pragma once
// Progress of a sweep on standard error: one line rewritten in place on a terminal, plain lines
// otherwise (a batch job's log). Shared by `granchain sweep`, `reproduce` and `collapse` (whose
// units are launches rather than points).
#include <string>

#include "sweep/sweep_runner.hpp"

namespace granchain {

// "4.2 s", "37 s", "3.5 min", "2.1 h"; "?" when not finite.
std::string format_duration(double seconds);

class SweepProgressPrinter {
 public:
  SweepProgressPrinter(bool tty, std::string label, std::string unit = "points")
      : tty_(tty), label_(std::move(label)), unit_(std::move(unit)) {}
  void operator()(const SweepProgress& p) const;

 private:
  bool tty_;
  std::string label_, unit_;
};

}  // namespace granchain
