#include "config/parameter.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <cstdlib>

#include "config/input_error.hpp"
#include "config/value_list.hpp"
#include "engines/engine_registry.hpp"

namespace granchain {

namespace {

std::string strip(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t");
  std::string out = s.substr(b, e - b + 1);
  if (!out.empty() && out.front() == '+') out.erase(0, 1);
  return out;
}

const std::string* text_of(const RawValue& v) { return std::get_if<std::string>(&v.value); }

// The value as a finite number (text read strictly, whole), before any range check.
double finite_number(const Parameter& p, const RawValue& v) {
  double x = 0;
  if (const auto* raw = text_of(v)) {
    const std::string t = strip(*raw);
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), x);
    if (!t.empty() && ec == std::errc::result_out_of_range && end == t.data() + t.size())  // beyond a double, or below its least
      throw InputError(fmt::format("--{} = '{}'{} is out of range: {}; valid range: {}", p.name, *raw, from_where(v),
                                   std::abs(std::strtod(t.c_str(), nullptr)) > 1 ? "larger than the largest double"
                                                                                 : "smaller than the least positive double",
                                   p.range));
    if (t.empty() || ec != std::errc() || end != t.data() + t.size())
      throw InputError(fmt::format("--{} = '{}'{} is not a number; valid range: {}", p.name, *raw, from_where(v), p.range));
  } else if (const auto* i = std::get_if<long long>(&v.value)) {
    x = static_cast<double>(*i);
  } else {
    x = std::get<double>(v.value);
  }
  if (!std::isfinite(x))
    throw InputError(fmt::format("--{} = '{}'{} is not finite; valid range: {}", p.name, v.text(), from_where(v), p.range));
  return x;
}

}  // namespace

std::string RawValue::text() const {
  if (const auto* t = std::get_if<std::string>(&value)) return strip(*t);
  if (const auto* i = std::get_if<long long>(&value)) return fmt::format("{}", *i);
  return real_text(std::get<double>(value));
}

std::string real_text(double x) {
  std::string t = fmt::format("{}", x);
  if (t.find_first_of(".eEn") == std::string::npos) t += ".0";
  return t;
}

std::string from_where(const RawValue& v) { return v.source.empty() ? "" : " (from " + v.source + ")"; }

void value_out_of_range(const std::string& name, const RawValue& v, const std::string& range) {
  throw InputError(fmt::format("--{} = {}{} is out of range; valid range: {}", name, v.text(), from_where(v), range));
}

std::string Parameter::help() const { return meaning + "; " + range + (fallback.empty() ? "" : "; default " + fallback); }

std::string Parameter::type_name() const {
  switch (type) {
    case ParameterType::Integer: return "INT";
    case ParameterType::Real: return "REAL";
    case ParameterType::Name: return "NAME";
    case ParameterType::Path: return "PATH";
    case ParameterType::RealList: return "LIST";
  }
  return "";
}

double read_real(const Parameter& p, const RawValue& v) {
  const double x = finite_number(p, v);
  if (p.valid && !p.valid(x)) value_out_of_range(p.name, v, p.range);
  return x;
}

long long read_integer(const Parameter& p, const RawValue& v) {
  long long x = 0;
  if (const auto* raw = text_of(v)) {
    const std::string t = strip(*raw);
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), x);
    if (!t.empty() && ec == std::errc::result_out_of_range && end == t.data() + t.size())
      throw InputError(fmt::format("--{} = '{}'{} is out of range; valid range: {}", p.name, *raw, from_where(v), p.range));
    if (t.empty() || ec != std::errc() || end != t.data() + t.size())
      throw InputError(fmt::format("--{} = '{}'{} is not an integer; valid range: {}", p.name, *raw, from_where(v), p.range));
  } else if (const auto* i = std::get_if<long long>(&v.value)) {
    x = *i;
  } else {  // a real number is an integer only as text says so: 3.0 is refused as "3.0" is
    throw InputError(fmt::format("--{} = '{}'{} is not an integer; valid range: {}", p.name, v.text(), from_where(v), p.range));
  }
  if (p.valid && !p.valid(static_cast<double>(x)))
    throw InputError(fmt::format("--{} = '{}'{} is out of range; valid range: {}", p.name, v.text(), from_where(v), p.range));
  return x;
}

std::string read_name(const Parameter& p, const RawValue& v) {
  if (const auto* raw = text_of(v)) return strip(*raw);
  throw InputError(fmt::format("--{} = {}{} is not a name; valid: {}", p.name, v.text(), from_where(v), p.range));
}

std::vector<double> read_real_list(const Parameter& p, const RawValue& v) {
  std::vector<double> xs;
  if (const auto* raw = text_of(v)) {
    xs = parse_value_list(*raw, "--" + p.name + from_where(v));
  } else {
    xs = {finite_number(p, v)};
  }
  for (double x : xs)  // a list's message names the value: "--e: 2 is out of range"
    if (!std::isfinite(x) || (p.valid && !p.valid(x)))
      throw InputError(fmt::format("--{}: {}{} is out of range; valid range: {}", p.name, x, from_where(v), p.range));
  return xs;
}

std::string rounded_bound(double x, bool upper) {
  if (!(x > 0) || !std::isfinite(x)) return fmt::format("{:.3g}", x);
  const double unit = std::pow(10.0, std::floor(std::log10(x)) - 2);
  return fmt::format("{:.3g}", (upper ? std::floor(x / unit) : std::ceil(x / unit)) * unit);
}

void check_engine_scope(const std::vector<Parameter>& table, const std::map<std::string, RawValue>& raw, const EngineInfo& engine) {
  for (const Parameter& p : table) {
    if (!raw.count(p.name)) continue;
    if (p.engines == EngineScope::Soft && engine.hard_spheres)
      throw InputError(fmt::format("--{}: {}; leave --{} out", p.name, p.scope_note, p.name));
    if (p.engines == EngineScope::Hard && !engine.hard_spheres)
      throw InputError(fmt::format("--{}: {} belongs to --engine hard", p.name, p.scope_note));
  }
}

const Parameter* find_parameter(const std::vector<Parameter>& table, const std::string& name) {
  for (const Parameter& p : table)
    if (p.name == name) return &p;
  return nullptr;
}

std::string parameter_names(const std::vector<Parameter>& table, unsigned uses) {
  std::string names;
  for (const Parameter& p : table)
    if (p.uses & uses) names += (names.empty() ? "" : ", ") + p.name;
  return names;
}

}  // namespace granchain
