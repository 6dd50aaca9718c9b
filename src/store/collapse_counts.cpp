// The free-space collapse counts of the results store (granchain collapse, reproduce): one row
// per count in collapse_runs, identified by its definition (collapse_identity_columns()), and one per
// launch in collapse_realizations.
#include <fmt/format.h>
#include <sqlite3.h>

#include <chrono>
#include <memory>
#include <tuple>
#include <vector>
#include <unistd.h>

#include "config/collapse_options.hpp"
#include "config/run_key.hpp"
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
  r.law.tau_c = find.column_double(0);
  r.n_tot_mean = find.column_double(1);
  r.n_tot_error = find.column_double(2);
  r.n_tot_min = static_cast<std::uint64_t>(find.column_int(3));
  r.n_tot_max = static_cast<std::uint64_t>(find.column_int(4));
  r.collapsed = static_cast<int>(find.column_int(5));
  r.wall_seconds = find.column_double(6);
  // The contacts below the exact engine's resolution are kept in the count's JSON only.
  const nlohmann::json j = nlohmann::json::parse(find.column_text(7), nullptr, false);
  if (j.is_object() && j.contains("observables")) {
    const nlohmann::json& obs = j["observables"];
    r.grazing_contacts = obs.value("grazing_contacts", std::uint64_t{0});
    r.held_contacts = obs.value("held_contacts", std::uint64_t{0});
    r.one_body = obs.value("one_body", 0);
  }
  SqlStatement real(db_, "SELECT particle_collisions, wall_hits, collapsed, t_stop FROM collapse_realizations WHERE run_id = ? ORDER BY realization");
  real.bind(1, *id);
  while (real.row()) {
    RealizationOutcome o;
    o.particle_collisions = static_cast<std::uint64_t>(real.column_int(0));
    o.wall_hits = static_cast<std::uint64_t>(real.column_int(1));
    o.collapsed = real.column_int(2) != 0;
    o.t_stop = real.column_double(3);
    r.collisions += o.particle_collisions;
    r.outcomes.push_back(o);
  }
  if (static_cast<int>(r.outcomes.size()) != spec.realizations) return std::nullopt;  // an incomplete row is not the count
  return r;
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

int ResultsStore::kept_launches(const CollapseSpec& spec) {
  if (!has_table(db_, "collapse_launches")) return 0;
  SqlStatement n(db_, "SELECT count(*) FROM collapse_launches WHERE count_key = ? AND realization < ?");
  n.bind(1, collapse_key(spec));
  n.bind(2, static_cast<std::int64_t>(spec.realizations));
  n.row();
  return static_cast<int>(n.column_int(0));
}

LaunchCheckpoint ResultsStore::launch_checkpoint(const CollapseSpec& spec) {
  const std::string key = collapse_key(spec);
  LaunchCheckpoint c;
  SqlStatement kept(db_, "SELECT realization, particle_collisions, wall_hits, collapsed, t_stop, grazing_contacts, held_contacts, "
                         "one_body, seconds FROM collapse_launches WHERE count_key = ? AND realization < ? ORDER BY realization");
  kept.bind(1, key);
  kept.bind(2, static_cast<std::int64_t>(spec.realizations));
  while (kept.row()) {
    RealizationOutcome o;
    o.particle_collisions = static_cast<std::uint64_t>(kept.column_int(1));
    o.wall_hits = static_cast<std::uint64_t>(kept.column_int(2));
    o.collapsed = kept.column_int(3) != 0;
    o.t_stop = kept.column_double(4);
    o.grazing_contacts = static_cast<std::uint64_t>(kept.column_int(5));
    o.held_contacts = static_cast<std::uint64_t>(kept.column_int(6));
    o.one_body = kept.column_int(7) != 0;
    o.seconds = kept.column_double(8);
    c.done[static_cast<int>(kept.column_int(0))] = o;
  }
  // Each earlier sitting's wall time up to the last launch it kept (what it spent on launches lost
  // to its interruption is not counted).
  SqlStatement spent(db_, "SELECT total(m) FROM (SELECT max(sitting_seconds) AS m FROM collapse_launches WHERE count_key = ? "
                          "GROUP BY sitting)");
  spent.bind(1, key);
  spent.row();
  c.earlier_seconds = spent.column_double(0);
  // Launches are written in batches, one transaction at most every second (a commit costs a few
  // milliseconds, more than a short launch): a process killed outright loses at most the last
  // second's launches; run_collapse flushes the rest before it returns.
  struct Pending {
    std::vector<std::tuple<int, RealizationOutcome, double>> launches;  // realization, outcome, sitting seconds
    std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now(), written = started;
  };
  auto pending = std::make_shared<Pending>();
  const std::string sitting = fmt::format("{} pid {}", utc_now(), getpid());
  c.flush = [this, key, sitting, pending] {
    if (pending->launches.empty()) return;
    in_transaction([&] {
      SqlStatement add(db_, "INSERT OR IGNORE INTO collapse_launches(count_key, realization, created_utc, code_version, sitting, "
                            "sitting_seconds, particle_collisions, wall_hits, collapsed, t_stop, grazing_contacts, held_contacts, "
                            "one_body, seconds) VALUES(?,?,?,?,?,?,?,?,?,?,?,?,?,?)");
      const std::string now = utc_now();
      for (const auto& [r, o, at] : pending->launches) {
        int i = 1;
        add.bind(i++, key);
        add.bind(i++, static_cast<std::int64_t>(r));
        add.bind(i++, now);
        add.bind(i++, std::string(code_version()));
        add.bind(i++, sitting);
        add.bind(i++, at);
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
    pending->launches.clear();
    pending->written = std::chrono::steady_clock::now();
  };
  c.finished = [pending, flush = c.flush](int r, const RealizationOutcome& o) {
    const auto now = std::chrono::steady_clock::now();
    pending->launches.emplace_back(r, o, std::chrono::duration<double>(now - pending->started).count());
    if (now - pending->written >= std::chrono::seconds(1)) flush();
  };
  return c;
}

bool ResultsStore::empty() {
  for (const char* table : {"runs", "collapse_runs", "collapse_launches", "collapsed_points"}) {
    if (!has_table(db_, table)) continue;
    SqlStatement any(db_, fmt::format("SELECT 1 FROM {} LIMIT 1", table).c_str());
    if (any.row()) return false;
  }
  return true;
}

}  // namespace granchain
