#include "cli/plot_script.hpp"

#include <fmt/format.h>

#include <cstdlib>

#ifndef GRANCHAIN_PLOTS_DIR
#define GRANCHAIN_PLOTS_DIR "plots"
#endif

namespace granchain {

namespace {
std::string shell_quoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}
}  // namespace

std::string run_plot_script(const std::string& script, const std::vector<std::string>& args) {
  std::string cmd = "/usr/bin/python3 " + shell_quoted(std::string(GRANCHAIN_PLOTS_DIR) + "/" + script);
  for (const auto& a : args) cmd += " " + shell_quoted(a);
  cmd += " > /dev/null";
  if (std::system(cmd.c_str()) != 0)
    return fmt::format("drawing with plots/{} failed (it needs /usr/bin/python3 with matplotlib, which "
                       "scripts/install-deps.sh installs)", script);
  return "";
}

}  // namespace granchain
