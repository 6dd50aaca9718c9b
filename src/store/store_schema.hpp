#pragma once
// The results store's schema, written once: the tables and columns a store of the current version
// holds (store/results_store.hpp), and the check of an existing store against them.
#include <string>

struct sqlite3;

namespace granchain {

// The columns of `runs` as a parenthesised SQL list (also for the rebuild of a version-1 store):
// the row's id and provenance, one column per stored parameter of the driven column
// (config/run_options.hpp: stored_run_parameters(), typed as the parameter is, NOT NULL unless the
// parameter may be absent), then the results.
std::string runs_columns_sql();

// "ALTER TABLE runs ADD COLUMN ..." for every nullable column that `db`'s runs table lacks (a
// parameter or a result added to the tables after the store was made: NULL in its older runs).
std::string missing_runs_columns_sql(sqlite3* db);

// The whole schema: every CREATE TABLE / INDEX IF NOT EXISTS of the current version.
std::string schema_sql();

// What a store of this schema version lacks ("the table 'profiles'", "the column 'n_coll' of the
// table 'runs'"), "" if nothing. The expected tables and columns are read from schema_sql() set up
// in memory; a store may lack the columns of runs the tables gained after schema version 3
// (added when it is next written), a version-1 store tc and bins, a version-1 or -2 store the
// verdict columns (stationary, cpu_seconds), by design. Throws StoreError when `db`
// cannot be read.
std::string missing_schema_part(sqlite3* db, int version);

}  // namespace granchain
