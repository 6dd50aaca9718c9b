// A run's identity follows from the parameter table (config/run_options.cpp): the point key, the
// store's parameter columns and the typed rows read back are all the table's entries, so a
// parameter added to the table is keyed, stored and read without another list to keep.
#include <algorithm>
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <cmath>
#include <limits>
#include <map>
#include <string>

#include "config/collapse_options.hpp"
#include "config/run_key.hpp"
#include "config/run_options.hpp"
#include "engines/engine_registry.hpp"
#include "simulation/driven_run.hpp"
#include "store/results_store.hpp"
#include "store/stored_rows.hpp"
#include "temp_dir.hpp"

using namespace granchain;

namespace {

// name -> (declared type, NOT NULL) of a table of a store.
std::map<std::string, std::pair<std::string, bool>> columns_of(const std::string& path, const std::string& table) {
  sqlite3* db = nullptr;
  EXPECT_EQ(sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
  sqlite3_stmt* st = nullptr;
  sqlite3_prepare_v2(db, ("SELECT name, type, \"notnull\" FROM pragma_table_info('" + table + "')").c_str(), -1, &st, nullptr);
  std::map<std::string, std::pair<std::string, bool>> out;
  while (sqlite3_step(st) == SQLITE_ROW)
    out[reinterpret_cast<const char*>(sqlite3_column_text(st, 0))] = {reinterpret_cast<const char*>(sqlite3_column_text(st, 1)),
                                                                      sqlite3_column_int(st, 2) != 0};
  sqlite3_finalize(st);
  sqlite3_close(db);
  return out;
}

void exec(const std::string& path, const std::string& sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  char* err = nullptr;
  EXPECT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &err), SQLITE_OK) << (err ? err : "");
  sqlite3_free(err);
  sqlite3_close(db);
}

std::string sql_type(ParameterType t) {
  return t == ParameterType::Integer ? "INTEGER" : t == ParameterType::Name ? "TEXT" : "REAL";
}

RunResult small_run(EngineKind engine, DriveSpec drive = {}) {
  RunSpec s;
  s.engine.kind = engine;
  s.drive = drive;
  s.params.N = 4;
  s.params.k = engine == EngineKind::Hard ? std::numeric_limits<double>::infinity() : 1e4;
  s.params.e = 0.8;
  s.T = 20;
  s.transient = 5;
  s.seed = 0xfedcba9876543210ULL;  // above 2^63: kept as the signed integer of its bits
  return run_driven_column(s);
}

}  // namespace

// The key names every stored parameter that acts, in the identity's order (engine, physics,
// window, engine options, seed), as docs/results-store.md spells it.
TEST(RunIdentity, ThePointKeyIsTheTableInTheIdentitysOrder) {
  RunSpec s;
  s.params.N = 25;
  s.params.e = 0.88;
  s.params.k = 1e8;
  s.T = 1e4;
  s.transient = 1e3;
  s.seed = 7;
  EXPECT_EQ(point_key(s), "driven_column engine=exact N=25 e=0.88 k=100000000 T0=1 m=1 d=1 g=1 T=10000 transient=1000 "
                          "sample_interval=0.01 bins=1024 seed=7");
  EXPECT_EQ(trajectory_key(s), "driven_column engine=exact N=25 e=0.88 k=100000000 T0=1 m=1 d=1 g=1 seed=7");
  EXPECT_EQ(point_key_without_seed(s), "driven_column engine=exact N=25 e=0.88 k=100000000 T0=1 m=1 d=1 g=1 T=10000 "
                                       "transient=1000 sample_interval=0.01 bins=1024");
  s.engine.kind = EngineKind::Reference;  // a time-stepped engine: dt_factor acts
  s.engine.dt_factor = 200;
  EXPECT_EQ(trajectory_key(s), "driven_column engine=reference N=25 e=0.88 k=100000000 T0=1 m=1 d=1 g=1 dt_factor=200 seed=7");
  s.drive = {DriveKind::Sine, 0.125, 3.0};  // a plate: the drive and its A and omega act, among the physics
  EXPECT_EQ(trajectory_key(s), "driven_column engine=reference N=25 e=0.88 k=100000000 T0=1 drive=sine plate_A=0.125 plate_omega=3 "
                               "m=1 d=1 g=1 dt_factor=200 seed=7");
  s.drive = {};
  s.engine.kind = EngineKind::Hard;  // the hard engine: k infinite, tc acts, dt_factor does not
  s.params.k = std::numeric_limits<double>::infinity();
  s.engine.hard.tc = 0.001;
  s.seed = 0xfedcba9876543210ULL;
  EXPECT_EQ(trajectory_key(s), "driven_column engine=hard N=25 e=0.88 k=inf T0=1 m=1 d=1 g=1 tc=0.001 seed=18364758544493064720");
}

