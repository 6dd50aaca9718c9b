#pragma once
// The columns of the store's runs table after the run's parameters: what the run measured and what
// it cost, each written once — its name, its SQL declaration and the value it takes from a result.
// The schema (store_schema.cpp) and the insert (results_store.cpp) both read this list; the
// parameters' columns come from the parameter table (config/run_options.hpp).
#include <functional>
#include <vector>

#include "simulation/driven_run.hpp"
#include "store/sqlite_statement.hpp"

namespace granchain {

struct ResultColumn {
  const char* name;
  const char* declaration;  // "REAL NOT NULL"; a column added after schema version 3 must be nullable
  std::function<void(SqlStatement&, int, const RunResult&)> bind;
};

// In the table's order.
const std::vector<ResultColumn>& run_result_columns();

}  // namespace granchain
