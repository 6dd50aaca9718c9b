#include "sweep/sweep_grid.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string_view>
#include <tuple>

#include "config/input_error.hpp"
#include "config/value_list.hpp"
#include "engines/engine_registry.hpp"
#include "model/random.hpp"
#include "config/run_key.hpp"

namespace granchain {

const std::vector<std::string>& sweep_grid_parameters() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    for (const Parameter& p : run_parameters())
      if (p.sweep_axis) v.push_back(p.name);
    return v;
  }();
  return names;
}

std::uint64_t fnv1a(const std::string& s) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : s) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  return h;
}

namespace {

// One value of a grid axis; not given: the run's default applies.
struct AxisValue {
  bool given = false;
  RawValue value;
};

// The values of one grid axis, typed: each number of the list as the parameter's type (an
// integer axis takes whole numbers; another value is passed as its text, which validation
// refuses with the run's message), engine names as text. An axis not given holds one value,
// "absent": the run's default applies.
std::vector<AxisValue> grid_values(const SweepDefinition& def, const std::string& name) {
  const auto it = def.raw.find(name);
  if (it == def.raw.end()) return {AxisValue{}};
  const std::string option = "--" + name + (it->second.source.empty() ? "" : " (from " + it->second.source + ")");
  const Parameter& p = *find_parameter(run_parameters(), name);
  std::vector<AxisValue> out;
  if (p.type == ParameterType::Name) {
    std::vector<std::string> names = parse_name_list(it->second.text());
    if (names.empty()) throw InputError(option + ": the list is empty; give engine names such as exact,reference");
    for (auto& n : names) out.push_back({true, RawValue{n}});
    return out;
  }
  for (double x : parse_value_list(it->second.text(), option)) {
    if (p.type == ParameterType::Integer && x == std::floor(x) && std::abs(x) < 9.2e18)
      out.push_back({true, RawValue{static_cast<long long>(x)}});
    else if (p.type == ParameterType::Integer)
      out.push_back({true, RawValue{exact_decimal(x)}});
    else
      out.push_back({true, RawValue{x}});
  }
  return out;
}

}  // namespace

std::uint64_t point_seed(std::uint64_t base_seed, const RunSpec& spec, int replica) {
  const std::uint64_t h = derive_seed(base_seed, fnv1a(point_key_without_seed(spec)));
  return derive_seed(h, static_cast<std::uint64_t>(replica)) >> 1;  // 63 bits: fits SQLite's INTEGER
}

