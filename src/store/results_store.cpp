#include "store/results_store.hpp"

#include <sqlite3.h>
#include <unistd.h>

#include <chrono>
#include <ctime>
#include <filesystem>
#include <limits>
#include <fmt/format.h>

#include "config/run_options.hpp"
#include "store/run_columns.hpp"
#include "store/run_json.hpp"
#include "config/run_key.hpp"
#include "store/sqlite_statement.hpp"
#include "store/stationarity_verdicts.hpp"
#include "store/store_schema.hpp"
#include "version.hpp"

namespace granchain {

std::string ResultsStore::utc_now() {
  const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

std::string cannot_create_file_reason(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_directory(path, ec)) return fmt::format("'{}' is a folder, not a file", path);
  fs::path dir = fs::path(path).parent_path();
  if (dir.empty()) dir = ".";
  if (!fs::is_directory(dir, ec)) return fmt::format("folder '{}' does not exist", dir.string());
  if (access(dir.c_str(), W_OK) != 0) return fmt::format("folder '{}' is not writable", dir.string());
  return "";
}

void ResultsStore::recover_interrupted_write(const std::string& path, const std::string& option) {
  namespace fs = std::filesystem;
  const auto nonempty = [](const std::string& p) {
    std::error_code ec;
    const auto size = fs::file_size(p, ec);
    return !ec && size > 0;
  };
  if (!nonempty(path + "-journal") && !nonempty(path + "-wal")) return;
  fs::path dir = fs::path(path).parent_path();
  if (dir.empty()) dir = ".";
  // SQLite rolls a hot journal back (or checkpoints a WAL) on the first read through a connection
  // that may write; a journal that a live writer holds is not hot and is left alone. Without write
  // access nothing is tried here: a reader of a store that is being written goes on (and waits),
  // and one that meets a hot journal is told so by SQLite (interrupted_write_message).
  if (::access(path.c_str(), R_OK | W_OK) != 0 || ::access(dir.c_str(), W_OK) != 0) return;
  sqlite3* db = nullptr;
  int rc = sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READWRITE, nullptr);
  if (rc == SQLITE_OK) {
    sqlite3_busy_timeout(db, 60000);
    rc = sqlite3_exec(db, "SELECT count(*) FROM sqlite_master", nullptr, nullptr, nullptr);
  }
  sqlite3_close(db);
  (void)rc;  // a file that is no database at all is named by the caller's checks
  (void)option;
}

std::string ResultsStore::interrupted_write_message(const std::string& path, const std::string& option) {
  return fmt::format("{}: '{}' has the journal of an interrupted write beside it; SQLite must roll it back before the store "
                     "can be read, which needs write access to the store and its folder",
                     option, path);
}

