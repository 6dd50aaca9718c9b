#pragma once
// The results store: an embedded SQLite database, one row per run in `runs`, the per-particle
// profiles in `profiles`. Every run is written in one transaction, so an interrupted or failed
// run leaves no partial row (SQLite's atomic commit holds even through kill -9 or power loss).
#include <cstdint>
#include <stdexcept>
#include <string>

#include "simulation/collapse_run.hpp"
#include "simulation/driven_run.hpp"

struct sqlite3;

namespace granchain {

class StoreError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

inline constexpr int kStoreSchemaVersion = 1;

// Why a new file could not be created at `path` ("" if it can): its folder must exist and be
// writable, and the path must not be a folder.
std::string cannot_create_file_reason(const std::string& path);

class ResultsStore {
 public:
  // Checks, without creating or changing anything, that `path` can hold a store: an existing
  // file must be a granchain store of a known schema; a new file needs a writable folder.
  static void preflight(const std::string& path);

  explicit ResultsStore(const std::string& path);  // opens or creates
  ~ResultsStore();
  ResultsStore(const ResultsStore&) = delete;
  ResultsStore& operator=(const ResultsStore&) = delete;

  // Appends one run with its profiles in one transaction and returns its id.
  std::int64_t insert_run(const RunResult& r);
  // Appends one collapse count (granchain collapse) with its per-realisation counts, in one
  // transaction, and returns its id.
  std::int64_t insert_collapse(const CollapseResult& r);
  std::int64_t count_runs();
  sqlite3* handle() { return db_; }

 private:
  void exec(const char* sql);
  // Runs write() between BEGIN IMMEDIATE and COMMIT, rolling back if it throws; returns its id.
  template <class Write>
  std::int64_t in_transaction(Write write);
  sqlite3* db_ = nullptr;
  std::string path_;
};

}  // namespace granchain
