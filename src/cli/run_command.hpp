#pragma once
#include <CLI/CLI.hpp>

namespace granchain {

// Exit codes of the command line.
enum ExitCode : int {
  kExitOk = 0,
  kExitBadInput = 2,     // bad flag, value, config file or output path; nothing written
  kExitUnphysical = 3,   // the simulation turned unphysical; no result printed or stored
  kExitStoreFailed = 4,  // the results store could not be written; the run is not stored
};

// `granchain run`: registers its flags on the app; after app.parse(), execute() runs it and
// returns the exit code.
class RunCommand {
 public:
  explicit RunCommand(CLI::App& app);
  bool selected() const { return sub_->parsed(); }
  int execute();

 private:
  CLI::App* sub_;
  struct Impl;
  std::shared_ptr<Impl> impl_;
};

}  // namespace granchain
