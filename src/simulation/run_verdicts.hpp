#pragma once
// The quality verdicts of a driven-column run, each a sentence its reader must see: the command
// line prints them as warnings under the summary, the run's JSON keeps them ("warnings"), the
// Python module raises them as granchain.QualityWarning.
#include <string>
#include <vector>

#include "simulation/driven_run.hpp"

namespace granchain {

// In this order, those that apply: n_coll's blocking found no plateau; the window is not
// stationary (the halves of n_coll or of the mean height differ by more than 3 standard errors);
// some profile error bars found no plateau. Empty for a run without reservations.
std::vector<std::string> run_warnings(const RunResult& r);

}  // namespace granchain
