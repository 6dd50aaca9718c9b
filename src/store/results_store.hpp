#pragma once
// The results store: an embedded SQLite database, one row per run in `runs`, the per-particle
// profiles in `profiles`, free-space collapse counts in `collapse_runs` and `collapse_realizations`,
// and the launches of counts not yet finished in `collapse_launches` (store/collapse_counts.cpp). Every run is written in one transaction, so an interrupted or failed
// run leaves no partial row (SQLite's atomic commit holds even through kill -9 or power loss).
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <map>
#include <memory>
#include <set>
#include <optional>
#include <string>
#include <unordered_set>
#include <vector>

#include <nlohmann/json.hpp>

#include "simulation/collapse_run.hpp"
#include "simulation/driven_run.hpp"

struct sqlite3;

namespace granchain {

class StoreError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Version 2: runs has tc and bins, and dt NULL for event-driven engines. Version 3: runs has
// stationary (the window's halves check, 1 or 0) and cpu_seconds (the run's thread CPU time),
// NULL for runs stored before they were recorded. An older store is upgraded when it is opened
// for writing; readers read every version.
inline constexpr int kStoreSchemaVersion = 3;

// The columns of collapse_runs that define a collapse count: the store columns of the collapse
// parameters (config/collapse_options.hpp); two rows with equal values there hold the same count
// (ResultsStore::insert_collapse, merge).
std::vector<std::string> collapse_identity_columns();

// Why a new file could not be created at `path` ("" if it can): its folder must exist and be
// writable, and the path must not be a folder.
std::string cannot_create_file_reason(const std::string& path);

// The version-2 form of runs written in version 1 (dt = 0 for event-driven engines, no tc or bins):
// dt NULL where it is 0, tc (hard engine) and bins from each run's JSON. Idempotent; for the
// upgrade of a store and for runs merged from a version-1 source.
inline constexpr const char* kVersion1RunsToVersion2 =
    "UPDATE runs SET dt = NULL WHERE dt = 0;"
    "UPDATE runs SET bins = json_extract(result_json, '$.parameters.bins') WHERE bins IS NULL;"
    "UPDATE runs SET tc = json_extract(result_json, '$.parameters.tc') WHERE tc IS NULL AND engine = 'hard';";

// The version-3 columns of runs written before them, from each run's JSON (NULL where the JSON
// has none). Idempotent; for the upgrade of a store and for runs merged from an older source.
inline constexpr const char* kRunsVerdictsFromJson =
    "UPDATE runs SET stationary = json_extract(result_json, '$.stationarity.stationary') WHERE stationary IS NULL;"
    "UPDATE runs SET cpu_seconds = json_extract(result_json, '$.cost.cpu_seconds') WHERE cpu_seconds IS NULL;";

class ResultsStore {
 public:
  // Checks, without creating or changing anything, that `path` can hold a store: an existing
  // file must be a granchain store of a known schema; a new file needs a writable folder. ReadOnly:
  // the store must exist and be readable (a read-only file or mount is fine). A store that another
  // process holds locked is waited for (up to 60 s, as writers do) and then reported as busy.
  // Messages start with `option` (the flag that named the store).
  enum class Access { ReadWrite, ReadOnly };
  static void preflight(const std::string& path, Access access = Access::ReadWrite, const std::string& option = "--db");
  // A process killed while it wrote (kill -9, a power cut) leaves a hot rollback journal beside
  // the store; the store's committed state is intact, but a read-only connection cannot roll the
  // journal back and SQLite refuses to read. This rolls it back through a connection that may
  // write (nothing else is changed); throws StoreError when the store or its folder is not writable.
  static void recover_interrupted_write(const std::string& path, const std::string& option = "--db");
  // What a reader without write access is told when SQLite finds such a journal (SQLITE_READONLY_ROLLBACK).
  static std::string interrupted_write_message(const std::string& path, const std::string& option = "--db");

  explicit ResultsStore(const std::string& path);  // opens or creates
  // Access::ReadOnly: opens an existing store of schema version 2 or later for reading only (a
  // version-1 store is refused: the first command that writes it upgrades it); writing through it
  // fails. Its methods read what every version from 2 on holds.
  ResultsStore(const std::string& path, Access access);
  ~ResultsStore();
  ResultsStore(const ResultsStore&) = delete;
  ResultsStore& operator=(const ResultsStore&) = delete;

