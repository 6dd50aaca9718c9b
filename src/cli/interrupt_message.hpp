#pragma once
// What a command says when it is interrupted (Ctrl-C, SIGTERM from a batch system): one line on
// standard error saying what was kept and how to resume, then the process ends by that signal as
// before (exit status 130 for SIGINT, 143 for SIGTERM), so the results store's transactions and
// the shell's conventions are untouched.
#include <string>
#include <vector>

#include "simulation/cancellation.hpp"

namespace granchain {

// Installs handlers for SIGINT and SIGTERM that print
// "granchain: interrupted by SIGINT|SIGTERM; <what_was_kept>", remove `unfinished_file` (a
// temporary file being written, if any) and then re-raise the signal.
void announce_on_interrupt(const std::string& what_was_kept, const std::string& unfinished_file = "");
// The same with up to four unfinished files.
void announce_on_interrupt(const std::string& what_was_kept, const std::vector<std::string>& unfinished_files);

// For a run that saves its state before it stops (run --checkpoint): SIGINT and SIGTERM are only
// recorded, recorded_interrupt() returns the signal (0 before any), and the caller stops at its
// next sample, saves, says so and ends by the signal with reraise_interrupt. A second signal ends
// the process at once (the default action), the checkpoint as last saved. A call of
// announce_on_interrupt puts the handlers back. `also_set` (if given) is set too, for work that
// watches a CancelFlag (a sweep's points).
void record_interrupts(CancelFlag* also_set = nullptr);
int recorded_interrupt();
[[noreturn]] void reraise_interrupt(int sig);
// "SIGINT" or "SIGTERM".
const char* interrupt_name(int sig);

}  // namespace granchain