void ResultsStore::preflight(const std::string& path, Access access, const std::string& option) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const bool read_only = access == Access::ReadOnly;
  if (path.empty()) throw StoreError(fmt::format("{}: the file name is empty; name a results store", option));
  if (fs::exists(path, ec) && !fs::is_directory(path, ec)) {
    if (!fs::is_regular_file(path, ec)) throw StoreError(fmt::format("{}: '{}' is not a regular file", option, path));
    if (::access(path.c_str(), read_only ? R_OK : R_OK | W_OK) != 0)
      throw StoreError(fmt::format("{}: '{}' is not {}", option, path, read_only ? "readable" : "readable and writable"));
    recover_interrupted_write(path, option);
    sqlite3* db = nullptr;
    const int rc = sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr);
    std::string problem;
    auto busy = [](int code) { return (code & 0xff) == SQLITE_BUSY || (code & 0xff) == SQLITE_LOCKED; };
    if (rc != SQLITE_OK) {
      problem = "cannot be opened";
    } else {
      sqlite3_busy_timeout(db, 60000);  // a writer holding the store: wait as writers do
      sqlite3_stmt* st = nullptr;
      const int prc = sqlite3_prepare_v2(db, "SELECT value FROM meta WHERE key='schema_version'", -1, &st, nullptr);
      if (busy(prc) || busy(sqlite3_extended_errcode(db))) {
        problem = "is busy: another process has held it locked for over 60 s; try again when it is done";
      } else if (sqlite3_extended_errcode(db) == SQLITE_READONLY_ROLLBACK) {
        sqlite3_finalize(st);
        sqlite3_close(db);
        throw StoreError(interrupted_write_message(path, option));
      } else if (prc != SQLITE_OK) {
        // A database without our meta table: acceptable only if it is empty.
        sqlite3_stmt* any = nullptr;
        const int arc = sqlite3_prepare_v2(db, "SELECT count(*) FROM sqlite_master", -1, &any, nullptr);
        if (busy(arc)) {
          problem = "is busy: another process has held it locked for over 60 s; try again when it is done";
        } else if (arc != SQLITE_OK) {
          problem = "is not an SQLite database";
        } else {
          const int step = sqlite3_step(any);
          if (busy(step)) problem = "is busy: another process has held it locked for over 60 s; try again when it is done";
          else if (step == SQLITE_ROW && sqlite3_column_int(any, 0) != 0) problem = "is an SQLite database but not a granchain results store";
          else if (read_only) problem = "is empty: it holds no results store yet";  // a new store is made only by writers
        }
        sqlite3_finalize(any);
      } else {
        const int step = sqlite3_step(st);
        const int version = step == SQLITE_ROW ? sqlite3_column_int(st, 0) : 0;
        sqlite3_finalize(st);
        if (busy(step)) {
          problem = "is busy: another process has held it locked for over 60 s; try again when it is done";
        } else if (step == SQLITE_ROW && (version < 1 || version > kStoreSchemaVersion)) {
          // Version 1 is read as it is and upgraded when opened for writing.
          problem = fmt::format("has store schema version {}, this build reads 1 to {}", version, kStoreSchemaVersion);
        } else if (version > 0) {
          try {
            const std::string missing = missing_schema_part(db, version);
            if (!missing.empty())
              problem = fmt::format("is damaged or was not written by granchain: it lacks {} (store schema version {})", missing, version);
          } catch (const StoreError& e) {
            problem = fmt::format("cannot be read ({})", e.what());
          }
        }
      }
    }
    sqlite3_close(db);
    if (!problem.empty()) throw StoreError(fmt::format("{}: '{}' {}", option, path, problem));
    return;
  }
  if (read_only) {
    if (fs::is_directory(path, ec)) throw StoreError(fmt::format("{}: '{}' is a folder, not a results store", option, path));
    throw StoreError(fmt::format("{}: '{}' does not exist", option, path));
  }
  const std::string reason = cannot_create_file_reason(path);
  if (!reason.empty()) throw StoreError(option + ": " + reason);
}

ResultsStore::ResultsStore(const std::string& path, Access access) : path_(path) {
  if (access == Access::ReadWrite) {
    open_read_write();
    return;
  }
  recover_interrupted_write(path, "--db");
  if (sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
    const std::string msg = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    db_ = nullptr;
    throw StoreError(fmt::format("--db: cannot open '{}' for reading: {}", path, msg));
  }
  sqlite3_busy_timeout(db_, 60000);
  int version = 0;
  try {
    version = schema_version();
  } catch (const StoreError&) {
    const bool hot = sqlite3_extended_errcode(db_) == SQLITE_READONLY_ROLLBACK;
    sqlite3_close(db_);
    db_ = nullptr;
    if (hot) throw StoreError(interrupted_write_message(path, "--db"));
    throw;
  }
  if (version < 2) {
    sqlite3_close(db_);
    db_ = nullptr;
    throw StoreError(fmt::format("--db: '{}' has an older store schema; it is upgraded by the first command that writes it "
                                 "(reading it read-only needs version 2 or later)",
                                 path));
  }
}

ResultsStore::ResultsStore(const std::string& path) : path_(path) { open_read_write(); }

