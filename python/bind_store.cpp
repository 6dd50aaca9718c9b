// Reading a results store: the rows of store/store_export.hpp's selection (read-only) as typed
// numpy columns, straight from SQLite (no text in between), and the CLI's value-list syntax for
// filters.
#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <sqlite3.h>
#include <variant>

#include "bindings.hpp"
#include "config/input_error.hpp"
#include "config/value_list.hpp"
#include "reproduce/store_analysis.hpp"
#include "store/results_store.hpp"
#include "store/sqlite_statement.hpp"
#include "store/store_export.hpp"

namespace granchain::python {

namespace {

using namespace pybind11::literals;

ExportTable table_of(const std::string& name) {
  if (name == "runs") return ExportTable::Runs;
  if (name == "profiles") return ExportTable::Profiles;
  if (name == "collapse") return ExportTable::Collapse;
  if (name == "realizations") return ExportTable::Realizations;
  throw InputError(fmt::format("--table = '{}' is not a table; valid: runs, profiles, collapse, realizations", name));
}

ExportSelection selection_of(const std::string& table, const std::map<std::string, std::vector<double>>& values,
                             const std::vector<std::string>& engines, const std::string& where) {
  ExportSelection sel;
  sel.table = table_of(table);
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
  return sel;
}

// One stored value as SQLite holds it.
using Cell = std::variant<std::monostate, std::int64_t, double, std::string>;

// A column as numpy takes it, typed by what the store holds: text if any value is text (NULL as
// ""), float64 if any is real (NULL as nan; k = inf for hard spheres stays inf), int64 if all are
// integers, float64 with nan for integers beside NULLs while they are exact in a double, else
// objects (None for NULL); nan throughout if every value is NULL.
py::object numpy_column(const std::vector<Cell>& cells) {
  bool text = false, real = false, integer = false, null = false, exact = true;
  for (const Cell& c : cells) {
    text |= std::holds_alternative<std::string>(c);
    real |= std::holds_alternative<double>(c);
    null |= std::holds_alternative<std::monostate>(c);
    if (const auto* i = std::get_if<std::int64_t>(&c)) {
      integer = true;
      exact &= *i > -(std::int64_t{1} << 53) && *i < (std::int64_t{1} << 53);
    }
  }
  const auto n = static_cast<py::ssize_t>(cells.size());
  const double nan = std::nan("");
  if (text) {
    py::list out;
    for (const Cell& c : cells) {
      const std::string t = std::holds_alternative<std::string>(c) ? std::get<std::string>(c)
                            : std::holds_alternative<double>(c)    ? fmt::format("{}", std::get<double>(c))
                            : std::holds_alternative<std::int64_t>(c) ? std::to_string(std::get<std::int64_t>(c))
                                                                       : std::string();
      out.append(py::reinterpret_steal<py::object>(PyUnicode_DecodeUTF8(t.data(), static_cast<py::ssize_t>(t.size()), "replace")));
    }
    return py::module_::import("numpy").attr("array")(out, "dtype"_a = "str");
  }
  if (real || (integer && null && exact) || !integer) {
    py::array_t<double> a(n);
    auto w = a.mutable_unchecked<1>();
    for (py::ssize_t i = 0; i < n; ++i) {
      const Cell& c = cells[static_cast<std::size_t>(i)];
      w(i) = std::holds_alternative<double>(c) ? std::get<double>(c)
             : std::holds_alternative<std::int64_t>(c) ? static_cast<double>(std::get<std::int64_t>(c))
                                                       : nan;
    }
    return a;
  }
  if (!null) {
    py::array_t<std::int64_t> a(n);
    auto w = a.mutable_unchecked<1>();
    for (py::ssize_t i = 0; i < n; ++i) w(i) = std::get<std::int64_t>(cells[static_cast<std::size_t>(i)]);
    return a;
  }
  py::list out;  // large integers beside NULLs: exact, None for NULL
  for (const Cell& c : cells) out.append(std::holds_alternative<std::int64_t>(c) ? py::object(py::int_(std::get<std::int64_t>(c))) : py::none());
  return py::module_::import("numpy").attr("array")(out, "dtype"_a = "object");
}

// The selected rows as [(column, numpy array), ...] in the export's column order (result_json
// left out, as the export leaves it), read in one statement from the store opened read-only.
py::list read_columns(const py::object& db, const std::string& table, const std::map<std::string, std::vector<double>>& values,
                      const std::vector<std::string>& engines, const std::string& where) {
  const std::string path = path_text(db, "--db");
  const ExportSelection sel = selection_of(table, values, engines, where);
  std::vector<std::string> names;
  std::vector<int> shown;
  std::vector<std::vector<Cell>> cells;
  try {
    py::gil_scoped_release nogil;
    SelectedRows rows(path, sel);
    SqlStatement& r = rows.row();
    for (int i = 0; i < r.columns(); ++i)
      if (std::string(r.column_name(i)) != "result_json") {
        names.emplace_back(r.column_name(i));
        shown.push_back(i);
      }
    cells.resize(shown.size());
    while (rows.next())
      for (std::size_t j = 0; j < shown.size(); ++j) {
        const int i = shown[j];
        switch (r.column_type(i)) {
          case SQLITE_NULL: cells[j].emplace_back(std::monostate{}); break;
          case SQLITE_INTEGER: cells[j].emplace_back(static_cast<std::int64_t>(r.column_int(i))); break;
          case SQLITE_FLOAT: cells[j].emplace_back(r.column_double(i)); break;
          default: cells[j].emplace_back(std::string(r.column_text(i)));
        }
      }
  } catch (const StoreError& e) {
    throw py::value_error(e.what());
  }
  py::list out;
  for (std::size_t j = 0; j < names.size(); ++j) out.append(py::make_tuple(names[j], numpy_column(cells[j])));
  return out;
}

// The analysis `granchain analyze --json` writes for the runs selected by N, e, k, T0, T and engine, with
// fits over k >= k_min (reproduce/store_analysis.hpp), as JSON text.
std::string analyze_text(const py::object& db, const std::map<std::string, std::vector<double>>& values,
                         const std::vector<std::string>& engines, double k_min) {
  const std::string path = path_text(db, "--db");
  if (!(k_min >= 0 && std::isfinite(k_min)))
    throw InputError(fmt::format("--k-min = {} is out of range; valid range: finite k-min >= 0", k_min));
  const ExportSelection sel = selection_of("runs", values, engines, "");
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
  m.def("_read_columns", &read_columns, py::arg("db"), py::arg("table") = "runs",
        py::arg("values") = std::map<std::string, std::vector<double>>{}, py::arg("engines") = std::vector<std::string>{},
        py::arg("where") = "",
        "The rows `granchain export` selects, as [(column, numpy array), ...] typed by the store's values (store opened read-only).");
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
