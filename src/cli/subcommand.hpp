#pragma once
// The subcommands of `granchain`. Each add_*_command registers its flags on the app and returns
// the subcommand with the function that runs it once the command line has been parsed.
#include <CLI/CLI.hpp>

#include <functional>

#include "cli/exit_codes.hpp"

namespace granchain {

struct Subcommand {
  CLI::App* app = nullptr;
  std::function<int()> execute;  // returns the exit code
  bool selected() const { return app->parsed(); }
};

Subcommand add_run_command(CLI::App& app);       // one driven-column run
Subcommand add_theory_command(CLI::App& app);    // the paper's closed forms
Subcommand add_collapse_command(CLI::App& app);  // free-space and wall collapse counts
Subcommand add_sweep_command(CLI::App& app);     // grids of runs: threads, MPI, shards, resuming
Subcommand add_merge_command(CLI::App& app);     // joining results stores
Subcommand add_export_command(CLI::App& app);    // stored results as CSV or JSON
Subcommand add_analyze_command(CLI::App& app);   // regimes and critical values from stored runs
Subcommand add_trace_command(CLI::App& app);     // space-time diagrams z_i(t)
Subcommand add_reproduce_command(CLI::App& app); // the paper's figures with a report

}  // namespace granchain