  struct Stored {
    std::int64_t id = 0;
    bool inserted = false;
  };
  // Appends one run with its profiles and its point key (config/run_key.hpp) in one
  // transaction, unless a run with the same key (every parameter and the seed: the same
  // trajectory) is stored already: then nothing is written and that run's id is returned with
  // inserted = false, so one trajectory is never stored, nor counted, twice.
  // before_commit, when given, runs inside that transaction with the new id (for example to write
  // an output that must exist exactly when the run is stored); if it throws, nothing is stored.
  Stored insert_run(const RunResult& r, const std::function<void(std::int64_t)>& before_commit = {});
  // The stored run with this identity (point key, seed included) read back: its id, its result and
  // its JSON marked as read back ("stored": {db, run_id}, "reused": true); nothing if none. Throws
  // StoreError naming the run when its JSON cannot be read.
  struct ReadBack {
    std::int64_t id = 0;
    RunResult result;
    nlohmann::json json;
  };
  std::optional<ReadBack> read_back_run(const RunSpec& spec);
  // A sweep point: in one transaction, appends the run, its profiles and its key unless a run
  // with that key is already stored. Returns the run's id and whether it was appended now.
  Stored insert_sweep_point(const RunResult& r, const std::string& key, std::uint64_t base_seed, int replica);
  // Keys of every stored point.
  std::unordered_set<std::string> point_keys();
  // Hard spheres that collapsed at a sweep point (InelasticCollapseError): the point's outcome is
  // kept in collapsed_points by its key, so that a repeated sweep does not run it again and a figure
  // can tell a collapse from a point not yet run. It is not a run (no n_coll; nothing that reads runs
  // sees it). Returns false, writing nothing, when the key is stored already (as a run or a collapse).
  struct CollapsedPoint {
    double t = 0;                        // when the engine stopped
    int first_particle = 0, last_particle = 0;  // the collapsing particles (1-based)
    std::uint64_t collisions = 0;        // collisions since the engine started, the collapse included
    std::string message;                 // the engine's description
  };
  static CollapsedPoint collapsed_point(const InelasticCollapseError& c);
  bool insert_collapsed_point(const std::string& key, const CollapsedPoint& c);
  // Every collapsed point by key ({} for a store without the table: made before it existed).
  std::map<std::string, CollapsedPoint> collapsed_points();
  struct PointSummary {
    std::int64_t id = 0;
    double n_coll = 0, n_coll_err = 0;  // NaN where the store holds NULL
  };
  // Every stored point by key, with its run id and n_coll.
  std::map<std::string, PointSummary> point_summaries();
  // Stores one collapse count (granchain collapse) with its per-realisation counts, in one
  // transaction, and returns its id. A count is a deterministic function of its definition
  // (collapse_identity_columns()), so one already stored with the same definition is kept and its id
  // returned: a repeated command adds nothing.
  std::int64_t insert_collapse(const CollapseResult& r);
  // The stored count with this definition (collapse_identity_columns()), with its per-launch outcomes,
  // or nothing. The contacts below the exact engine's resolution are read from the count's JSON
  // (totals only; 0 per launch).
  std::optional<CollapseResult> find_collapse(const CollapseSpec& spec);
  // The stored count's JSON as it was written when it was counted (its code version, provenance and
  // cost), with "read_back": {"collapse_run_id": id} added; nothing if not stored.
  std::optional<nlohmann::json> stored_collapse_json(const CollapseSpec& spec);
  // A count carried over sittings: its launches are kept in collapse_launches by
  // collapse_key(spec) as they finish, so that a count stopped anywhere (a signal, a batch job's
  // walltime, a Python interrupt) continues from them when run again; insert_collapse deletes them
  // once the whole count is stored. Launches are matched by the count's definition, not by code
  // version (as stored counts are); the versions that counted them are reported.
  struct KeptLaunches {
    std::map<int, RealizationOutcome> done;
    double earlier_seconds = 0;              // each earlier sitting's wall time up to its last kept launch
    std::set<std::string> code_versions;     // of the sittings that counted them
  };
  // What is kept of this count (nothing for a store without the table; a read-only store serves).
  KeptLaunches kept_launches(const CollapseSpec& spec);
  // A checkpoint that continues from what is kept and keeps each new launch through this store,
  // which must outlive it. A launch that took 0.1 s or more is written at once, shorter ones in
  // batches at most a second apart (a commit costs milliseconds): a process killed outright loses
  // the launch it was writing and at most about a second of short launches per thread.
  LaunchCheckpoint launch_checkpoint(const CollapseSpec& spec);
  // The same from launches already read (kept_launches) over the store at `path`, opened for writing
  // (into `writer`) only when the first launch is kept: a count that keeps nothing creates no store
  // and leaves an existing one unchanged.
  static LaunchCheckpoint lazy_launch_checkpoint(const std::string& path, const CollapseSpec& spec, KeptLaunches kept,
                                                 std::shared_ptr<ResultsStore>& writer);
  // Whether `path` holds a store that can be read (not missing, not an empty database awaiting its
  // first writer).
  static bool holds_a_store(const std::string& path);
  // One kept launch as written: its realisation, outcome and the seconds into its sitting.
  struct KeptLaunch {
    int realization = 0;
    RealizationOutcome outcome;
    double sitting_seconds = 0;
  };
  void write_kept_launches(const std::string& key, const std::string& sitting, const std::vector<KeptLaunch>& launches);
  std::int64_t count_runs();
  sqlite3* handle() { return db_; }

 private:
  void open_read_write();  // opens or creates path_, creating or upgrading the schema
  void exec(const char* sql);
  int schema_version();
  void migrate_from_version_1();
  void migrate_from_version_2();
  std::int64_t append_run(const RunResult& r);  // inside a transaction
  // Runs write() between BEGIN IMMEDIATE and COMMIT, rolling back if it throws; returns its id.
  std::int64_t in_transaction(const std::function<std::int64_t()>& write);
  static std::string utc_now();  // "2026-11-24T05:00:00Z", the created_utc of a new row
  sqlite3* db_ = nullptr;
  std::string path_;
};

}  // namespace granchain
