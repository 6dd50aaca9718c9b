// Reading a results store: the text of store/store_export.hpp's export_results (read-only), which
// the package's store.py turns into numpy arrays, and the CLI's value-list syntax for filters.
#include <fmt/format.h>

#include <cmath>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "config/input_error.hpp"
#include "config/value_list.hpp"
#include "reproduce/store_analysis.hpp"
#include "store/results_store.hpp"
#include "store/store_export.hpp"

namespace granchain::python {

namespace {

ExportTable table_of(const std::string& name) {
  if (name == "runs") return ExportTable::Runs;
  if (name == "profiles") return ExportTable::Profiles;
  if (name == "collapse") return ExportTable::Collapse;
  if (name == "realizations") return ExportTable::Realizations;
  throw InputError(fmt::format("--table = '{}' is not a table; valid: runs, profiles, collapse, realizations", name));
}

// The selected rows as CSV or JSON text, exactly as `granchain export` writes them. A missing or
// foreign store and a bad `where` raise ValueError with the CLI's message (its exit 2).
std::string export_text(const py::object& db, const std::string& table, const std::string& format,
                        const std::map<std::string, std::vector<double>>& values, const std::vector<std::string>& engines,
                        const std::string& where) {
  const std::string path = path_text(db, "--db");
  ExportSelection sel;
  sel.table = table_of(table);
  if (format != "csv" && format != "json") throw InputError(fmt::format("--format = '{}' is not a format; valid: csv, json", format));
  const bool collapse = sel.table == ExportTable::Collapse || sel.table == ExportTable::Realizations;
  for (const auto& [name, list] : values) {
    if (name != "N" && name != "e" && name != "k" && name != "T0" && name != "T")
      throw InputError(fmt::format("unknown filter '{}'; valid: N, e, k, T0, T, engine, where", name));
    if (collapse && (name == "T0" || name == "T"))
      throw InputError(fmt::format("--{}: collapse counts have no {}; valid filters for --table {}: N, e, k, engine, where",
                                   name, name, table));
    sel.values[name] = list;
  }
  sel.engines = engines;
  sel.where = where;
  std::string text;
  try {
    py::gil_scoped_release nogil;
    text = export_results(path, sel, format == "json" ? ExportFormat::Json : ExportFormat::Csv);
  } catch (const StoreError& e) {
    throw py::value_error(e.what());
  }
  return text;
}

// The analysis `granchain analyze --json` writes for the runs selected by N, T0 and engine, with
// fits over k >= k_min (reproduce/store_analysis.hpp), as JSON text.
std::string analyze_text(const py::object& db, const std::map<std::string, std::vector<double>>& values,
                         const std::vector<std::string>& engines, double k_min) {
  const std::string path = path_text(db, "--db");
  if (!(k_min >= 0 && std::isfinite(k_min)))
    throw InputError(fmt::format("--k-min = {} is out of range; valid range: finite k-min >= 0", k_min));
  ExportSelection sel;
  for (const auto& [name, list] : values) {
    if (name != "N" && name != "T0") throw InputError(fmt::format("unknown filter '{}'; valid: N, T0", name));
    sel.values[name] = list;
  }
  sel.engines = engines;
  std::string text;
  try {
    py::gil_scoped_release nogil;
    text = analyze_store(path, sel, k_min).json.dump();
  } catch (const StoreError& e) {
    throw py::value_error(e.what());
  }
  return text;
}

}  // namespace

void bind_store(py::module_& m) {
  m.def("_analyze_text", &analyze_text, py::arg("db"), py::arg("values") = std::map<std::string, std::vector<double>>{},
        py::arg("engines") = std::vector<std::string>{}, py::arg("k_min") = 0.0,
        "The JSON text of `granchain analyze --json` for the selected runs (store opened read-only).");
  m.def("_export_text", &export_text, py::arg("db"), py::arg("table") = "runs", py::arg("format") = "csv",
        py::arg("values") = std::map<std::string, std::vector<double>>{}, py::arg("engines") = std::vector<std::string>{},
        py::arg("where") = "",
        "The text `granchain export` writes for this selection (store opened read-only); values maps N, e, k, T0, T "
        "to accepted values.");
  m.def("_check_store", [](const py::object& db) {
    const std::string path = path_text(db, "--db");
    try {
      ResultsStore::preflight(path, ResultsStore::Access::ReadOnly);
    } catch (const StoreError& e) {
      throw py::value_error(e.what());
    }
    return path;
  }, py::arg("db"), "Checks, without changing anything, that db is a readable granchain store; returns its path.");
  m.def("parse_value_list", &parse_value_list, py::arg("text"), py::arg("option") = "value list",
        "The CLI's lists and ranges: '3,4,5', '0.80:0.90:0.002' (first:last:step), '1e4:1e12:x10' (geometric).");
  m.def("parse_name_list", &parse_name_list, py::arg("text"), "Names separated by commas, blanks dropped.");
}

}  // namespace granchain::python
