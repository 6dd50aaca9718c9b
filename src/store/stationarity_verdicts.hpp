#pragma once
// A stored run's stationarity verdict judged by the current rule (analysis/blocking.hpp,
// judge_halves) from the halves its JSON keeps (the value and blocked error of n_coll and of the
// mean height on each half of the window), so that every reader sees the verdict today's rule
// gives, whichever rule the run was stored under. The store's `stationary` column and the JSON's
// own flag hold the verdict given when the run was stored; a store opened for writing brings its
// column up to date (kRejudgeStoredRuns), rewriting only the rows whose verdict changed.
#include <string>

struct sqlite3;

namespace granchain {

// Registers the SQL function granchain_stationary(stationarity) on `db`: its argument is a run's
// '$.stationarity' JSON object (text); it returns 1 where both halves checks pass, 0 where one
// fails, and NULL for a NULL argument or halves stored without values.
void register_stationarity_function(sqlite3* db);

// The SQL expression of the current verdict of a run of the table aliased `alias` (1, 0, or NULL
// for a run stored before the check), for a connection with the function registered.
std::string current_stationary_sql(const std::string& alias);

// Brings every run's stationary column to the current verdict, writing only where it changed.
extern const char* const kRejudgeStoredRuns;

}  // namespace granchain
