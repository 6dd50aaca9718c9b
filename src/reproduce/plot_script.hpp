#pragma once
// The matplotlib scripts in plots/, run with Debian's /usr/bin/python3 (Python is for plotting only).
#include <string>
#include <vector>

namespace granchain {

// Runs plots/<script> with the arguments as a child process that dies with granchain (a killed
// reproduction leaves no script drawing behind it); the scripts write each figure whole or not at
// all. Returns "" on success, otherwise one line saying what went wrong: the script's last line
// of error output (a missing matplotlib, a full disk), or the signal that ended it.
std::string run_plot_script(const std::string& script, const std::vector<std::string>& args);

}  // namespace granchain
