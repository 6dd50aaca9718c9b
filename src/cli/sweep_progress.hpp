#pragma once
// Progress of a sweep on standard error: one line rewritten in place on a terminal, plain lines
// otherwise (a batch job's log). Shared by `granchain sweep` and `granchain reproduce`.
#include <string>

#include "sweep/sweep_runner.hpp"

namespace granchain {

// "4.2 s", "37 s", "3.5 min", "2.1 h"; "?" when not finite.
std::string format_duration(double seconds);

class SweepProgressPrinter {
 public:
  SweepProgressPrinter(bool tty, std::string label) : tty_(tty), label_(std::move(label)) {}
  void operator()(const SweepProgress& p) const;

 private:
  bool tty_;
  std::string label_;
};

}  // namespace granchain
