#include "store/store_schema.hpp"

#include <sqlite3.h>

#include <algorithm>
#include <vector>

#include <fmt/format.h>

#include "config/collapse_options.hpp"
#include "config/run_options.hpp"
#include "store/run_columns.hpp"
#include "store/sqlite_statement.hpp"

namespace granchain {

namespace {

const char* sql_type(ParameterType t) {
  switch (t) {
    case ParameterType::Integer: return "INTEGER";
    case ParameterType::Real:
    case ParameterType::RealList: return "REAL";  // a list parameter keeps one value per row
    default: return "TEXT";
  }
}

}  // namespace

std::string runs_columns_sql() {
  std::string sql = "(\n  id INTEGER PRIMARY KEY,\n  created_utc TEXT NOT NULL,\n  code_version TEXT NOT NULL,\n  setup TEXT NOT NULL,\n";
  for (const StoredParameter& c : stored_run_parameters())
    sql += fmt::format("  {} {}{},\n", c.parameter->store_column, sql_type(c.parameter->type), c.nullable ? "" : " NOT NULL");
  const auto& results = run_result_columns();
  for (std::size_t i = 0; i < results.size(); ++i)
    sql += fmt::format("  {} {}{}\n", results[i].name, results[i].declaration, i + 1 < results.size() ? "," : "");
  return sql + ")";
}

std::string missing_runs_columns_sql(sqlite3* db) {
  std::vector<std::string> have;
  SqlStatement cols(db, "SELECT name FROM pragma_table_info('runs')");
  while (cols.row()) have.push_back(cols.column_text(0));
  const auto lacks = [&](const std::string& name) { return std::find(have.begin(), have.end(), name) == have.end(); };
  std::string sql;
  for (const StoredParameter& c : stored_run_parameters())
    if (c.nullable && lacks(c.parameter->store_column))
      sql += fmt::format("ALTER TABLE runs ADD COLUMN {} {};", c.parameter->store_column, sql_type(c.parameter->type));
  for (const ResultColumn& c : run_result_columns())
    if (lacks(c.name) && std::string(c.declaration).find("NOT NULL") == std::string::npos)
      sql += fmt::format("ALTER TABLE runs ADD COLUMN {} {};", c.name, c.declaration);
  return sql;
}

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
@COLLAPSE@  tau_c REAL NOT NULL,
  n_tot REAL,
  n_tot_err REAL,
  n_tot_min INTEGER NOT NULL,
  n_tot_max INTEGER NOT NULL,
  collapsed INTEGER NOT NULL,
  wall_seconds REAL NOT NULL,
  result_json TEXT NOT NULL
);
CREATE INDEX IF NOT EXISTS collapse_runs_by_point ON collapse_runs(setup, N, e, k);
CREATE TABLE IF NOT EXISTS collapsed_points(
  point_key TEXT PRIMARY KEY,
  created_utc TEXT NOT NULL,
  code_version TEXT NOT NULL,
  t REAL NOT NULL,
  first_particle INTEGER NOT NULL,
  last_particle INTEGER NOT NULL,
  collisions INTEGER NOT NULL,
  message TEXT NOT NULL
);
CREATE TABLE IF NOT EXISTS collapse_realizations(
  run_id INTEGER NOT NULL REFERENCES collapse_runs(id) ON DELETE CASCADE,
  realization INTEGER NOT NULL,
  particle_collisions INTEGER NOT NULL,
  wall_hits INTEGER NOT NULL,
  collapsed INTEGER NOT NULL,
  t_stop REAL NOT NULL,
  PRIMARY KEY(run_id, realization)
);
CREATE TABLE IF NOT EXISTS collapse_launches(
  count_key TEXT NOT NULL,
  realization INTEGER NOT NULL,
  created_utc TEXT NOT NULL,
  code_version TEXT NOT NULL,
  sitting TEXT NOT NULL,
  sitting_seconds REAL NOT NULL,
  particle_collisions INTEGER NOT NULL,
  wall_hits INTEGER NOT NULL,
  collapsed INTEGER NOT NULL,
  t_stop REAL NOT NULL,
  grazing_contacts INTEGER NOT NULL,
  held_contacts INTEGER NOT NULL,
  one_body INTEGER NOT NULL,
  seconds REAL NOT NULL,
  PRIMARY KEY(count_key, realization)
);
)sql";

}  // namespace

// `CREATE TABLE IF NOT EXISTS runs` with the current columns where @RUNS@ stands.
std::string schema_sql() {
  std::string sql = kSchemaRest;
  sql.replace(sql.find("@RUNS@"), 6, "CREATE TABLE IF NOT EXISTS runs" + runs_columns_sql() + ";");
  // collapse_runs: one column per stored collapse parameter (config/collapse_options.hpp)
  std::string collapse;
  for (const Parameter* p : stored_collapse_parameters()) collapse += fmt::format("  {} {} NOT NULL,\n", p->store_column, sql_type(p->type));
  sql.replace(sql.find("@COLLAPSE@"), 10, collapse);
  return sql;
}

namespace {

// The columns of runs in schema version 3, frozen: a parameter or a result the tables gain later
// has a nullable column that older stores lack (NULL when read, added when next written); these
// must be there.
constexpr const char* kVersion3RunsColumns[] = {
    "id", "created_utc", "code_version", "setup", "engine", "N", "e", "k", "T0", "m", "d", "g", "T", "transient",
    "sample_interval", "bins", "dt_factor", "tc", "seed", "damping_D", "tau_c", "dt", "samples", "n_coll", "n_coll_err",
    "n_coll_blocks", "n_coll_converged", "floor_rate", "floor_rate_err", "pp_rate", "pp_rate_err", "particle_collisions",
    "floor_hits", "steps", "events", "wall_seconds", "result_json", "stationary", "cpu_seconds"};

bool added_after_version_3(const std::string& name) {
  for (const char* c : kVersion3RunsColumns)
    if (name == c) return false;
  return true;
}

}  // namespace

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
      // collapsed_points came after version 3: a store without it has none (added when next written).
      if (table == "collapsed_points") continue;
      // collapse_launches came later still: a store without it holds no unfinished count.
      if (table == "collapse_launches") continue;
      missing = fmt::format("the table '{}'", table);
      break;
    }
    SqlStatement want(ref, ("SELECT name FROM pragma_table_info('" + table + "')").c_str());
    while (missing.empty() && want.row()) {
      const std::string c = want.column_text(0);
      if (table == "runs" && added_after_version_3(c)) continue;
      if (version == 1 && table == "runs" && (c == "tc" || c == "bins")) continue;
      if (version <= 2 && table == "runs" && (c == "stationary" || c == "cpu_seconds")) continue;
      if (std::find(have.begin(), have.end(), c) == have.end()) missing = fmt::format("the column '{}' of the table '{}'", c, table);
    }
  }
  sqlite3_close(ref);
  return missing;
}

}  // namespace granchain
