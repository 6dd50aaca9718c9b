#include "store/run_json.hpp"

#include <cmath>
#include <limits>

#include "config/run_options.hpp"
#include "engines/engine_registry.hpp"
#include "version.hpp"
#include "provenance.hpp"
#include "simulation/run_verdicts.hpp"

namespace granchain {

using nlohmann::json;

json to_json(const Estimate& e) {
  return json{{"value", e.value}, {"error", e.error}, {"blocks", e.blocks}, {"converged", e.converged}};
}

// The set-up and every stored parameter of the table (config/run_options.hpp), under its store
// column's name; k is null for hard spheres (JSON has no infinity), and so is a parameter that does
// not act where the store keeps NULL for it (tc of a soft engine; the drive and the plate's A and
// omega under the thermal floor).
json run_spec_to_json(const RunSpec& s) {
  json j{{"setup", "driven_column"}};
  const auto& stored = stored_run_parameters();
  const auto values = stored_values(s);
  for (std::size_t i = 0; i < stored.size(); ++i) {
    const Parameter& p = *stored[i].parameter;
    const TypedValue& v = values[i].value;
    if (stored[i].nullable && !values[i].acts) j[p.store_column] = nullptr;  // NULL in the store too: tc of a soft engine
    else if (const auto* t = std::get_if<std::string>(&v)) j[p.store_column] = *t;
    else if (const auto* n = std::get_if<long long>(&v)) j[p.store_column] = unsigned_integer(p) ? json(static_cast<std::uint64_t>(*n)) : json(*n);
    else j[p.store_column] = std::get<double>(v);
  }
  return j;
}

json run_result_to_json(const RunResult& r) {
  json profiles = json::array();
  for (std::size_t i = 0; i < r.profiles.size(); ++i) {
    const ParticleProfile& p = r.profiles[i];
    profiles.push_back({{"i", i + 1},
                        {"z_mean", p.z_mean.value},
                        {"z_mean_err", p.z_mean.error},
                        {"z_std", p.z_std.value},
                        {"z_std_err", p.z_std.error},
                        {"K", p.kinetic.value},
                        {"K_err", p.kinetic.error},
                        // whether each error's blocking found a plateau (else a lower bound)
                        {"z_mean_plateau", p.z_mean.converged},
                        {"z_std_plateau", p.z_std.converged},
                        {"K_plateau", p.kinetic.converged}});
  }
  json j{{"code_version", code_version()},
              {"provenance", provenance_json()},
              {"parameters", run_spec_to_json(r.spec)},
              {"derived", {{"D", r.law.D}, {"tau_c", r.law.tau_c}, {"dt", r.time_step > 0 ? json(r.time_step) : json(nullptr)},
                           {"sample_interval", r.sample_interval}, {"samples", r.samples}}},
              {"observables", {{"n_coll", to_json(r.n_coll)},
                               {"floor_rate", to_json(r.floor_rate)},
                               {"pp_rate", to_json(r.pp_rate)},
                               {"particle_collisions", r.particle_collisions},
                               {"floor_hits", r.floor_hits}}},
              {"profiles", profiles},
              {"cost", {{"steps", r.steps}, {"events", r.events}, {"wall_seconds", r.wall_seconds}, {"cpu_seconds", r.cpu_seconds}}}};
  auto halves = [](const StationarityCheck& c) {
    return json{{"first", c.first.value}, {"first_err", c.first.error}, {"second", c.second.value},
                {"second_err", c.second.error}, {"z", c.z}, {"z_settled", c.z_settled}, {"stationary", c.stationary}};
  };
  j["stationarity"] = {{"stationary", r.stationary()},
                       {"n_coll", halves(r.n_coll_halves)},
                       {"mean_height", halves(r.height_halves)}};
  if (!r.n_coll_blocking.empty()) {
    // The blocking curves: per level, the blocks, the standard error and the blocks' lag-1 autocorrelation.
    auto curve = [](const std::vector<BlockingLevel>& c) {
      json a = json::array();
      for (const BlockingLevel& l : c) a.push_back({{"blocks", l.blocks}, {"error", l.error}, {"lag1", l.lag1}});
      return a;
    };
    j["blocking"] = {{"n_coll", curve(r.n_coll_blocking)}, {"mean_height", curve(r.height_blocking)}};
  }
  if (!r.contacts.empty()) {
    // Durations in units of tau_c; histogram[j] counts log2(duration / tau_c) in
    // [log2_min + (first_bin + j) / bins_per_octave, ... + 1 / bins_per_octave).
    json pairs = json::array();
    for (std::size_t i = 0; i < r.contacts.size(); ++i) {
      const PairContacts& c = r.contacts[i];
      pairs.push_back({{"pair", i}, {"contacts", c.contacts}, {"began_before", c.began_before}, {"open_at_end", c.open_at_end},
                       {"mean", c.mean}, {"longest", c.longest}, {"contact_fraction", c.contact_fraction},
                       {"long_fraction", c.long_fraction},
                       {"first_bin", c.first_bin}, {"histogram", c.histogram}});
    }
    j["contacts"] = {{"unit", "tau_c"}, {"log2_min", ContactDurations::kLog2Min}, {"bins_per_octave", ContactDurations::kBinsPerOctave},
                     {"long_contact", ContactDurations::kLongContact}, {"pairs", pairs}};
  }
  j["warnings"] = run_warnings(r);  // the verdicts above as the sentences the command line prints
  // A value of the wrong sign fails the run (run_driven_column), so a result's audit found none.
  if (r.spec.engine.audit) j["audit"] = {{"instants", r.audit_instants}, {"values", r.audit_values}};
  return j;
}

namespace {

// JSON has no infinity or NaN: nlohmann writes them as null. Reading back, a null k is the hard
// spheres' infinity and any other null is NaN (an undefined error bar).
double real_or(const json& j, const char* key, double if_null) {
  const json& v = j.at(key);
  return v.is_null() ? if_null : v.get<double>();
}

Estimate estimate_from_json(const json& j) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  return Estimate{real_or(j, "value", nan), real_or(j, "error", nan), j.at("blocks").get<int>(),
                  j.at("converged").get<bool>()};
}

}  // namespace