void ResultsStore::open_read_write() {
  const std::string& path = path_;
  std::error_code ec;
  const bool created = !std::filesystem::exists(path, ec);
  // A store this constructor created and could not set up (a full disk) is removed again, so no
  // empty file is left behind.
  auto remove_created = [&] {
    if (created) std::filesystem::remove(path, ec);
  };
  if (sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) != SQLITE_OK) {
    const std::string msg = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    db_ = nullptr;
    remove_created();
    throw StoreError(fmt::format("--db: cannot open '{}': {}", path, msg));
  }
  sqlite3_busy_timeout(db_, 60000);  // concurrent writers (parallel runs) wait instead of failing
  register_stationarity_function(db_);
  exec("PRAGMA foreign_keys = OFF");  // while a version-1 store's runs table is rebuilt
  exec("BEGIN IMMEDIATE");
  try {
    exec(schema_sql().c_str());
    if (schema_version() == 1) migrate_from_version_1();
    if (schema_version() == 2) migrate_from_version_2();
    exec(missing_runs_columns_sql(db_).c_str());
    exec(kRejudgeStoredRuns);  // verdicts stored under an earlier rule (store/stationarity_verdicts.hpp)
    exec("COMMIT");
    exec("PRAGMA foreign_keys = ON");
  } catch (...) {
    sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
    sqlite3_close(db_);
    db_ = nullptr;
    remove_created();
    throw;
  }
}

ResultsStore::~ResultsStore() { sqlite3_close(db_); }

int ResultsStore::schema_version() {
  SqlStatement st(db_, "SELECT value FROM meta WHERE key = 'schema_version'");
  return st.row() ? std::stoi(st.column_text(0)) : 0;
}

// Version 1 -> 3, in the caller's transaction: runs gains tc and bins, dt may be NULL, and
// stationary and cpu_seconds are added. SQLite cannot drop a NOT NULL constraint in place, so the
// table is rebuilt (create, copy, drop, rename) and its index made again; profiles and run_points
// keep their run ids. The rows are then given their later values (kVersion1RunsToVersion2,
// kRunsVerdictsFromJson).
void ResultsStore::migrate_from_version_1() {
  // SQLite's order for a rebuild (create new, copy, drop old, rename new), with foreign keys off:
  // renaming the old table instead would rewrite the profiles' reference to follow it.
  exec(("CREATE TABLE runs_version_2" + runs_columns_sql()).c_str());
  exec(R"sql(INSERT INTO runs_version_2(id, created_utc, code_version, setup, engine, N, e, k, T0, m, d, g, T, transient, seed,
        dt_factor, damping_D, tau_c, dt, sample_interval, samples, n_coll, n_coll_err, n_coll_blocks, n_coll_converged,
        floor_rate, floor_rate_err, pp_rate, pp_rate_err, particle_collisions, floor_hits, steps, events, wall_seconds,
        result_json)
      SELECT id, created_utc, code_version, setup, engine, N, e, k, T0, m, d, g, T, transient, seed,
        dt_factor, damping_D, tau_c, dt, sample_interval, samples, n_coll, n_coll_err,
        n_coll_blocks, n_coll_converged, floor_rate, floor_rate_err, pp_rate, pp_rate_err, particle_collisions, floor_hits,
        steps, events, wall_seconds, result_json
      FROM runs)sql");
  exec("DROP TABLE runs");
  exec("ALTER TABLE runs_version_2 RENAME TO runs");
  exec("CREATE INDEX runs_by_point ON runs(setup, N, e, k, T0)");
  exec(kVersion1RunsToVersion2);
  exec(kRunsVerdictsFromJson);
  exec(fmt::format("UPDATE meta SET value = '{}' WHERE key = 'schema_version'", kStoreSchemaVersion).c_str());
}

// Version 2 -> 3, in the caller's transaction: runs gains stationary and cpu_seconds (nullable
// columns, added in place), filled from each run's JSON.
void ResultsStore::migrate_from_version_2() {
  exec("ALTER TABLE runs ADD COLUMN stationary INTEGER");
  exec("ALTER TABLE runs ADD COLUMN cpu_seconds REAL");
  exec(kRunsVerdictsFromJson);
  exec("UPDATE meta SET value = '3' WHERE key = 'schema_version'");
}

