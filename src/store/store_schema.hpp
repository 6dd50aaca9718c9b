#pragma once
// The results store's schema, written once: the tables and columns a store of the current version
// holds (store/results_store.hpp), and the check of an existing store against them.
#include <string>

struct sqlite3;

namespace granchain {

// The columns of `runs` as a parenthesised SQL list (also for the rebuild of a version-1 store).
extern const char* const kRunsColumns;

// The whole schema: every CREATE TABLE / INDEX IF NOT EXISTS of the current version.
std::string schema_sql();

// What a store of this schema version lacks ("the table 'profiles'", "the column 'n_coll' of the
// table 'runs'"), "" if nothing. The expected tables and columns are read from schema_sql() set up
// in memory; a version-1 store lacks tc and bins of runs by design. Throws StoreError when `db`
// cannot be read.
std::string missing_schema_part(sqlite3* db, int version);

}  // namespace granchain
