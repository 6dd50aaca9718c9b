#pragma once
// How the driven column's parameter table is written (config/run_options.cpp and the tables it
// gathers, config/drive_options.cpp): an entry, how a run's spec holds it, how a raw value is read.
// Private to the config layer.
#include <fmt/format.h>

#include <functional>
#include <string>
#include <type_traits>
#include <variant>

#include "config/input_error.hpp"
#include "config/parameter.hpp"
#include "config/run_options.hpp"

namespace granchain {

namespace run_table {

// A parameter of the driven column: its entry, how a run's spec holds it (get, and set from a typed
// value whose range is already checked), and how a raw value is read (apply; by default read as
// the entry's type, then set).
struct Definition {
  Parameter info;
  bool nullable = false;  // its store column may be NULL: where it does not act, and in runs stored before it
  std::function<TypedValue(const RunSpec&)> get;
  std::function<void(RunSpec&, const TypedValue&)> set;
  std::function<void(RunOptions&, const Parameter&, const RawValue&)> apply;
  // Where it acts, if not by its engine scope alone (acts()): a drive's amplitude only with that drive.
  std::function<bool(const RunSpec&)> acts_in = {};
};

inline double as_real(const TypedValue& v) {
  if (const auto* i = std::get_if<long long>(&v)) return static_cast<double>(*i);
  if (const auto* x = std::get_if<double>(&v)) return *x;
  throw InputError(fmt::format("'{}' is not a number", std::get<std::string>(v)));
}

inline long long as_integer(const TypedValue& v) {
  if (const auto* i = std::get_if<long long>(&v)) return *i;
  if (const auto* x = std::get_if<double>(&v)) return static_cast<long long>(*x);
  throw InputError(fmt::format("'{}' is not a number", std::get<std::string>(v)));
}

// A real (integer) parameter held by `field` of the spec: `field(spec)` is a reference to it.
template <class Field>
Definition real(Parameter p, RunIdentity part, Field field) {
  p.type = ParameterType::Real;
  p.identity = part;
  return {std::move(p), false, [field](const RunSpec& s) -> TypedValue { return field(s); },
          [field](RunSpec& s, const TypedValue& v) { field(s) = as_real(v); }, {}};
}

template <class Field>
Definition integer(Parameter p, RunIdentity part, Field field) {
  p.type = ParameterType::Integer;
  p.identity = part;
  return {std::move(p), false,
          [field](const RunSpec& s) -> TypedValue { return static_cast<long long>(field(s)); },
          [field](RunSpec& s, const TypedValue& v) { field(s) = static_cast<std::remove_cvref_t<decltype(field(s))>>(as_integer(v)); },
          {}};
}

}  // namespace run_table

}  // namespace granchain