void ResultsStore::exec(const char* sql) {
  char* err = nullptr;
  if (sqlite3_exec(db_, sql, nullptr, nullptr, &err) != SQLITE_OK) {
    const std::string msg = err ? err : "unknown error";
    sqlite3_free(err);
    throw StoreError(fmt::format("results store '{}': {}", path_, msg));
  }
}

std::int64_t ResultsStore::in_transaction(const std::function<std::int64_t()>& write) {
  exec("BEGIN IMMEDIATE");
  try {
    const std::int64_t id = write();
    exec("COMMIT");
    return id;
  } catch (...) {
    sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
    throw;
  }
}

ResultsStore::Stored ResultsStore::insert_run(const RunResult& r, const std::function<void(std::int64_t)>& before_commit) {
  Stored out;
  out.id = in_transaction([&]() -> std::int64_t {
    // The same identity (every parameter and the seed) is the same trajectory: kept once.
    const std::string identity = point_key(r.spec);
    SqlStatement find(db_, "SELECT run_id FROM run_points WHERE point_key = ?");
    find.bind(1, identity);
    if (find.row()) return find.column_int(0);
    const std::int64_t id = append_run(r);
    SqlStatement key(db_, "INSERT INTO run_points(point_key, run_id) VALUES(?,?)");
    key.bind(1, identity);
    key.bind(2, id);
    key.run();
    if (before_commit) before_commit(id);
    out.inserted = true;
    return id;
  });
  return out;
}

std::optional<ResultsStore::ReadBack> ResultsStore::read_back_run(const RunSpec& spec) {
  SqlStatement find(db_, "SELECT r.id, r.result_json FROM run_points p JOIN runs r ON r.id = p.run_id WHERE p.point_key = ?");
  find.bind(1, point_key(spec));
  if (!find.row()) return std::nullopt;
  ReadBack out;
  out.id = find.column_int(0);
  try {
    out.json = nlohmann::json::parse(find.column_text(1));
    out.result = run_result_from_json(out.json);
  } catch (const std::exception& e) {
    throw StoreError(fmt::format("run {} of '{}' cannot be read back ({})", out.id, path_, e.what()));
  }
  out.json["stored"] = {{"db", path_}, {"run_id", out.id}};
  out.json["reused"] = true;
  return out;
}

ResultsStore::Stored ResultsStore::insert_sweep_point(const RunResult& r, const std::string& key, std::uint64_t base_seed,
                                                      int replica) {
  Stored out;
  out.id = in_transaction([&]() -> std::int64_t {
    SqlStatement find(db_, "SELECT run_id FROM run_points WHERE point_key = ?");
    find.bind(1, key);
    if (find.row()) return find.column_int(0);
    const std::int64_t id = append_run(r);
    SqlStatement add(db_, "INSERT INTO run_points(point_key, run_id, sweep_seed, replica) VALUES(?,?,?,?)");
    add.bind(1, key);
    add.bind(2, id);
    add.bind(3, static_cast<std::int64_t>(base_seed));
    add.bind(4, static_cast<std::int64_t>(replica));
    add.run();
    out.inserted = true;
    return id;
  });
  return out;
}

std::unordered_set<std::string> ResultsStore::point_keys() {
  std::unordered_set<std::string> keys;
  SqlStatement st(db_, "SELECT point_key FROM run_points");
  while (st.row()) keys.insert(st.column_text(0));
  return keys;
}

ResultsStore::CollapsedPoint ResultsStore::collapsed_point(const InelasticCollapseError& c) {
  return {c.time(), c.particle_a(), c.particle_b(), c.collisions(), c.what()};
}