// A fresh store has one column per stored parameter, typed as the parameter and NOT NULL unless
// the parameter may be absent; the collapse counts likewise.
TEST(RunIdentity, TheStoresParameterColumnsAreTheTables) {
  TempDir dir;
  const std::string path = dir.file("s.db");
  { ResultsStore store(path); }
  const auto runs = columns_of(path, "runs");
  ASSERT_FALSE(stored_run_parameters().empty());
  for (const StoredParameter& c : stored_run_parameters()) {
    const auto it = runs.find(c.parameter->store_column);
    ASSERT_NE(it, runs.end()) << c.parameter->store_column;
    EXPECT_EQ(it->second.first, sql_type(c.parameter->type)) << c.parameter->store_column;
    EXPECT_EQ(it->second.second, !c.nullable) << c.parameter->store_column;
  }
  const auto collapse = columns_of(path, "collapse_runs");
  for (const Parameter* p : stored_collapse_parameters()) {
    const auto it = collapse.find(p->store_column);
    ASSERT_NE(it, collapse.end()) << p->store_column;
    EXPECT_EQ(it->second.first, sql_type(p->type)) << p->store_column;
  }
  EXPECT_EQ(collapse_identity_columns().size(), stored_collapse_parameters().size());
}

// Stored and read back, a run of every engine has the spec it ran with, and so its point key,
// bit for bit (a 64-bit seed included).
TEST(RunIdentity, TypedRowsReadBackTheSpecAndItsKey) {
  TempDir dir;
  const std::string path = dir.file("s.db");
  std::map<EngineKind, std::string> keys;
  {
    ResultsStore store(path);
    for (const EngineInfo& e : engines()) {
      const RunResult r = small_run(e.kind);
      store.insert_run(r);
      keys[e.kind] = point_key(r.spec);
    }
    store.insert_run(small_run(EngineKind::ReferenceLocated, {DriveKind::Quadratic, 0.0625, 2.5}));
  }
  std::vector<StoredRun> rows = read_runs(path, ExportSelection{});
  ASSERT_EQ(rows.size(), engines().size() + 1);
  // The plate's run: its drive read back (and its key holds it), the others' thermal floor.
  const auto plate = std::find_if(rows.begin(), rows.end(), [](const StoredRun& r) { return r.spec.drive.plate(); });
  ASSERT_NE(plate, rows.end());
  EXPECT_EQ(plate->spec.drive.kind, DriveKind::Quadratic);
  EXPECT_EQ(plate->spec.drive.A, 0.0625);
  EXPECT_EQ(plate->spec.drive.omega, 2.5);
  EXPECT_NE(plate->point_key.find("drive=quadratic plate_A=0.0625 plate_omega=2.5"), std::string::npos);
  EXPECT_EQ(point_key(plate->spec), plate->point_key);
  rows.erase(plate);
  for (const StoredRun& row : rows) {
    EXPECT_FALSE(row.spec.drive.plate());
    EXPECT_EQ(row.point_key, keys.at(row.spec.engine.kind));
    EXPECT_EQ(point_key(row.spec), row.point_key);
    EXPECT_EQ(row.spec.seed, 0xfedcba9876543210ULL);
  }
}

// A store that lacks a nullable parameter column (as stores made before a parameter joined the
// table do; here tc, removed by hand) gains it when it is next written, NULL in its older runs,
// whose typed rows and keys stay the same.
TEST(RunIdentity, AStoreLackingANullableParameterColumnGainsItWhenWritten) {
  TempDir dir;
  const std::string path = dir.file("s.db");
  std::string key;
  {
    ResultsStore store(path);
    const RunResult r = small_run(EngineKind::Exact);
    store.insert_run(r);
    key = point_key(r.spec);
  }
  const StoredParameter* added = nullptr;
  for (const StoredParameter& c : stored_run_parameters())
    if (c.nullable) added = &c;
  ASSERT_NE(added, nullptr);
  exec(path, "ALTER TABLE runs DROP COLUMN " + added->parameter->store_column);
  ASSERT_EQ(columns_of(path, "runs").count(added->parameter->store_column), 0u);
  { ResultsStore store(path); }  // written: the column is back
  const auto runs = columns_of(path, "runs");
  ASSERT_EQ(runs.count(added->parameter->store_column), 1u);
  EXPECT_FALSE(runs.at(added->parameter->store_column).second);  // nullable
  const std::vector<StoredRun> rows = read_runs(path, ExportSelection{});
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(point_key(rows[0].spec), key);
}
