#pragma once
// Exit codes of the command line. Only cli/ turns outcomes and errors into them; the layers below
// return outcomes (a figure's FigureStatus) or throw typed errors (InputError, StoreError,
// UnphysicalStateError, OutputError).
#include <string>

#include "cli/text_wrap.hpp"

namespace granchain {

enum ExitCode : int {
  kExitOk = 0,
  kExitBadInput = 2,     // bad flag, value, config file or output path; nothing written
  kExitUnphysical = 3,   // the simulation turned unphysical; no result printed or stored
  kExitStoreFailed = 4,  // an output (results store, file, standard output) could not be written; the message says what was kept
  kExitTimeLimit = 75,   // --time-limit left points for a repeat of the command (EX_TEMPFAIL: try again)
};

// The end of every command's --help: its exit codes, `own` being those it returns besides 0 with
// what each means for it, then the two every command shares (cli/interrupt_message.hpp); wrapped at
// 100 columns, as the footers are.
inline std::string exit_codes_help(const std::string& own) {
  return wrap_words("Exit codes: 0 ok" + (own.empty() ? std::string() : ", " + own) +
                        ", 130 interrupted by SIGINT (Ctrl-C), 143 by SIGTERM (a batch system's kill); an interrupted "
                        "command prints one line saying what was kept.",
                    100);
}

}  // namespace granchain
