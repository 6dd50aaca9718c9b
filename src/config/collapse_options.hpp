#pragma once
// The parameters of a collapse count (`granchain collapse`, `granchain.collapse`): one table of
// Parameter entries (config/parameter.hpp) and one function that reads and checks them, so that
// the command line and the Python module accept the same values with the same messages.
#include <map>
#include <string>
#include <vector>

#include "config/parameter.hpp"
#include "simulation/collapse_run.hpp"

namespace granchain {

// Every parameter of a collapse count, in the order of --help.
const std::vector<Parameter>& collapse_parameters();

// The parameters a collapse count keeps in the store's collapse_runs table (those with a store
// column), in table order: together they define the count (two rows with equal values hold the
// same count), and the table's parameter columns follow them (store/store_schema.cpp).
std::vector<const Parameter*> stored_collapse_parameters();
// Their values for one count (aligned with stored_collapse_parameters(); k = +inf for hard spheres).
std::vector<TypedValue> stored_collapse_values(const CollapseSpec& spec);

struct CollapseOptions {
  CollapseSpec base;      // everything but e and k
  std::vector<double> es;  // each e of the list, in order
  std::vector<double> ks;  // each k of the list; {inf} for the hard-sphere engine
};

// Reads `raw` (names as in collapse_parameters(); a name of no entry is refused with the known
// ones), fills in the defaults and checks every value and every combination: the engine's k and
// TC model, the launch's time scale, each contact against the engine's clock, the stop rule
// against the set-up, at most 1e9 launches. InputError on the first problem, one line naming the
// parameter and its valid range.
CollapseOptions resolve_collapse_options(const std::map<std::string, RawValue>& raw);

// A count goes into a results store by its stored parameters; the hard engine's collapse watch
// (collapse-collisions, collapse-time) is not among them, so a count with another watch than the
// default cannot be told apart there: InputError naming the parameter, for a count to be stored.
void check_storable(const CollapseSpec& spec);

}  // namespace granchain
