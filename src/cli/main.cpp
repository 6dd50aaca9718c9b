// granchain: inelastic collapse in one-dimensional granular chains.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <vector>

#include "cli/subcommand.hpp"
#include "version.hpp"

namespace {

int standard_output_failed() {
  fmt::print(stderr, "granchain: error: cannot write standard output: {}; what it should have shown is incomplete\n",
             std::strerror(errno ? errno : EIO));
  return granchain::kExitStoreFailed;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"granchain: inelastic collapse of soft and hard spheres on a vertical line (Wakou et al.)"};
  app.set_version_flag("--version", granchain::code_version());
  app.require_subcommand(1);
  const std::vector<granchain::Subcommand> commands = {
      granchain::add_run_command(app),   granchain::add_theory_command(app), granchain::add_collapse_command(app),
      granchain::add_sweep_command(app), granchain::add_merge_command(app),  granchain::add_export_command(app),
      granchain::add_analyze_command(app), granchain::add_trace_command(app), granchain::add_reproduce_command(app)};
  const auto selected = [&]() -> const granchain::Subcommand* {
    for (const auto& c : commands)
      if (c.selected()) return &c;
    return nullptr;
  };
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
    const auto* c = selected();
    fmt::print(stderr, "granchain: error: {} (see granchain {}--help)\n", msg, c ? c->app->get_name() + " " : "");
    return granchain::kExitBadInput;
  }
  int rc = 0;
  try {
    if (const auto* c = selected()) rc = c->execute();
  } catch (const std::exception& e) {
    if (std::ferror(stdout)) return standard_output_failed();
    fmt::print(stderr, "granchain: error: {}\n", e.what());
    return 1;
  }
  // Whatever was printed must have reached standard output (a full disk, a closed pipe). A command
  // that failed has said so already.
  errno = 0;
  if ((std::fflush(stdout) != 0 || std::ferror(stdout)) && rc == granchain::kExitOk) return standard_output_failed();
  return rc;
}
