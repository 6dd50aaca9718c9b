// The SQLite results store: round trip, atomic writes, and refusal of files it does not own.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "simulation/collapse_run.hpp"
#include "simulation/driven_run.hpp"
#include "store/results_store.hpp"
#include "store/store_export.hpp"
#include "store/store_merge.hpp"
#include "temp_dir.hpp"

using namespace granchain;
namespace fs = std::filesystem;

namespace {

RunResult small_run() {
  RunSpec s;
  s.params.N = 4;
  s.params.k = 1e4;
  s.params.e = 0.8;
  s.T = 20;
  s.transient = 5;
  return run_driven_column(s);
}

double query_double(sqlite3* db, const std::string& sql) {
  sqlite3_stmt* st = nullptr;
  EXPECT_EQ(sqlite3_prepare_v2(db, sql.c_str(), -1, &st, nullptr), SQLITE_OK) << sqlite3_errmsg(db);
  double x = NAN;
  if (sqlite3_step(st) == SQLITE_ROW) x = sqlite3_column_double(st, 0);
  sqlite3_finalize(st);
  return x;
}

}  // namespace

TEST(ResultsStore, RoundTripOfRunAndProfiles) {
  TempDir dir;
  const std::string path = (dir.path / "r.db").string();
  ResultsStore::preflight(path);
  EXPECT_FALSE(fs::exists(path));  // preflight writes nothing
  const RunResult r = small_run();
  ResultsStore store(path);
  const auto id = store.insert_run(r).id;
  EXPECT_EQ(store.count_runs(), 1);
  EXPECT_EQ(query_double(store.handle(), "SELECT n_coll FROM runs WHERE id=" + std::to_string(id)), r.n_coll.value);
  EXPECT_EQ(query_double(store.handle(), "SELECT count(*) FROM profiles WHERE run_id=" + std::to_string(id)), 4.0);
  EXPECT_EQ(query_double(store.handle(), "SELECT K FROM profiles WHERE i=3"), r.profiles[2].kinetic.value);
  EXPECT_EQ(query_double(store.handle(), "SELECT seed FROM runs"), 1.0);
  ResultsStore::preflight(path);  // an existing store is accepted
}

// A collapse count is a deterministic function of its definition: storing the same definition
// again keeps the stored row (same id, no new realisations); another seed is another count.
TEST(ResultsStore, CollapseCountIsStoredOncePerDefinition) {
  TempDir dir;
  ResultsStore store((dir.path / "c.db").string());
  CollapseResult r;
  r.spec.params.N = 3;
  r.spec.params.e = 0.3;
  r.spec.params.k = 1e6;
  r.spec.realizations = 2;
  r.outcomes.resize(2);
  const auto first = store.insert_collapse(r);
  EXPECT_EQ(store.insert_collapse(r), first);
  EXPECT_EQ(query_double(store.handle(), "SELECT count(*) FROM collapse_runs"), 1.0);
  EXPECT_EQ(query_double(store.handle(), "SELECT count(*) FROM collapse_realizations"), 2.0);
  r.spec.seed = 2;
  EXPECT_NE(store.insert_collapse(r), first);
  EXPECT_EQ(query_double(store.handle(), "SELECT count(*) FROM collapse_runs"), 2.0);
}

// A failure half-way through writing a run (here: the third profile row is refused) leaves
// neither the run row nor any profile row behind.
TEST(ResultsStore, FailedWriteLeavesNoPartialRow) {
  TempDir dir;
  const std::string path = (dir.path / "r.db").string();
  ResultsStore store(path);
  const RunResult r = small_run();
  store.insert_run(r);
  ASSERT_EQ(sqlite3_exec(store.handle(),
                         "CREATE TRIGGER refuse BEFORE INSERT ON profiles WHEN NEW.i = 3 "
                         "BEGIN SELECT RAISE(ABORT, 'injected failure'); END;",
                         nullptr, nullptr, nullptr),
            SQLITE_OK);
  RunResult other = r;
  other.spec.seed = r.spec.seed + 1;  // another trajectory: the same one would not be written again
  EXPECT_THROW(store.insert_run(other), StoreError);
  EXPECT_EQ(store.count_runs(), 1);
  EXPECT_EQ(query_double(store.handle(), "SELECT count(*) FROM profiles"), 4.0);
}

