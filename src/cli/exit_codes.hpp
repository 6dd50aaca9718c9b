#pragma once
// Exit codes of the command line. Only cli/ turns outcomes and errors into them; the layers below
// return outcomes (a figure's FigureStatus) or throw typed errors (InputError, StoreError,
// UnphysicalStateError, OutputError).
namespace granchain {

enum ExitCode : int {
  kExitOk = 0,
  kExitBadInput = 2,     // bad flag, value, config file or output path; nothing written
  kExitUnphysical = 3,   // the simulation turned unphysical; no result printed or stored
  kExitStoreFailed = 4,  // an output (results store, file, standard output) could not be written; the message says what was kept
  kExitTimeLimit = 75,   // --time-limit left points for a repeat of the command (EX_TEMPFAIL: try again)
};

}  // namespace granchain
