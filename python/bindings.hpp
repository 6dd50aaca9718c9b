#pragma once
// Shared pieces of the extension _granchain: keyword arguments read the way the command line
// reads its flags, and the functions that add each group of bindings to the module.
#include <pybind11/pybind11.h>

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "config/parameter.hpp"

namespace granchain::python {

namespace py = pybind11;

// A keyword argument as a typed value (config/parameter.hpp): a Python int (or anything with
// __index__: numpy integers) as an integer, a float (or anything with __float__: numpy floats, a
// 0-d array) as a real number, or as an integer where `parameter` is an integer one and the value
// whole (N=25.0), a str as text; True and False, and integers beyond 64 bits, as their text, which
// every numeric parameter refuses with the CLI's message.
RawValue keyword_value(const py::handle& value, const Parameter* parameter);

// A message of bad input as a Python caller reads it: each parameter of `table` (and each name of
// `extra`) written as a flag, "--dt-factor", becomes its keyword, "dt_factor", and a hyphenated
// name standing alone (in a valid range) the same: "dt_factor = 5 is out of range; valid range:
// 10 <= dt_factor <= 1e6".
std::string keyword_message(std::string message, const std::vector<Parameter>& table, const std::vector<std::string>& extra = {});

// The entries of a parameter table (config/parameter.hpp) that the Python module takes, as dicts:
// name, help, type, unit, range, default, engines, sweep_axis, store_column.
py::list parameter_list(const std::vector<Parameter>& table);

// Keyword arguments by flag name: '_' reads as '-' (dt_factor -> dt-factor); None means "not
// given" and is dropped.
std::map<std::string, py::object> flag_arguments(const py::kwargs& kwargs);

// Takes `name` out of `args` (nullopt if absent).
std::optional<py::object> take(std::map<std::string, py::object>& args, const std::string& name);

// A path argument (str or os.PathLike) as text; ValueError naming `option` otherwise.
std::string path_text(const py::handle& value, const std::string& option, const std::string& what = "file name");

// Runs `work` on a thread of its own without the GIL while the calling thread wakes every 0.1 s
// to look for Ctrl-C and, every `progress_every` seconds, calls `progress` (if set). A
// KeyboardInterrupt (or an exception from progress) sets `cancel`, which the work reads between its
// events (simulation/cancellation.hpp), and is returned once the work has ended: the caller
// returns what finished and marks it interrupted (a KeyboardInterrupt; the package raises
// granchain.Interrupted) or rethrows it. An exception from the work itself is rethrown.
std::optional<py::error_already_set> run_interruptible(std::atomic<bool>& cancel, const std::function<void()>& work,
                                                       const std::function<void()>& progress = {}, double progress_every = 0.5);

// A driven-column result as the dict run() returns (bind_run.cpp); db "" when not stored.
}  // namespace granchain::python
namespace granchain { struct RunResult; }
namespace granchain::python {
py::dict run_result_dict(const RunResult& r, const std::string& json_text, const std::string& db, std::int64_t run_id);

// The groups of functions; module.cpp calls each.
void bind_run(py::module_& m);
void bind_collapse(py::module_& m);
void bind_theory(py::module_& m);
void bind_store(py::module_& m);
void bind_analysis(py::module_& m);
void bind_sweep(py::module_& m);
void bind_trace(py::module_& m);

}  // namespace granchain::python