std::vector<SweepPoint> build_sweep_points(const SweepDefinition& def) {
  if (def.replicas < 1) throw InputError("--replicas must be an integer 1 <= replicas <= 1000000");
  std::map<std::string, RawValue> scalar;  // non-grid parameters, passed as given
  for (const auto& [name, value] : def.raw) {
    if (std::find(sweep_grid_parameters().begin(), sweep_grid_parameters().end(), name) == sweep_grid_parameters().end())
      scalar[name] = value;
  }
  if (scalar.count("seed")) throw InputError("--seed: a sweep takes a base seed (--seed of sweep), not a run seed");
  // Every sweep axis of the parameter table (sweep_grid_parameters(), table order), each a list of
  // values or one "absent" value. The engine axis decides, per point, which engine-scoped
  // parameters apply: the hard-sphere engine takes no Soft axis (k) and only it takes a Hard one (tc).
  const std::vector<std::string>& names = sweep_grid_parameters();
  std::vector<const Parameter*> axes;
  std::vector<std::vector<AxisValue>> values;
  std::size_t engine_axis = names.size();  // the table has an engine axis (.at below would say if not)
  for (const std::string& name : names) {
    axes.push_back(find_parameter(run_parameters(), name));
    values.push_back(grid_values(def, name));
    if (axes.back()->identity == RunIdentity::Engine) engine_axis = axes.size() - 1;
  }
  // An unknown name is refused by resolve_run_options below, with the valid ones.
  const auto is_hard = [](const AxisValue& name) {
    const EngineInfo* e = name.given ? find_engine(name.value.text()) : &granchain::engines().front();
    return e != nullptr && e->hard_spheres;
  };
  const auto hard_at = [&](const std::vector<std::size_t>& at) { return is_hard(values.at(engine_axis)[at[engine_axis]]); };
  const bool any_hard = std::any_of(values.at(engine_axis).begin(), values.at(engine_axis).end(), is_hard);
  if (scalar.count("tc") && !any_hard) throw InputError("--tc: the TC model belongs to --engine hard; add hard to --engine");
  if (scalar.count("start-k") && !any_hard)
    throw InputError("--start-k: the hard-sphere engine's start belongs to --engine hard; add hard to --engine");

  std::vector<SweepPoint> points;
  // Counted in double: lists of up to 100000 values and 1000000 replicas multiply to more than a
  // 64-bit integer holds, and a wrapped product would pass the limit.
  constexpr double kMaxPoints = 10'000'000;
  double expected = static_cast<double>(def.replicas);
  std::string product;
  for (std::size_t i = 0; i < names.size(); ++i) {
    expected *= static_cast<double>(values[i].size());
    product += "--" + names[i] + " x ";
  }
  if (expected > kMaxPoints)
    throw InputError(fmt::format("the sweep has {:.4g} points (values of {}--replicas); valid: at most {:.0f}", expected, product,
                                 kMaxPoints));
  std::vector<std::size_t> at(names.size(), 0);  // the current value of each axis
  for (;;) {
    const bool hard = hard_at(at);
    bool skip = false;  // a Soft axis beyond its first value under the hard engine repeats a point
    std::map<std::string, RawValue> raw = scalar;
    for (const auto& [name, value] : scalar) {
      const Parameter* p = find_parameter(run_parameters(), name);
      if (p && p->engines == EngineScope::Hard && !hard) raw.erase(name);
    }
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (hard && axes[i]->engines == EngineScope::Soft) {
        skip |= at[i] > 0;
        continue;
      }
      if (values[i][at[i]].given) raw[names[i]] = values[i][at[i]].value;
    }
    if (!skip) {
      RunSpec spec = resolve_run_options(raw).spec;
      for (int r = 0; r < def.replicas; ++r) {
        SweepPoint p;
        p.spec = spec;
        p.spec.seed = point_seed(def.base_seed, spec, r);
        p.replica = r;
        p.key = point_key(p.spec);
        p.cost = estimate_cost_seconds(p.spec);
        points.push_back(std::move(p));
      }
    }
    std::size_t i = 0;  // the next combination, the first axis fastest
    for (; i < at.size(); ++i) {
      if (++at[i] < values[i].size()) break;
      at[i] = 0;
    }
    if (i == at.size()) break;
  }
  std::sort(points.begin(), points.end(), [](const SweepPoint& a, const SweepPoint& b) {
    return a.cost != b.cost ? a.cost > b.cost : a.key < b.key;
  });
  // A point listed twice (a value repeated in a list) is one run.
  points.erase(std::unique(points.begin(), points.end(), [](const SweepPoint& a, const SweepPoint& b) { return a.key == b.key; }),
               points.end());
  return points;
}

std::vector<std::size_t> points_to_run(const std::vector<SweepPoint>& points, const std::unordered_set<std::string>& stored) {
  std::vector<std::size_t> todo;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!stored.count(points[i].key)) todo.push_back(i);
  return todo;
}

std::vector<SweepPoint> shard_points(const std::vector<SweepPoint>& points, int i, int n) {
  std::vector<SweepPoint> out;
  for (std::size_t j = static_cast<std::size_t>(i - 1); j < points.size(); j += static_cast<std::size_t>(n))
    out.push_back(points[j]);
  return out;
}

std::vector<std::size_t> table_order(const std::vector<SweepPoint>& points) {
  std::vector<std::size_t> order(points.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
    const RunSpec& x = points[i].spec;
    const RunSpec& y = points[j].spec;
    const std::string_view xe = engine_name(x.engine.kind), ye = engine_name(y.engine.kind);  // by name, as printed
    return std::tie(xe, x.params.N, x.params.kT0, x.drive.kind, x.drive.A, x.drive.omega, x.params.k, x.T, x.params.e, points[i].replica) <
           std::tie(ye, y.params.N, y.params.kT0, y.drive.kind, y.drive.A, y.drive.omega, y.params.k, y.T, y.params.e, points[j].replica);
  });
  return order;
}

}  // namespace granchain