std::vector<BlockingLevel> blocking_curve_from_json(const json& levels) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<BlockingLevel> c;
  for (const json& l : levels) c.push_back({l.at("blocks").get<int>(), real_or(l, "error", nan), real_or(l, "lag1", nan)});
  return c;
}

RunResult run_result_from_json(const json& j) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  RunResult r;
  const json& p = j.at("parameters");
  RunSpec& s = r.spec;
  const auto& stored = stored_run_parameters();
  for (std::size_t i = 0; i < stored.size(); ++i) {
    const auto it = p.find(stored[i].parameter->store_column);
    if (it == p.end() || it->is_null()) continue;  // a parameter this JSON predates; k of hard spheres
    if (it->is_string()) set_stored_value(s, i, it->get<std::string>());
    else if (it->is_number_unsigned()) set_stored_value(s, i, static_cast<long long>(it->get<std::uint64_t>()));
    else if (it->is_number_integer()) set_stored_value(s, i, it->get<long long>());
    else set_stored_value(s, i, it->get<double>());
  }
  if (engine_info(s.engine.kind).hard_spheres) s.params.k = std::numeric_limits<double>::infinity();
  r.law = contact_law(s.params);
  const json& d = j.at("derived");
  r.law.D = real_or(d, "D", std::numeric_limits<double>::infinity());
  r.law.tau_c = real_or(d, "tau_c", nan);
  r.time_step = d.at("dt").is_null() ? 0.0 : d.at("dt").get<double>();  // null: an event-driven engine
  r.sample_interval = d.at("sample_interval").get<double>();
  r.samples = d.at("samples").get<std::int64_t>();
  const json& o = j.at("observables");
  r.n_coll = estimate_from_json(o.at("n_coll"));
  r.floor_rate = estimate_from_json(o.at("floor_rate"));
  r.pp_rate = estimate_from_json(o.at("pp_rate"));
  r.particle_collisions = o.at("particle_collisions").get<std::uint64_t>();
  r.floor_hits = o.at("floor_hits").get<std::uint64_t>();
  // The plateau verdicts of the profile errors; runs stored before they were kept read back without
  // a verdict against them (true), so that a run read back never warns of what it cannot know.
  for (const json& q : j.at("profiles")) {
    r.profiles.push_back(ParticleProfile{Estimate{real_or(q, "z_mean", nan), real_or(q, "z_mean_err", nan), 0, q.value("z_mean_plateau", true)},
                                         Estimate{real_or(q, "z_std", nan), real_or(q, "z_std_err", nan), 0, q.value("z_std_plateau", true)},
                                         Estimate{real_or(q, "K", nan), real_or(q, "K_err", nan), 0, q.value("K_plateau", true)}});
  }
  // Runs stored before the stationarity check have none: they read back as stationary with z = NaN.
  // Every other run is judged by the current rule from its stored halves (analysis/blocking.hpp),
  // whatever verdict it was stored with.
  auto halves = [nan](const json& h) {
    const Estimate first{real_or(h, "first", nan), real_or(h, "first_err", nan)};
    const Estimate second{real_or(h, "second", nan), real_or(h, "second_err", nan)};
    if (std::isnan(first.value) || std::isnan(second.value)) {
      StationarityCheck c;
      c.z = c.z_settled = nan;
      c.stationary = h.at("stationary").get<bool>();
      return c;
    }
    return judge_halves(first, second);
  };
  if (j.contains("stationarity")) {
    r.n_coll_halves = halves(j.at("stationarity").at("n_coll"));
    r.height_halves = halves(j.at("stationarity").at("mean_height"));
  } else {
    r.n_coll_halves.z = r.height_halves.z = r.n_coll_halves.z_settled = r.height_halves.z_settled = nan;
  }
  if (j.contains("blocking")) {  // runs stored before the curves were kept have none
    r.n_coll_blocking = blocking_curve_from_json(j.at("blocking").at("n_coll"));
    r.height_blocking = blocking_curve_from_json(j.at("blocking").at("mean_height"));
  }
  if (j.contains("contacts"))  // runs stored before contact durations were kept have none
    for (const json& q : j.at("contacts").at("pairs")) {
      // (long_fraction: absent in runs stored before it was kept)
      const double long_fraction = q.contains("long_fraction") && q.at("long_fraction").is_number() ? q.at("long_fraction").get<double>()
                                                                                                    : std::numeric_limits<double>::quiet_NaN();
      r.contacts.push_back(PairContacts{q.at("contacts").get<std::uint64_t>(), q.at("began_before").get<std::uint64_t>(),
                                        q.at("open_at_end").get<std::uint64_t>(), q.at("mean").get<double>(),
                                        q.at("longest").get<double>(), q.at("contact_fraction").get<double>(), long_fraction,
                                        q.at("first_bin").get<int>(), q.at("histogram").get<std::vector<std::uint64_t>>()});
    }
  const json& c = j.at("cost");
  r.steps = c.at("steps").get<std::uint64_t>();
  r.events = c.at("events").get<std::uint64_t>();
  r.wall_seconds = c.at("wall_seconds").get<double>();
  // Absent in runs stored before it was recorded; null where it was NaN.
  r.cpu_seconds = c.contains("cpu_seconds") && c.at("cpu_seconds").is_number() ? c.at("cpu_seconds").get<double>()
                                                                                 : std::numeric_limits<double>::quiet_NaN();
  return r;
}

}  // namespace granchain