bool ResultsStore::insert_collapsed_point(const std::string& key, const CollapsedPoint& c) {
  bool inserted = false;
  in_transaction([&]() -> std::int64_t {
    SqlStatement run(db_, "SELECT 1 FROM run_points WHERE point_key = ? UNION ALL SELECT 1 FROM collapsed_points WHERE point_key = ?");
    run.bind(1, key);
    run.bind(2, key);
    if (run.row()) return 0;
    SqlStatement add(db_, "INSERT INTO collapsed_points(point_key, created_utc, code_version, t, first_particle, last_particle, "
                          "collisions, message) VALUES(?,?,?,?,?,?,?,?)");
    add.bind(1, key);
    add.bind(2, utc_now());
    add.bind(3, std::string(code_version()));
    add.bind(4, c.t);
    add.bind(5, static_cast<std::int64_t>(c.first_particle));
    add.bind(6, static_cast<std::int64_t>(c.last_particle));
    add.bind(7, static_cast<std::int64_t>(c.collisions));
    add.bind(8, c.message);
    add.run();
    inserted = true;
    return 0;
  });
  return inserted;
}

std::map<std::string, ResultsStore::CollapsedPoint> ResultsStore::collapsed_points() {
  std::map<std::string, CollapsedPoint> out;
  {
    SqlStatement has(db_, "SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = 'collapsed_points'");
    if (!has.row()) return out;
  }
  SqlStatement st(db_, "SELECT point_key, t, first_particle, last_particle, collisions, message FROM collapsed_points");
  while (st.row())
    out[st.column_text(0)] = CollapsedPoint{st.column_double(1), static_cast<int>(st.column_int(2)), static_cast<int>(st.column_int(3)),
                                            static_cast<std::uint64_t>(st.column_int(4)), st.column_text(5)};
  return out;
}

std::map<std::string, ResultsStore::PointSummary> ResultsStore::point_summaries() {
  std::map<std::string, PointSummary> out;
  SqlStatement st(db_, "SELECT p.point_key, r.id, r.n_coll, r.n_coll_err FROM run_points p JOIN runs r ON r.id = p.run_id");
  while (st.row()) out[st.column_text(0)] = PointSummary{st.column_int(1), st.column_double(2), st.column_double(3)};
  return out;
}

std::int64_t ResultsStore::append_run(const RunResult& r) {
  {
    // The provenance, the stored parameters (config/run_options.hpp, NULL where one does not act),
    // then the results (store/run_columns.hpp): the columns of store_schema.cpp in their order.
    static const std::string insert = [] {
      std::string names = "created_utc, code_version, setup", marks = "?,?,?";
      for (const StoredParameter& c : stored_run_parameters()) {
        names += ", " + c.parameter->store_column;
        marks += ",?";
      }
      for (const ResultColumn& c : run_result_columns()) {
        names += std::string(", ") + c.name;
        marks += ",?";
      }
      return "INSERT INTO runs(" + names + ") VALUES(" + marks + ")";
    }();
    SqlStatement run(db_, insert.c_str());
    int c = 1;
    run.bind(c++, utc_now());
    run.bind(c++, std::string(code_version()));
    run.bind(c++, std::string("driven_column"));
    const auto& stored = stored_run_parameters();
    const auto values = stored_values(r.spec);
    for (std::size_t i = 0; i < stored.size(); ++i) {
      if (stored[i].nullable && !values[i].acts) run.bind_null(c++);  // tc of a soft engine
      else run.bind(c++, values[i].value);
    }
    for (const ResultColumn& column : run_result_columns()) column.bind(run, c++, r);
    run.run();
    const std::int64_t id = sqlite3_last_insert_rowid(db_);

    SqlStatement prof(db_, "INSERT INTO profiles(run_id, i, z_mean, z_mean_err, z_std, z_std_err, K, K_err) VALUES(?,?,?,?,?,?,?,?)");
    for (std::size_t i = 0; i < r.profiles.size(); ++i) {
      const ParticleProfile& p = r.profiles[i];
      prof.bind(1, id);
      prof.bind(2, static_cast<std::int64_t>(i + 1));
      prof.bind(3, p.z_mean.value);
      prof.bind(4, p.z_mean.error);
      prof.bind(5, p.z_std.value);
      prof.bind(6, p.z_std.error);
      prof.bind(7, p.kinetic.value);
      prof.bind(8, p.kinetic.error);
      prof.run();
    }
    return id;
  }
}

std::int64_t ResultsStore::count_runs() {
  SqlStatement st(db_, "SELECT count(*) FROM runs");
  st.row();
  return st.column_int(0);
}

}  // namespace granchain
