#include "config/run_key.hpp"

#include <fmt/format.h>

#include "config/collapse_options.hpp"
#include "config/run_options.hpp"

namespace granchain {

std::string exact_decimal(double x) { return fmt::format("{}", x); }

namespace {

std::string value_text(const Parameter& p, const TypedValue& v) {
  if (const auto* t = std::get_if<std::string>(&v)) return *t;
  if (const auto* i = std::get_if<long long>(&v))
    return unsigned_integer(p) ? fmt::format("{}", static_cast<std::uint64_t>(*i)) : fmt::format("{}", *i);
  return exact_decimal(std::get<double>(v));
}

// "driven_column" and `column=value` for every stored parameter that acts (config/run_options.hpp:
// dt_factor for the time-stepped engines, tc for the hard engine), in the identity's order,
// leaving out the window and the seed where asked.
std::string identity_text(const RunSpec& s, bool window, bool seed) {
  const auto& stored = stored_run_parameters();
  const auto values = stored_values(s);
  std::string key = "driven_column";
  for (std::size_t i = 0; i < stored.size(); ++i) {
    const Parameter& p = *stored[i].parameter;
    if (p.identity == RunIdentity::None || !values[i].acts) continue;
    if ((p.identity == RunIdentity::Window && !window) || (p.identity == RunIdentity::Seed && !seed)) continue;
    key += fmt::format(" {}={}", p.store_column, value_text(p, values[i].value));
  }
  return key;
}

}  // namespace

std::string point_key_without_seed(const RunSpec& s) { return identity_text(s, true, false); }

std::string trajectory_key(const RunSpec& s) { return identity_text(s, false, true); }

std::string point_key(const RunSpec& spec) { return identity_text(spec, true, true); }

std::string collapse_key(const CollapseSpec& spec) { return collapse_key(stored_collapse_values(spec)); }

std::string collapse_key(const std::vector<TypedValue>& values) {
  const std::vector<const Parameter*> stored = stored_collapse_parameters();
  std::string key = "collapse";
  for (std::size_t i = 0; i < stored.size(); ++i) key += fmt::format(" {}={}", stored[i]->store_column, value_text(*stored[i], values[i]));
  return key;
}

}  // namespace granchain