TEST(ResultsStore, PreflightRefusesWhatItCannotUse) {
  TempDir dir;
  EXPECT_THROW(ResultsStore::preflight((dir.path / "missing" / "r.db").string()), StoreError);
  const std::string text = (dir.path / "notes.txt").string();
  std::ofstream(text) << "not a database, just some notes that happen to be long enough\n";
  EXPECT_THROW(ResultsStore::preflight(text), StoreError);
  // Another program's SQLite database is left alone.
  const std::string other = (dir.path / "other.db").string();
  sqlite3* db = nullptr;
  sqlite3_open(other.c_str(), &db);
  sqlite3_exec(db, "CREATE TABLE t(x)", nullptr, nullptr, nullptr);
  sqlite3_close(db);
  EXPECT_THROW(ResultsStore::preflight(other), StoreError);
  EXPECT_THROW(ResultsStore::preflight(dir.path.string()), StoreError);  // a folder
}

// The store's columns: dt is the reference engine's step and NULL for the event-driven engines;
// tc is the hard engine's TC time (NULL for the soft engines); bins the blocking bins.
TEST(ResultsStore, ColumnsHoldStepTcAndBins) {
  TempDir dir;
  ResultsStore store((dir.path / "c.db").string());
  RunSpec s;
  s.params.N = 3;
  s.T = 2;
  s.transient = 0.5;
  s.bins = 256;
  store.insert_run(run_driven_column(s));  // exact
  s.engine.kind = EngineKind::Reference;
  store.insert_run(run_driven_column(s));
  s.engine.kind = EngineKind::Hard;
  s.engine.hard.tc = 1e-6;
  store.insert_run(run_driven_column(s));
  sqlite3* db = store.handle();
  EXPECT_EQ(query_double(db, "SELECT count(*) FROM runs WHERE engine = 'exact' AND dt IS NULL AND tc IS NULL"), 1.0);
  EXPECT_GT(query_double(db, "SELECT dt FROM runs WHERE engine = 'reference'"), 0.0);
  EXPECT_EQ(query_double(db, "SELECT count(*) FROM runs WHERE engine = 'hard' AND dt IS NULL"), 1.0);
  EXPECT_EQ(query_double(db, "SELECT tc FROM runs WHERE engine = 'hard'"), 1e-6);
  EXPECT_EQ(query_double(db, "SELECT min(bins) FROM runs"), 256.0);
  EXPECT_EQ(query_double(db, "SELECT value FROM meta WHERE key = 'schema_version'"), static_cast<double>(kStoreSchemaVersion));
}

// The window's verdict and the CPU time are columns, equal to what each run's JSON says; a store of
// schema version 2 (which keeps them only in the JSON) is read as it is and gains them when opened
// for writing.
TEST(ResultsStore, VerdictAndCpuTimeAreColumnsAndVersionTwoStoresGainThem) {
  TempDir dir;
  const std::string path = (dir.path / "v.db").string();
  {
    ResultsStore store(path);
    RunSpec s;
    s.params.N = 3;
    s.T = 2;
    s.transient = 0.5;
    const RunResult r = run_driven_column(s);
    store.insert_run(r);
    sqlite3* db = store.handle();
    EXPECT_EQ(query_double(db, "SELECT stationary FROM runs"), r.stationary() ? 1.0 : 0.0);
    EXPECT_EQ(query_double(db, "SELECT cpu_seconds FROM runs"), r.cpu_seconds);
    EXPECT_EQ(query_double(db, "SELECT count(*) FROM runs WHERE stationary = json_extract(result_json, '$.stationarity.stationary') "
                               "AND cpu_seconds = json_extract(result_json, '$.cost.cpu_seconds')"), 1.0);
    // Back to version 2: the columns dropped, the version set.
    ASSERT_EQ(sqlite3_exec(db, "ALTER TABLE runs DROP COLUMN stationary; ALTER TABLE runs DROP COLUMN cpu_seconds; "
                               "UPDATE meta SET value = '2' WHERE key = 'schema_version'", nullptr, nullptr, nullptr), SQLITE_OK);
  }
  ResultsStore::preflight(path, ResultsStore::Access::ReadOnly);
  {
    ResultsStore reader(path, ResultsStore::Access::ReadOnly);  // read as it is
    EXPECT_EQ(reader.point_keys().size(), 1u);
  }
  const std::string exported = export_results(path, ExportSelection{}, ExportFormat::Csv);
  ResultsStore store(path);
  sqlite3* db = store.handle();
  EXPECT_EQ(query_double(db, "SELECT value FROM meta WHERE key = 'schema_version'"), 3.0);
  EXPECT_EQ(query_double(db, "SELECT count(*) FROM runs WHERE stationary = json_extract(result_json, '$.stationarity.stationary') "
                             "AND cpu_seconds = json_extract(result_json, '$.cost.cpu_seconds')"), 1.0);
  // The export is the same before and after: the verdict and the CPU time last, from the JSON or the columns.
  EXPECT_EQ(export_results(path, ExportSelection{}, ExportFormat::Csv), exported);
}

