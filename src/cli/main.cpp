// granchain: inelastic collapse in one-dimensional granular chains.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <exception>

#include "cli/collapse_command.hpp"
#include "cli/run_command.hpp"
#include "cli/theory_command.hpp"
#include "version.hpp"

int main(int argc, char** argv) {
  CLI::App app{"granchain: inelastic collapse of soft and hard spheres on a vertical line (Wakou et al.)"};
  app.set_version_flag("--version", granchain::code_version());
  app.require_subcommand(1);
  granchain::RunCommand run(app);
  granchain::TheoryCommand theory(app);
  granchain::CollapseCommand collapse(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::string msg = e.what();
    std::replace(msg.begin(), msg.end(), '\n', ' ');
    const char* sub = run.selected() ? "run " : theory.selected() ? "theory " : collapse.selected() ? "collapse " : "";
    fmt::print(stderr, "granchain: error: {} (see granchain {}--help)\n", msg, sub);
    return granchain::kExitBadInput;
  }
  try {
    if (run.selected()) return run.execute();
    if (theory.selected()) return theory.execute();
    if (collapse.selected()) return collapse.execute();
  } catch (const std::exception& e) {
    fmt::print(stderr, "granchain: error: {}\n", e.what());
    return 1;
  }
  return 0;
}
