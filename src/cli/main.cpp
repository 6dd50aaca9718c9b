// granchain: inelastic collapse in one-dimensional granular chains.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <string>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>
#include <vector>

#include "cli/subcommand.hpp"
#include "cli/suggest.hpp"
#include "config/input_error.hpp"
#include "version.hpp"
#include "provenance.hpp"

namespace {

// For a parse error caused by a mistyped name: "'swep' is not a command; did you mean 'sweep'?" or
// "--NN is not a flag of run; did you mean --N?", else "".
std::string suggestion(const CLI::App& app, const CLI::App* sub, int argc, char** argv) {
  if (!sub) {
    std::vector<std::string> names;
    std::string list;
    for (const CLI::App* s : app.get_subcommands([](const CLI::App*) { return true; })) {
      names.push_back(s->get_name());
      list += (list.empty() ? "" : ", ") + s->get_name();
    }
    if (argc < 2 || argv[1][0] == '-') return fmt::format("name a command first; commands: {}", list);
    const std::string near = granchain::nearest_name(argv[1], names);
    return near.empty() ? fmt::format("'{}' is not a command; commands: {}", argv[1], list)
                        : fmt::format("'{}' is not a command; did you mean '{}'?", argv[1], near);
  }
  std::vector<std::string> flags;
  for (const CLI::Option* o : sub->get_options())
    for (const std::string& l : o->get_lnames()) flags.push_back("--" + l);
  for (int i = 2; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg.rfind("--", 0) != 0) continue;
    arg = arg.substr(0, arg.find('='));
    if (std::find(flags.begin(), flags.end(), arg) != flags.end()) continue;
    const std::string near = granchain::nearest_name(arg, flags);
    return near.empty() ? fmt::format("{} is not a flag of {}", arg, sub->get_name())
                        : fmt::format("{} is not a flag of {}; did you mean {}?", arg, sub->get_name(), near);
  }
  return "";
}

// CLI11's own words for a value it cannot take, in granchain's: the flag, the value as given, and
// where its range is written.
std::string plain_parse_message(const std::string& msg) {
  const std::string convert = "Could not convert: ";
  if (msg.rfind(convert, 0) == 0) {
    const std::string rest = msg.substr(convert.size());  // "--a = abc"
    const std::size_t eq = rest.find(" = ");
    if (eq != std::string::npos)
      return fmt::format("{} = '{}' is not a number of the kind it takes (its valid range is in its help)", rest.substr(0, eq),
                         rest.substr(eq + 3));
  }
  if (const std::size_t at = msg.find(": At Most 1 required but received"); at != std::string::npos)
    return fmt::format("{} is given more than once; give it once", msg.substr(0, at));
  if (msg == "sources is required") return "merge: name at least one source store (granchain merge --into ALL.db SOURCE.db ...)";
  return msg;
}

int standard_output_failed() {
  fmt::print(stderr, "granchain: error: cannot write standard output: {}; what it should have shown is incomplete\n",
             std::strerror(errno ? errno : EIO));
  return granchain::kExitStoreFailed;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"granchain: inelastic collapse of soft and hard spheres on a vertical line (Wakou et al.)"};
  app.set_version_flag("--version", fmt::format("granchain {}\n{}", granchain::code_version(), granchain::build_settings()));
  granchain::set_invocation(argc, argv);
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
    const std::string hint = suggestion(app, c ? c->app : nullptr, argc, argv);
    if (hint.empty()) msg = plain_parse_message(msg);
    fmt::print(stderr, "granchain: error: {} (see granchain {}--help)\n", hint.empty() ? msg : hint, c ? c->app->get_name() + " " : "");
    return granchain::kExitBadInput;
  }
  int rc = 0;
  try {
    if (const auto* c = selected()) rc = c->execute();
  } catch (const granchain::InputError& e) {  // bad input found late: nothing was written
    fmt::print(stderr, "granchain: error: {}\n", e.what());
    return granchain::kExitBadInput;
  } catch (const std::bad_alloc&) {
    fmt::print(stderr, "granchain: error: not enough memory for what was asked (fewer particles, bins, launches or "
                       "values per list need less); what was stored before is kept\n");
    return granchain::kExitBadInput;
  } catch (const std::exception& e) {
    // Each command turns its expected failures into its own message and code; reaching this is a
    // fault of granchain, reported with the exit code of a failed output.
    if (std::ferror(stdout)) return standard_output_failed();
    fmt::print(stderr, "granchain: error: internal error ({}); the command stopped, what was stored before is kept; please "
                       "report it with the command line\n", e.what());
    return granchain::kExitStoreFailed;
  }
  // Whatever was printed must have reached standard output (a full disk, a closed pipe). A command
  // that failed has said so already.
  errno = 0;
  if ((std::fflush(stdout) != 0 || std::ferror(stdout)) && rc == granchain::kExitOk) return standard_output_failed();
  return rc;
}
