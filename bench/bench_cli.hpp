#pragma once
// Command-line parsing shared by the benchmark programs: bad input gives one line naming the
// parameter and its valid range and exit code 2, as granchain does.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <fmt/format.h>
#include <functional>
#include <optional>
#include <string>

namespace granchain::bench {

// Parses argv and runs `check` (which may throw CLI::ValidationError). Returns the exit code when
// the program should stop (help printed: 0; bad input: 2), or nothing when it should go on.
inline std::optional<int> parse_or_exit(CLI::App& app, int argc, char** argv, const std::string& program,
                                        const std::function<void()>& check = {}) {
  try {
    app.parse(argc, argv);
    if (check) check();
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::string msg = e.what();
    std::replace(msg.begin(), msg.end(), '\n', ' ');
    fmt::print(stderr, "{}: error: {} (see {} --help)\n", program, msg, program);
    return 2;
  }
  return std::nullopt;
}

// --repeat R of the micro-benchmarks: every timing is repeated R times and the fastest kept.
inline void add_repeat_option(CLI::App& app, int& repeat) {
  app.add_option("--repeat", repeat, "time every case this many times and keep the fastest")->check(CLI::Range(1, 100));
}

// Nanoseconds per call of body(c) over c = 0 .. calls - 1, the fastest of `repeat` timings.
template <class Body>
double fastest_ns_per_call(int repeat, int calls, Body&& body) {
  double best = 1e300;
  for (int r = 0; r < repeat; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int c = 0; c < calls; ++c) body(c);
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / calls);
  }
  return 1e9 * best;
}

}  // namespace granchain::bench
