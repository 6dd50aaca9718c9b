// The free-space collapse counts of the results store (granchain collapse, reproduce): one row
// per count in collapse_runs, identified by its definition (collapse_identity_columns()), and one per
// launch in collapse_realizations.
#include <fmt/format.h>
#include <sqlite3.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <tuple>
#include <vector>
#include <unistd.h>

#include "config/collapse_options.hpp"
#include "config/run_key.hpp"
#include "model/chain_parameters.hpp"
#include "store/collapse_json.hpp"
#include "store/results_store.hpp"
#include "store/sqlite_statement.hpp"
#include "version.hpp"

namespace granchain {

namespace {

// The values of collapse_identity_columns() for a collapse count, in that order, from index c on.
void bind_collapse_definition(SqlStatement& q, int& c, const CollapseSpec& s) {
  for (const TypedValue& v : stored_collapse_values(s)) q.bind(c++, v);  // k = +inf for hard spheres (SQLite keeps it as Inf)
}

// The id of the first stored count with this definition, if any.
std::optional<std::int64_t> stored_collapse_id(sqlite3* db, const CollapseSpec& spec) {
  std::string where;
  for (const std::string& c : collapse_identity_columns()) where += fmt::format("{}{} = ?", where.empty() ? "" : " AND ", c);
  SqlStatement find(db, ("SELECT id FROM collapse_runs WHERE " + where + " ORDER BY id LIMIT 1").c_str());
  int f = 1;
  bind_collapse_definition(find, f, spec);
  if (!find.row()) return std::nullopt;
  return find.column_int(0);
}

// The counts of one launch as both tables keep them: particle_collisions, wall_hits, collapsed and
// t_stop in the columns first .. first + 3 of a row.
RealizationOutcome launch_counts(SqlStatement& row, int first) {
  RealizationOutcome o;
  o.particle_collisions = static_cast<std::uint64_t>(row.column_int(first));
  o.wall_hits = static_cast<std::uint64_t>(row.column_int(first + 1));
  o.collapsed = row.column_int(first + 2) != 0;
  o.t_stop = row.column_double(first + 3);
  return o;
}

bool has_table(sqlite3* db, const char* name) {
  SqlStatement has(db, "SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = ?");
  has.bind(1, std::string(name));
  return has.row();
}

}  // namespace

std::vector<std::string> collapse_identity_columns() {
  std::vector<std::string> columns;
  for (const Parameter* p : stored_collapse_parameters()) columns.push_back(p->store_column);
  return columns;
}

std::optional<CollapseResult> ResultsStore::find_collapse(const CollapseSpec& spec) {
  const std::optional<std::int64_t> id = stored_collapse_id(db_, spec);
  if (!id) return std::nullopt;
  SqlStatement find(db_, "SELECT tau_c, n_tot, n_tot_err, n_tot_min, n_tot_max, collapsed, wall_seconds, result_json FROM collapse_runs "
                        "WHERE id = ?");
  find.bind(1, *id);
  find.row();
  CollapseResult r;
  r.spec = spec;
  r.law = contact_law(spec.params);
  r.law.tau_c = find.column_double(0);
  r.n_tot_mean = find.column_double(1);
  r.n_tot_error = find.column_double(2);
  r.n_tot_min = static_cast<std::uint64_t>(find.column_int(3));
  r.n_tot_max = static_cast<std::uint64_t>(find.column_int(4));
  r.collapsed = static_cast<int>(find.column_int(5));
  r.wall_seconds = find.column_double(6);
  // The contacts below the exact engine's resolution are kept in the count's JSON only.
  const nlohmann::json j = nlohmann::json::parse(find.column_text(7), nullptr, false);
  if (j.is_object() && j.contains("observables") && j["observables"].is_object()) {
    const nlohmann::json& obs = j["observables"];
    const auto count = [&](const char* name) -> std::uint64_t {
      return obs.contains(name) && obs[name].is_number_unsigned() ? obs[name].get<std::uint64_t>() : 0;
    };
    r.grazing_contacts = count("grazing_contacts");
    r.held_contacts = count("held_contacts");
    r.one_body = static_cast<int>(count("one_body"));
  }
  SqlStatement real(db_, "SELECT particle_collisions, wall_hits, collapsed, t_stop FROM collapse_realizations WHERE run_id = ? ORDER BY realization");
  real.bind(1, *id);
  while (real.row()) {
    const RealizationOutcome o = launch_counts(real, 0);
    r.collisions += o.n_tot();
    r.outcomes.push_back(o);
  }
  if (static_cast<int>(r.outcomes.size()) != spec.realizations) return std::nullopt;  // an incomplete row is not the count
  return r;
}

std::optional<nlohmann::json> ResultsStore::stored_collapse_json(const CollapseSpec& spec) {
  const std::optional<std::int64_t> id = stored_collapse_id(db_, spec);
  if (!id) return std::nullopt;
  SqlStatement row(db_, "SELECT result_json FROM collapse_runs WHERE id = ?");
  row.bind(1, *id);
  if (!row.row()) return std::nullopt;
  nlohmann::json j = nlohmann::json::parse(row.column_text(0), nullptr, false);
  if (!j.is_object()) return std::nullopt;
  j["read_back"] = {{"collapse_run_id", *id}};
  return j;
}

std::int64_t ResultsStore::insert_collapse(const CollapseResult& r) {
  return in_transaction([&] {
    if (const std::optional<std::int64_t> stored = stored_collapse_id(db_, r.spec)) {  // the same count is already stored
      SqlStatement kept(db_, "DELETE FROM collapse_launches WHERE count_key = ?");
      kept.bind(1, collapse_key(r.spec));
      kept.run();
      return *stored;
    }
    std::string names = "created_utc, code_version", marks = "?,?";
    for (const std::string& c : collapse_identity_columns()) {
      names += ", " + c;
      marks += ",?";
    }
    SqlStatement row(db_, fmt::format("INSERT INTO collapse_runs({}, tau_c, n_tot, n_tot_err, n_tot_min, n_tot_max, collapsed, "
                                      "wall_seconds, result_json) VALUES({},?,?,?,?,?,?,?,?)", names, marks).c_str());
    const CollapseSpec& s = r.spec;
    int c = 1;
    row.bind(c++, utc_now());
    row.bind(c++, std::string(code_version()));
    bind_collapse_definition(row, c, s);
    row.bind(c++, r.law.tau_c);
    row.bind(c++, r.n_tot_mean);  // NaN (no realisation finished) is stored as NULL
    row.bind(c++, r.n_tot_error);
    row.bind(c++, static_cast<std::int64_t>(r.n_tot_min));
    row.bind(c++, static_cast<std::int64_t>(r.n_tot_max));
    row.bind(c++, static_cast<std::int64_t>(r.collapsed));
    row.bind(c++, r.wall_seconds);
    row.bind(c++, collapse_result_to_json(r).dump());
    row.run();
    const std::int64_t id = sqlite3_last_insert_rowid(db_);
    SqlStatement kept(db_, "DELETE FROM collapse_launches WHERE count_key = ?");  // the count is whole now
    kept.bind(1, collapse_key(s));
    kept.run();
    SqlStatement real(db_, "INSERT INTO collapse_realizations(run_id, realization, particle_collisions, wall_hits, collapsed, t_stop) VALUES(?,?,?,?,?,?)");
    for (std::size_t i = 0; i < r.outcomes.size(); ++i) {
      const RealizationOutcome& o = r.outcomes[i];
      real.bind(1, id);
      real.bind(2, static_cast<std::int64_t>(i));
      real.bind(3, static_cast<std::int64_t>(o.particle_collisions));
      real.bind(4, static_cast<std::int64_t>(o.wall_hits));
      real.bind(5, static_cast<std::int64_t>(o.collapsed));
      real.bind(6, o.t_stop);
      real.run();
    }
    return id;
  });
}

ResultsStore::KeptLaunches ResultsStore::kept_launches(const CollapseSpec& spec) {
  KeptLaunches k;
  if (!has_table(db_, "collapse_launches")) return k;
  const std::string key = collapse_key(spec);
  SqlStatement kept(db_, "SELECT realization, particle_collisions, wall_hits, collapsed, t_stop, grazing_contacts, held_contacts, "
                         "one_body, seconds, code_version FROM collapse_launches WHERE count_key = ? AND realization >= 0 AND "
                         "realization < ? ORDER BY realization");
  kept.bind(1, key);
  kept.bind(2, static_cast<std::int64_t>(spec.realizations));
  while (kept.row()) {
    RealizationOutcome o = launch_counts(kept, 1);
    o.grazing_contacts = static_cast<std::uint64_t>(kept.column_int(5));
    o.held_contacts = static_cast<std::uint64_t>(kept.column_int(6));
    o.one_body = kept.column_int(7) != 0;
    o.seconds = kept.column_double(8);
    k.done[static_cast<int>(kept.column_int(0))] = o;
    k.code_versions.insert(kept.column_text(9));
  }
  SqlStatement spent(db_, "SELECT total(m) FROM (SELECT max(sitting_seconds) AS m FROM collapse_launches WHERE count_key = ? "
                          "GROUP BY sitting)");
  spent.bind(1, key);
  spent.row();
  k.earlier_seconds = spent.column_double(0);
  return k;
}

void ResultsStore::write_kept_launches(const std::string& key, const std::string& sitting, const std::vector<KeptLaunch>& launches) {
  in_transaction([&] {
    SqlStatement add(db_, "INSERT OR IGNORE INTO collapse_launches(count_key, realization, created_utc, code_version, sitting, "
                          "sitting_seconds, particle_collisions, wall_hits, collapsed, t_stop, grazing_contacts, held_contacts, "
                          "one_body, seconds) VALUES(?,?,?,?,?,?,?,?,?,?,?,?,?,?)");
    const std::string now = utc_now();
    for (const KeptLaunch& l : launches) {
      const RealizationOutcome& o = l.outcome;
      int i = 1;
      add.bind(i++, key);
      add.bind(i++, static_cast<std::int64_t>(l.realization));
      add.bind(i++, now);
      add.bind(i++, std::string(code_version()));
      add.bind(i++, sitting);
      add.bind(i++, l.sitting_seconds);
      add.bind(i++, static_cast<std::int64_t>(o.particle_collisions));
      add.bind(i++, static_cast<std::int64_t>(o.wall_hits));
      add.bind(i++, static_cast<std::int64_t>(o.collapsed));
      add.bind(i++, o.t_stop);
      add.bind(i++, static_cast<std::int64_t>(o.grazing_contacts));
      add.bind(i++, static_cast<std::int64_t>(o.held_contacts));
      add.bind(i++, static_cast<std::int64_t>(o.one_body));
      add.bind(i++, o.seconds);
      add.run();
    }
    return std::int64_t{0};
  });
}

namespace {

// The writing half of a checkpoint: `finished` and `flush` over the store that `writer()` gives.
void keep_through(LaunchCheckpoint& c, const std::string& key, const std::function<ResultsStore&()>& writer) {
  struct Pending {
    std::vector<ResultsStore::KeptLaunch> launches;
    std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now(), written = started;
    // A sitting: this process from this instant (to the nanosecond), so that two never share a name.
    std::string sitting = fmt::format("{} pid {}", std::chrono::system_clock::now().time_since_epoch().count(), getpid());
  };
  auto pending = std::make_shared<Pending>();
  c.flush = [key, writer, pending] {
    if (pending->launches.empty()) return;
    writer().write_kept_launches(key, pending->sitting, pending->launches);
    pending->launches.clear();
    pending->written = std::chrono::steady_clock::now();
  };
  c.finished = [pending, flush = c.flush](int r, const RealizationOutcome& o) {
    const auto now = std::chrono::steady_clock::now();
    pending->launches.push_back({r, o, std::chrono::duration<double>(now - pending->started).count()});
    if (o.seconds >= 0.1 || now - pending->written >= std::chrono::seconds(1)) flush();
  };
}

LaunchCheckpoint continuing(ResultsStore::KeptLaunches kept) {
  LaunchCheckpoint c;
  c.done = std::move(kept.done);
  c.earlier_seconds = kept.earlier_seconds;
  return c;
}

}  // namespace

LaunchCheckpoint ResultsStore::launch_checkpoint(const CollapseSpec& spec) {
  LaunchCheckpoint c = continuing(kept_launches(spec));
  keep_through(c, collapse_key(spec), [this]() -> ResultsStore& { return *this; });
  return c;
}

LaunchCheckpoint ResultsStore::lazy_launch_checkpoint(const std::string& path, const CollapseSpec& spec, KeptLaunches kept,
                                                      std::shared_ptr<ResultsStore>& writer) {
  LaunchCheckpoint c = continuing(std::move(kept));
  keep_through(c, collapse_key(spec), [&writer, path]() -> ResultsStore& {
    if (!writer) writer = std::make_shared<ResultsStore>(path);
    return *writer;
  });
  return c;
}

bool ResultsStore::holds_a_store(const std::string& path) {
  if (!std::filesystem::exists(path)) return false;
  try {
    preflight(path, Access::ReadOnly, "--db");
    return true;
  } catch (const StoreError&) {
    return false;
  }
}

}  // namespace granchain
