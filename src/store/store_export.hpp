#pragma once
// Stored results as CSV or JSON, with every parameter beside every number.
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace granchain {

// runs: one row per driven-column run (all its columns, its point key, sweep seed and replica);
// profiles: one row per particle of each run with the run's parameters; collapse: one row per
// collapse count; realizations: one row per launch of a collapse count with its parameters.
enum class ExportTable { Runs, Profiles, Collapse, Realizations };
enum class ExportFormat { Csv, Json };

struct ExportSelection {
  ExportTable table = ExportTable::Runs;
  // Column -> accepted values (N, e, k, T0, T): a row matches a value within 1e-12 relative.
  std::map<std::string, std::vector<double>> values;
  std::vector<std::string> engines;  // empty: all
  std::string where;                 // an SQL condition on the exported columns, or ""
  // Runs and profiles only: non-empty keeps just the runs stored under these point keys
  // (config/run_key.hpp), so an analysis sees exactly the points of its own grid.
  std::vector<std::string> point_keys;
};

class SqlStatement;

// The selected rows of one table, read one at a time (the store opened read-only; a bad --where
// throws StoreError naming SQLite's complaint, here or at next()). For typed readers
// (store/stored_rows.hpp) and the export below.
class SelectedRows {
 public:
  SelectedRows(const std::string& db_path, const ExportSelection& selection);
  ~SelectedRows();
  SelectedRows(const SelectedRows&) = delete;
  SelectedRows& operator=(const SelectedRows&) = delete;
  bool next();
  SqlStatement& row();
  int column(const std::string& name);       // the index of a column of the selection; throws StoreError if none
  int find_column(const std::string& name);  // the same, or -1

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The selected rows as text. The store is opened read-only. Throws StoreError (a bad --where
// names SQLite's complaint). CSV: a header, NULL as an empty field, infinity as inf; JSON: an
// array of objects, NULL, NaN and infinity as null.
std::string export_results(const std::string& db_path, const ExportSelection& selection, ExportFormat format);

}  // namespace granchain
