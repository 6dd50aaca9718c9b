#pragma once
// The matplotlib scripts in plots/, run with Debian's /usr/bin/python3 (Python is for plotting only).
#include <string>
#include <vector>

namespace granchain {

// Runs plots/<script> with the arguments (each quoted for the shell). Returns "" on success,
// otherwise one line saying what went wrong.
std::string run_plot_script(const std::string& script, const std::vector<std::string>& args);

}  // namespace granchain
