#include "store/store_schema.hpp"

#include <sqlite3.h>

#include <algorithm>
#include <vector>

#include <fmt/format.h>

#include "store/sqlite_statement.hpp"

namespace granchain {

const char* const kRunsColumns = R"sql((
  id INTEGER PRIMARY KEY,
  created_utc TEXT NOT NULL,
  code_version TEXT NOT NULL,
  setup TEXT NOT NULL,
  engine TEXT NOT NULL,
  N INTEGER NOT NULL,
  e REAL NOT NULL,
  k REAL NOT NULL,
  T0 REAL NOT NULL,
  m REAL NOT NULL,
  d REAL NOT NULL,
  g REAL NOT NULL,
  T REAL NOT NULL,
  transient REAL NOT NULL,
  seed INTEGER NOT NULL,
  dt_factor REAL NOT NULL,
  damping_D REAL NOT NULL,
  tau_c REAL NOT NULL,
  dt REAL,
  sample_interval REAL NOT NULL,
  samples INTEGER NOT NULL,
  n_coll REAL NOT NULL,
  n_coll_err REAL,
  n_coll_blocks INTEGER NOT NULL,
  n_coll_converged INTEGER NOT NULL,
  floor_rate REAL NOT NULL,
  floor_rate_err REAL,
  pp_rate REAL NOT NULL,
  pp_rate_err REAL,
  particle_collisions INTEGER NOT NULL,
  floor_hits INTEGER NOT NULL,
  steps INTEGER NOT NULL,
  events INTEGER NOT NULL,
  wall_seconds REAL NOT NULL,
  result_json TEXT NOT NULL,
  tc REAL,
  bins INTEGER,
  stationary INTEGER,
  cpu_seconds REAL
))sql";

namespace {

const char* kSchemaRest = R"sql(
CREATE TABLE IF NOT EXISTS meta(key TEXT PRIMARY KEY, value TEXT NOT NULL);
INSERT OR IGNORE INTO meta(key, value) VALUES('schema_version', '3');
@RUNS@
CREATE INDEX IF NOT EXISTS runs_by_point ON runs(setup, N, e, k, T0);
CREATE TABLE IF NOT EXISTS profiles(
  run_id INTEGER NOT NULL REFERENCES runs(id) ON DELETE CASCADE,
  i INTEGER NOT NULL,
  z_mean REAL NOT NULL,
  z_mean_err REAL,
  z_std REAL NOT NULL,
  z_std_err REAL,
  K REAL NOT NULL,
  K_err REAL,
  PRIMARY KEY(run_id, i)
);
CREATE TABLE IF NOT EXISTS run_points(
  point_key TEXT PRIMARY KEY,
  run_id INTEGER NOT NULL UNIQUE REFERENCES runs(id) ON DELETE CASCADE,
  sweep_seed INTEGER,
  replica INTEGER
);
CREATE TABLE IF NOT EXISTS collapse_runs(
  id INTEGER PRIMARY KEY,
  created_utc TEXT NOT NULL,
  code_version TEXT NOT NULL,
  setup TEXT NOT NULL,
  engine TEXT NOT NULL,
  N INTEGER NOT NULL,
  e REAL NOT NULL,
  k REAL NOT NULL,
  a REAL NOT NULL,
  v0 REAL NOT NULL,
  dv0 REAL NOT NULL,
  stop_rule TEXT NOT NULL,
  realizations INTEGER NOT NULL,
  seed INTEGER NOT NULL,
  dt_factor REAL NOT NULL,
  tc REAL NOT NULL,
  tau_c REAL NOT NULL,
  n_tot REAL,
  n_tot_err REAL,
  n_tot_min INTEGER NOT NULL,
  n_tot_max INTEGER NOT NULL,
  collapsed INTEGER NOT NULL,
  wall_seconds REAL NOT NULL,
  result_json TEXT NOT NULL
);
CREATE INDEX IF NOT EXISTS collapse_runs_by_point ON collapse_runs(setup, N, e, k);
CREATE TABLE IF NOT EXISTS collapse_realizations(
  run_id INTEGER NOT NULL REFERENCES collapse_runs(id) ON DELETE CASCADE,
  realization INTEGER NOT NULL,
  particle_collisions INTEGER NOT NULL,
  wall_hits INTEGER NOT NULL,
  collapsed INTEGER NOT NULL,
  t_stop REAL NOT NULL,
  PRIMARY KEY(run_id, realization)
);
)sql";

}  // namespace

// `CREATE TABLE IF NOT EXISTS runs` with the current columns where @RUNS@ stands.
std::string schema_sql() {
  std::string sql = kSchemaRest;
  sql.replace(sql.find("@RUNS@"), 6, std::string("CREATE TABLE IF NOT EXISTS runs") + kRunsColumns + ";");
  return sql;
}

std::string missing_schema_part(sqlite3* db, int version) {
  sqlite3* ref = nullptr;
  sqlite3_open(":memory:", &ref);
  sqlite3_exec(ref, schema_sql().c_str(), nullptr, nullptr, nullptr);
  std::string missing;
  SqlStatement tables(ref, "SELECT name FROM sqlite_master WHERE type = 'table' ORDER BY name");
  while (missing.empty() && tables.row()) {
    const std::string table = tables.column_text(0);
    std::vector<std::string> have;
    {
      SqlStatement cols(db, ("SELECT name FROM pragma_table_info('" + table + "')").c_str());
      while (cols.row()) have.push_back(cols.column_text(0));
    }
    if (have.empty()) {
      // The first stores (version 1) may lack the later tables; opening them for writing adds them.
      if (version == 1 && table != "meta" && table != "runs" && table != "profiles") continue;
      missing = fmt::format("the table '{}'", table);
      break;
    }
    SqlStatement want(ref, ("SELECT name FROM pragma_table_info('" + table + "')").c_str());
    while (missing.empty() && want.row()) {
      const std::string c = want.column_text(0);
      if (version == 1 && table == "runs" && (c == "tc" || c == "bins")) continue;
      if (version <= 2 && table == "runs" && (c == "stationary" || c == "cpu_seconds")) continue;
      if (std::find(have.begin(), have.end(), c) == have.end()) missing = fmt::format("the column '{}' of the table '{}'", c, table);
    }
  }
  sqlite3_close(ref);
  return missing;
}

}  // namespace granchain