// A run stored under an earlier rule (its column and JSON say stationary) whose stored halves
// the current rule fails (the second half 5 of its errors below the first, where both halves'
// errors together allowed it): every reader sees the current verdict (export, the stored rows,
// a run read back), and a store opened for writing, or merged, brings its column up to date.
TEST(ResultsStore, StoredVerdictsAreJudgedByTheCurrentRule) {
  TempDir dir;
  const std::string path = (dir.path / "old.db").string(), merged = (dir.path / "merged.db").string();
  const RunResult r = small_run();
  {
    ResultsStore store(path);
    store.insert_run(r);
    RunSpec second = r.spec;
    second.seed = 2;
    store.insert_run(run_driven_column(second));
    // Run 1 rewritten as an earlier rule judged it: a first half with a wide error (a relaxation),
    // a settled second half 5 of its own errors below, z = -1.6 but z_settled = -3.5.
    ASSERT_EQ(sqlite3_exec(store.handle(),
                           "UPDATE runs SET stationary = 1, result_json = json_set(result_json, "
                           "'$.stationarity.n_coll.first', 10.0, '$.stationarity.n_coll.first_err', 3.0, "
                           "'$.stationarity.n_coll.second', 9.5, '$.stationarity.n_coll.second_err', 0.1, "
                           "'$.stationarity.mean_height.first', 1.0, '$.stationarity.mean_height.first_err', 0.1, "
                           "'$.stationarity.mean_height.second', 1.0, '$.stationarity.mean_height.second_err', 0.1, "
                           "'$.stationarity.stationary', json('true')) WHERE id = 1",
                           nullptr, nullptr, nullptr), SQLITE_OK);
    ASSERT_EQ(sqlite3_exec(store.handle(),
                           "UPDATE runs SET stationary = 1, result_json = json_set(result_json, "
                           "'$.stationarity.n_coll.first', 10.0, '$.stationarity.n_coll.first_err', 0.1, "
                           "'$.stationarity.n_coll.second', 10.0, '$.stationarity.n_coll.second_err', 0.1, "
                           "'$.stationarity.mean_height.first', 1.0, '$.stationarity.mean_height.first_err', 0.1, "
                           "'$.stationarity.mean_height.second', 1.0, '$.stationarity.mean_height.second_err', 0.1) WHERE id = 2",
                           nullptr, nullptr, nullptr), SQLITE_OK);
  }
  fs::copy_file(path, dir.path / "copy.db");
  const std::string copy = (dir.path / "copy.db").string();
  // Read without writing: the column still holds the old verdict, the readers the current one.
  ExportSelection sel;
  sel.where = "stationary = 0";
  const std::string csv = export_results(path, sel, ExportFormat::Csv);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 2) << csv;  // the header and run 1
  {
    ResultsStore reader(path, ResultsStore::Access::ReadOnly);
    EXPECT_EQ(query_double(reader.handle(), "SELECT sum(stationary) FROM runs"), 2.0);  // untouched
    const auto back_1 = reader.read_back_run(r.spec);
    ASSERT_TRUE(back_1.has_value());
    const RunResult& back = back_1->result;
    EXPECT_FALSE(back.stationary());
    EXPECT_NEAR(back.n_coll_halves.z, -0.5 / std::hypot(3.0, 0.1), 1e-12);
    EXPECT_NEAR(back.n_coll_halves.z_settled, -0.5 / (std::sqrt(2.0) * 0.1), 1e-12);
    RunSpec second = r.spec;
    second.seed = 2;
    EXPECT_TRUE(reader.read_back_run(second)->result.stationary());
  }
  // Opened for writing: run 1's column brought to 0, run 2's left as it was.
  {
    ResultsStore writer(path);
    EXPECT_EQ(query_double(writer.handle(), "SELECT stationary FROM runs WHERE id = 1"), 0.0);
    EXPECT_EQ(query_double(writer.handle(), "SELECT stationary FROM runs WHERE id = 2"), 1.0);
  }
  // Merged from the untouched copy: the target judges the runs it takes; the source is not changed.
  merge_stores(merged, {copy});
  {
    ResultsStore target(merged, ResultsStore::Access::ReadOnly);
    EXPECT_EQ(query_double(target.handle(), "SELECT count(*) FROM runs WHERE stationary = 0"), 1.0);
    ResultsStore source(copy, ResultsStore::Access::ReadOnly);
    EXPECT_EQ(query_double(source.handle(), "SELECT sum(stationary) FROM runs"), 2.0);
  }
}

