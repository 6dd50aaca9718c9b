// Keyword arguments as typed values, parameter tables as dicts (bindings.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>

#include "bindings.hpp"

namespace granchain::python {

RawValue keyword_value(const py::handle& value, const Parameter* parameter) {
  PyObject* v = value.ptr();
  if (PyUnicode_Check(v)) return RawValue{value.cast<std::string>()};
  if (PyBool_Check(v)) return RawValue{std::string(py::str(value))};
  if (PyIndex_Check(v)) {  // int, numpy integers (a float array's __index__ fails: read as a float below)
    py::object i = py::reinterpret_steal<py::object>(PyNumber_Index(v));
    if (i) {
      int overflow = 0;
      const long long x = PyLong_AsLongLongAndOverflow(i.ptr(), &overflow);
      if (overflow == 0 && !(x == -1 && PyErr_Occurred())) return RawValue{x};
      PyErr_Clear();
      return RawValue{std::string(py::str(i))};
    }
    PyErr_Clear();
  }
  if (PyFloat_Check(v) || PyObject_HasAttrString(v, "__float__")) {  // float, numpy floats, 0-d arrays
    const double x = PyFloat_AsDouble(v);
    if (!(x == -1.0 && PyErr_Occurred())) {
      // An integer parameter written as a whole float (N=25.0, np.float32(4)) is that integer, as
      // Python users write it; a fraction (N=2.5) stays a real and is refused by the reading.
      if (parameter && parameter->type == ParameterType::Integer && std::isfinite(x) && x == std::floor(x) && std::abs(x) < 0x1p53)
        return RawValue{static_cast<long long>(x)};
      return RawValue{x};
    }
    PyErr_Clear();
  }
  return RawValue{std::string(py::str(value))};
}

std::string keyword_message(std::string message, const std::vector<Parameter>& table, const std::vector<std::string>& extra) {
  std::vector<std::string> names = extra;
  for (const Parameter& p : table) names.push_back(p.name);
  std::sort(names.begin(), names.end(), [](const std::string& a, const std::string& b) { return a.size() > b.size(); });
  const auto name_char = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_'; };
  const auto keyword = [](std::string n) {
    for (char& c : n)
      if (c == '-') c = '_';
    return n;
  };
  // "--name" -> "name" (as a keyword), then a hyphenated name standing alone ("dt-factor" in a range).
  for (const bool flag : {true, false})
    for (const std::string& n : names) {
      if (!flag && n.find('-') == std::string::npos) continue;
      const std::string from = flag ? "--" + n : n;
      for (std::size_t at = message.find(from); at != std::string::npos; at = message.find(from, at)) {
        const std::size_t end = at + from.size();
        const bool whole = (end == message.size() || !name_char(message[end])) && (flag || at == 0 || !name_char(message[at - 1]));
        if (!whole) {
          at = end;
          continue;
        }
        const std::string to = keyword(n);
        message.replace(at, from.size(), to);
        at += to.size();
      }
    }
  return message;
}

py::list parameter_list(const std::vector<Parameter>& table) {
  py::list out;
  for (const Parameter& p : table) {
    if (!(p.uses & kUsePython)) continue;
    py::dict d;
    d["name"] = p.name;
    d["help"] = p.help();
    d["type"] = p.type_name();
    d["unit"] = p.unit;
    d["range"] = p.range;
    d["default"] = p.fallback;
    d["engines"] = p.engines == EngineScope::Soft ? "soft" : p.engines == EngineScope::Hard ? "hard"
                   : p.engines == EngineScope::TimeStepped ? "time-stepped" : "any";
    d["sweep_axis"] = p.sweep_axis;
    d["store_column"] = p.store_column;
    out.append(d);
  }
  return out;
}

std::map<std::string, py::object> flag_arguments(const py::kwargs& kwargs) {
  std::map<std::string, py::object> out;
  for (const auto& [key, value] : kwargs) {
    if (value.is_none()) continue;
    std::string name = py::str(key);
    for (char& c : name)
      if (c == '_') c = '-';
    out[name] = py::reinterpret_borrow<py::object>(value);
  }
  return out;
}

std::optional<py::object> take(std::map<std::string, py::object>& args, const std::string& name) {
  const auto it = args.find(name);
  if (it == args.end()) return std::nullopt;
  py::object v = it->second;
  args.erase(it);
  return v;
}

std::string path_text(const py::handle& value, const std::string& option, const std::string& what) {
  py::object p = py::reinterpret_borrow<py::object>(value);
  if (!PyUnicode_Check(p.ptr())) {
    try {
      p = py::module_::import("os").attr("fspath")(value);
    } catch (const py::error_already_set&) {
      throw py::value_error(fmt::format("{}: expected a path (str or os.PathLike), got {}", option,
                                        std::string(py::str(py::type::of(value).attr("__name__")))));
    }
    if (!PyUnicode_Check(p.ptr())) p = p.attr("decode")();
  }
  const std::string text = p.cast<std::string>();
  if (text.empty()) throw py::value_error(fmt::format("{}: the path is empty; give a {}", option, what));
  return text;
}

}  // namespace granchain::python
