#pragma once
// Command-line parsing shared by the benchmark programs: bad input gives one line naming the
// parameter and its valid range and exit code 2, as granchain does.
#include <CLI/CLI.hpp>
#include <algorithm>
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

}  // namespace granchain::bench