// A store of schema version 1 (tests/data/store_version_1.db: exact, hard with tc = 1e-6 and
// reference runs, dt = 0 for the first two, no tc or bins columns) is read as it is, and upgraded
// in place when opened for writing: the same runs and profiles, dt NULL for the event-driven
// engines, tc and bins from each run's JSON, foreign keys intact.
TEST(ResultsStore, VersionOneStoreIsUpgradedWhenOpenedForWriting) {
  TempDir dir;
  const std::string path = (dir.path / "v1.db").string();
  fs::copy_file(fs::path(GRANCHAIN_SOURCE_DIR) / "tests/data/store_version_1.db", path);
  ResultsStore::preflight(path, ResultsStore::Access::ReadOnly);
  ResultsStore::preflight(path);
  {
    ResultsStore store(path);
    sqlite3* db = store.handle();
    EXPECT_EQ(query_double(db, "SELECT value FROM meta WHERE key = 'schema_version'"), static_cast<double>(kStoreSchemaVersion));
    EXPECT_EQ(query_double(db, "SELECT count(*) FROM runs"), 3.0);
    EXPECT_EQ(query_double(db, "SELECT count(*) FROM profiles"), 9.0);
    EXPECT_EQ(query_double(db, "SELECT count(*) FROM runs WHERE engine IN ('exact', 'hard') AND dt IS NULL"), 2.0);
    EXPECT_GT(query_double(db, "SELECT dt FROM runs WHERE engine = 'reference'"), 0.0);
    EXPECT_EQ(query_double(db, "SELECT tc FROM runs WHERE engine = 'hard'"), 1e-6);
    EXPECT_EQ(query_double(db, "SELECT count(*) FROM runs WHERE tc IS NOT NULL"), 1.0);
    EXPECT_EQ(query_double(db, "SELECT min(bins) FROM runs"), 1024.0);
    EXPECT_EQ(query_double(db, "SELECT count(*) FROM pragma_foreign_key_check"), 0.0);
    // Deleting a run still removes its profiles: the reference follows the rebuilt table.
    EXPECT_EQ(sqlite3_exec(db, "PRAGMA foreign_keys = ON; DELETE FROM runs WHERE engine = 'reference'", nullptr, nullptr, nullptr), SQLITE_OK);
    EXPECT_EQ(query_double(db, "SELECT count(*) FROM profiles"), 6.0);
    store.insert_run(small_run());
    EXPECT_EQ(query_double(db, "SELECT count(*) FROM runs"), 3.0);
  }
  ResultsStore again(path);  // a version-2 store opens as it is
  EXPECT_EQ(query_double(again.handle(), "SELECT count(*) FROM runs"), 3.0);
  // Merged from a version-1 source (read only, not upgraded), the runs take the version-2 form.
  const std::string source = (dir.path / "source_v1.db").string();
  fs::copy_file(fs::path(GRANCHAIN_SOURCE_DIR) / "tests/data/store_version_1.db", source);
  merge_stores((dir.path / "merged.db").string(), {source});
  ResultsStore merged((dir.path / "merged.db").string());
  EXPECT_EQ(query_double(merged.handle(), "SELECT count(*) FROM runs WHERE dt IS NULL AND bins = 1024"), 2.0);
  EXPECT_EQ(query_double(merged.handle(), "SELECT tc FROM runs WHERE engine = 'hard'"), 1e-6);
  sqlite3* src = nullptr;
  ASSERT_EQ(sqlite3_open_v2(source.c_str(), &src, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
  EXPECT_EQ(query_double(src, "SELECT value FROM meta WHERE key = 'schema_version'"), 1.0);  // the source untouched
  sqlite3_close(src);
}

// Opened read-only, a store is read as it is and refuses writes; a version-1 store is refused (the
// first command that writes it upgrades it) and left untouched.
TEST(ResultsStore, ReadOnlyAccessReadsAndNeverWrites) {
  TempDir dir;
  const std::string path = (dir.path / "r.db").string();
  {
    ResultsStore store(path);
    store.insert_run(small_run());
  }
  const auto bytes = fs::file_size(path);
  {
    ResultsStore reader(path, ResultsStore::Access::ReadOnly);
    EXPECT_EQ(reader.count_runs(), 1);
    RunResult other = small_run();
    other.spec.seed += 1;  // another trajectory (the stored one would not be written again)
    EXPECT_THROW(reader.insert_run(other), StoreError);
  }
  EXPECT_EQ(fs::file_size(path), bytes);
  EXPECT_THROW(ResultsStore((dir.path / "missing.db").string(), ResultsStore::Access::ReadOnly), StoreError);
  EXPECT_FALSE(fs::exists(dir.path / "missing.db"));
  const std::string v1 = (dir.path / "v1.db").string();
  fs::copy_file(fs::path(GRANCHAIN_SOURCE_DIR) / "tests/data/store_version_1.db", v1);
  EXPECT_THROW(ResultsStore(v1, ResultsStore::Access::ReadOnly), StoreError);
  sqlite3* src = nullptr;
  ASSERT_EQ(sqlite3_open_v2(v1.c_str(), &src, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
  EXPECT_EQ(query_double(src, "SELECT value FROM meta WHERE key = 'schema_version'"), 1.0);
  sqlite3_close(src);
}

// A run read back from the store has the blocking verdicts of its profile errors (whether each
// found a plateau) as it ran, so that reading it back never warns of a plateau it had, nor hides
// one it lacked: a short window (T = 20) leaves some errors without a plateau.
TEST(ResultsStore, ARunReadBackKeepsThePlateauVerdictsOfItsProfiles) {
  TempDir dir;
  const std::string path = (dir.path / "r.db").string();
  const RunResult r = small_run();
  int without = 0;
  for (const ParticleProfile& p : r.profiles) without += !p.z_mean.converged + !p.z_std.converged + !p.kinetic.converged;
  ResultsStore store(path);
  store.insert_run(r);
  const auto back = store.read_back_run(r.spec);
  ASSERT_TRUE(back.has_value());
  ASSERT_EQ(back->result.profiles.size(), r.profiles.size());
  for (std::size_t i = 0; i < r.profiles.size(); ++i) {
    EXPECT_EQ(back->result.profiles[i].z_mean.converged, r.profiles[i].z_mean.converged) << i;
    EXPECT_EQ(back->result.profiles[i].z_std.converged, r.profiles[i].z_std.converged) << i;
    EXPECT_EQ(back->result.profiles[i].kinetic.converged, r.profiles[i].kinetic.converged) << i;
  }
  // Both verdicts occur (5 of the 12 errors have no plateau with this seed), so the check is not vacuous.
  EXPECT_GT(without, 0);
  EXPECT_LT(without, static_cast<int>(3 * r.profiles.size()));
}
