#include "sweep/sweep_grid.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

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

namespace {

std::uint64_t fnv1a(const std::string& s) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : s) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  return h;
}

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
  const auto Ns = grid_values(def, "N");
  const auto es = grid_values(def, "e");
  const auto ks = grid_values(def, "k");
  const auto T0s = grid_values(def, "T0");
  const auto Ts = grid_values(def, "T");
  const auto engines = grid_values(def, "engine");
  // An unknown name is refused by resolve_run_options below, with the valid ones.
  const auto is_hard = [](const AxisValue& name) {
    const EngineInfo* e = name.given ? find_engine(name.value.text()) : &granchain::engines().front();
    return e != nullptr && e->hard_spheres;
  };
  const bool any_hard = std::any_of(engines.begin(), engines.end(), is_hard);
  if (scalar.count("tc") && !any_hard) throw InputError("--tc: the TC model belongs to --engine hard; add hard to --engine");

  std::vector<SweepPoint> points;
  // Counted in double: six lists of up to 100000 values and 1000000 replicas multiply to more
  // than a 64-bit integer holds, and a wrapped product would pass the limit.
  constexpr double kMaxPoints = 10'000'000;
  const double expected = static_cast<double>(Ns.size()) * static_cast<double>(es.size()) * static_cast<double>(ks.size()) *
                          static_cast<double>(T0s.size()) * static_cast<double>(Ts.size()) * static_cast<double>(engines.size()) *
                          static_cast<double>(def.replicas);
  if (expected > kMaxPoints)
    throw InputError(fmt::format("the sweep has {:.4g} points (values of --N x --e x --k x --T0 x --T x --engine x --replicas); valid: at most {:.0f}",
                                 expected, kMaxPoints));
  for (const auto& engine : engines) {
    const bool hard = is_hard(engine);
    for (const auto& N : Ns)
      for (const auto& e : es)
        for (std::size_t ik = 0; ik < (hard ? 1 : ks.size()); ++ik)
          for (const auto& T0 : T0s)
            for (const auto& T : Ts) {
              std::map<std::string, RawValue> raw = scalar;
              if (!hard) raw.erase("tc");
              const auto set = [&raw](const char* name, const AxisValue& v) {
                if (v.given) raw[name] = v.value;
              };
              set("engine", engine);
              set("N", N);
              set("e", e);
              if (!hard) set("k", ks[ik]);
              set("T0", T0);
              set("T", T);
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

}  // namespace granchain
