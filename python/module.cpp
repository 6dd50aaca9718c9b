// The extension _granchain, imported by the package granchain (python/granchain/__init__.py).
// C++ errors become Python exceptions: bad input (InputError) ValueError with the CLI's one-line
// message (run and collapse name parameters by keyword: keyword_message); an unphysical simulation
// granchain.UnphysicalStateError (a RuntimeError, the CLI's exit 3); a store that cannot be written
// granchain.StoreError (an OSError, the CLI's exit 4); a file that cannot be written (a checkpoint)
// OSError.
#include "analysis/estimate_format.hpp"
#include "bindings.hpp"
#include "config/input_error.hpp"
#include "engines/engine.hpp"
#include "store/output_file.hpp"
#include "store/results_store.hpp"
#include "provenance.hpp"
#include "version.hpp"

namespace py = pybind11;
using namespace granchain;

PYBIND11_MODULE(_granchain, m) {
  m.doc() = "granchain: inelastic collapse in one-dimensional granular chains (compiled part; use the package granchain)";
  m.attr("__version__") = code_version();
  m.attr("build_settings") = build_settings();
  // The provenance of every result the module returns or stores names the Python program.
  m.def("_set_invocation", &set_invocation_text, py::arg("command_line"));
  // "12.345 ± 0.012" as the command line prints a value with its error (the results' reprs).
  m.def("_format_with_error", &format_with_error, py::arg("value"), py::arg("error"));

  // The module's attributes keep the two classes alive; the translator needs only their pointers.
  static PyObject* unphysical = py::exception<UnphysicalStateError>(m, "UnphysicalStateError", PyExc_RuntimeError).ptr();
  static PyObject* store_error = py::exception<StoreError>(m, "StoreError", PyExc_OSError).ptr();
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const UnphysicalStateError& e) {
      PyErr_SetString(unphysical, e.what());
    } catch (const StoreError& e) {
      PyErr_SetString(store_error, e.what());
    } catch (const OutputError& e) {  // a file that cannot be written (a checkpoint): the CLI's exit 4
      PyErr_SetString(PyExc_OSError, e.what());
    }
  });

  granchain::python::bind_run(m);
  granchain::python::bind_collapse(m);
  granchain::python::bind_theory(m);
  granchain::python::bind_store(m);
  granchain::python::bind_analysis(m);
  granchain::python::bind_sweep(m);
  granchain::python::bind_trace(m);
}
