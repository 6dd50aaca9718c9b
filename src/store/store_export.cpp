#include "store/store_export.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "config/run_options.hpp"
#include "store/sqlite_statement.hpp"
#include "store/stationarity_verdicts.hpp"

namespace granchain {

namespace {

// The runs with their points; stationary (the window's verdict by the current rule, 1 or 0:
// store/stationarity_verdicts.hpp) and cpu_seconds (the run's thread CPU time) come last, NULL for
// runs stored before they were recorded. A store older than version 3 keeps them only in each
// run's JSON.
std::string runs_sql(sqlite3* db) {
  std::string columns;
  bool has_verdicts = false;
  SqlStatement info(db, "SELECT name FROM pragma_table_info('runs')");
  while (info.row()) {
    const std::string c = info.column_text(0);
    if (c == "stationary" || c == "cpu_seconds") has_verdicts = true;
    else columns += (columns.empty() ? "r." : ", r.") + c;
  }
  return "SELECT " + columns + ", p.point_key, p.sweep_seed, p.replica, " + current_stationary_sql("r") + " AS stationary, " +
         (has_verdicts ? std::string("r.cpu_seconds ") : std::string("json_extract(r.result_json, '$.cost.cpu_seconds') AS cpu_seconds ")) +
         "FROM runs r LEFT JOIN run_points p ON p.run_id = r.id";
}

// The physics columns of the runs table that may be NULL (the drive's: "r.drive, r.plate_A,
// r.plate_omega, "), those the store has (a store written before the plates has none): a profile
// belongs to its run's drive.
std::string drive_columns_sql(sqlite3* db) {
  std::vector<std::string> have;
  SqlStatement info(db, "SELECT name FROM pragma_table_info('runs')");
  while (info.row()) have.push_back(info.column_text(0));
  std::string sql;
  for (const StoredParameter& c : stored_run_parameters())
    if (c.nullable && c.parameter->identity == RunIdentity::Physics &&
        std::find(have.begin(), have.end(), c.parameter->store_column) != have.end())
      sql += "r." + c.parameter->store_column + ", ";
  return sql;
}

std::string source_sql(ExportTable t, sqlite3* db) {
  switch (t) {
    case ExportTable::Runs:
      return runs_sql(db);
    case ExportTable::Profiles:
      return "SELECT pr.run_id, r.setup, r.engine, r.N, r.e, r.k, r.T0, r.m, r.d, r.g, r.T, r.transient, r.seed, "
             "r.dt_factor, " + drive_columns_sql(db) + "pr.i, pr.z_mean, pr.z_mean_err, pr.z_std, pr.z_std_err, pr.K AS K_mean, "
             "pr.K_err, p.point_key FROM profiles pr JOIN runs r ON r.id = pr.run_id LEFT JOIN run_points p ON p.run_id = r.id";
    case ExportTable::Collapse:
      return "SELECT * FROM collapse_runs";
    case ExportTable::Realizations:
      return "SELECT cr.run_id, c.setup, c.engine, c.N, c.e, c.k, c.a, c.v0, c.dv0, c.stop_rule, c.seed, c.dt_factor, "
             "c.tc, cr.realization, cr.particle_collisions, cr.wall_hits, cr.collapsed, cr.t_stop "
             "FROM collapse_realizations cr JOIN collapse_runs c ON c.id = cr.run_id";
  }
  return "";
}

const char* order_sql(ExportTable t) {
  switch (t) {
    case ExportTable::Runs:
    case ExportTable::Collapse: return " ORDER BY id";
    case ExportTable::Profiles: return " ORDER BY run_id, i";
    case ExportTable::Realizations: return " ORDER BY run_id, realization";
  }
  return "";
}

std::string csv_field(SqlStatement& row, int i) {
  switch (row.column_type(i)) {
    case SQLITE_NULL: return "";
    case SQLITE_INTEGER: return std::to_string(row.column_int(i));
    case SQLITE_FLOAT: return fmt::format("{}", row.column_double(i));  // shortest exact; inf as inf
    default: {
      const std::string t = row.column_text(i);
      if (t.find_first_of(",\"\n\r") == std::string::npos) return t;
      std::string q = "\"";
      for (char c : t) q += c == '"' ? std::string("\"\"") : std::string(1, c);
      return q + "\"";
    }
  }
}

nlohmann::ordered_json json_field(SqlStatement& row, int i) {
  switch (row.column_type(i)) {
    case SQLITE_NULL: return nullptr;
    case SQLITE_INTEGER: return row.column_int(i);
    case SQLITE_FLOAT: {
      const double x = row.column_double(i);
      return std::isfinite(x) ? nlohmann::ordered_json(x) : nlohmann::ordered_json(nullptr);
    }
    default: return row.column_text(i);
  }
}

// The next row; an error while stepping (a --where that fails on some row's values, such as a
// JSON path) names --where.
bool next_row(SqlStatement& rows, const ExportSelection& sel) {
  try {
    return rows.row();
  } catch (const StoreError& e) {
    if (sel.where.empty()) throw;
    throw StoreError(fmt::format("--where: '{}' failed on the stored rows: {}", sel.where, e.what()));
  }
}

}  // namespace

struct SelectedRows::Impl {
  std::unique_ptr<sqlite3, int (*)(sqlite3*)> db{nullptr, sqlite3_close};
  std::unique_ptr<SqlStatement> rows;
  ExportSelection sel;
};

SelectedRows::SelectedRows(const std::string& db_path, const ExportSelection& sel) : impl_(std::make_unique<Impl>()) {
  impl_->sel = sel;
  ResultsStore::preflight(db_path, ResultsStore::Access::ReadOnly);
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(db_path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
    sqlite3_close(db);
    throw StoreError(fmt::format("--db: cannot open '{}'", db_path));
  }
  impl_->db.reset(db);
  sqlite3_busy_timeout(db, 60000);
  register_stationarity_function(db);

  std::string where;
  std::vector<double> numbers;
  for (const auto& [column, values] : sel.values) {
    // Each value is one term of an OR chain, whose depth SQLite bounds (about 1000).
    if (values.size() > 500)
      throw StoreError(fmt::format("--{}: {} values in one filter; a filter takes at most 500 (select a range with --where "
                                   "instead, for example --where '{} BETWEEN 0.8 AND 0.9')", column, values.size(), column));
    std::string any;
    for (double v : values) {
      any += fmt::format("{}abs({} - ?) <= 1e-12 * max(1.0, abs(?))", any.empty() ? "" : " OR ", column);
      numbers.push_back(v);
      numbers.push_back(v);
    }
    where += fmt::format(" AND ({})", any);
  }
  if (!sel.engines.empty()) {
    std::string marks;
    for (std::size_t i = 0; i < sel.engines.size(); ++i) marks += i ? ", ?" : "?";
    where += " AND engine IN (" + marks + ")";
  }
  if (!sel.point_keys.empty()) {
    if (sel.table != ExportTable::Runs && sel.table != ExportTable::Profiles)
      throw StoreError("a selection by point keys applies to the runs and profiles tables only");
    std::string marks;
    for (std::size_t i = 0; i < sel.point_keys.size(); ++i) marks += i ? ", ?" : "?";
    where += " AND point_key IN (" + marks + ")";
  }
  if (!sel.where.empty()) where += " AND (" + sel.where + ")";
  const std::string sql = std::string("SELECT * FROM (") + source_sql(sel.table, db) + ") WHERE 1" + where + order_sql(sel.table);
  sqlite3_stmt* probe = nullptr;
  if (sqlite3_prepare_v2(db, sql.c_str(), -1, &probe, nullptr) != SQLITE_OK) {
    const std::string msg = sqlite3_errmsg(db);
    sqlite3_finalize(probe);
    throw StoreError(fmt::format("the selection is not valid SQL on the exported columns ({}); check --where and the "
                                 "filters against the columns of this table", msg));
  }
  sqlite3_finalize(probe);
  impl_->rows = std::make_unique<SqlStatement>(db, sql.c_str());
  SqlStatement& rows = *impl_->rows;
  int b = 1;
  for (double x : numbers) rows.bind(b++, x);
  for (const auto& e : sel.engines) rows.bind(b++, e);
  for (const auto& key : sel.point_keys) rows.bind(b++, key);
}

SelectedRows::~SelectedRows() = default;

bool SelectedRows::next() { return next_row(*impl_->rows, impl_->sel); }

SqlStatement& SelectedRows::row() { return *impl_->rows; }

int SelectedRows::find_column(const std::string& name) {
  for (int i = 0; i < impl_->rows->columns(); ++i)
    if (name == impl_->rows->column_name(i)) return i;
  return -1;
}

int SelectedRows::column(const std::string& name) {
  if (const int i = find_column(name); i >= 0) return i;
  throw StoreError(fmt::format("results store: the selection has no column '{}'", name));
}

std::string export_results(const std::string& db_path, const ExportSelection& sel, ExportFormat format) {
  SelectedRows selected(db_path, sel);
  SqlStatement& rows = selected.row();

  std::vector<int> shown;  // every column but the raw JSON provenance
  for (int i = 0; i < rows.columns(); ++i)
    if (std::string(rows.column_name(i)) != "result_json") shown.push_back(i);
  std::string out;
  if (format == ExportFormat::Csv) {
    for (std::size_t j = 0; j < shown.size(); ++j) out += std::string(j ? "," : "") + rows.column_name(shown[j]);
    out += "\n";
    while (selected.next()) {
      for (std::size_t j = 0; j < shown.size(); ++j) out += (j ? "," : "") + csv_field(rows, shown[j]);
      out += "\n";
    }
    return out;
  }
  nlohmann::ordered_json all = nlohmann::ordered_json::array();
  while (selected.next()) {
    nlohmann::ordered_json obj;
    for (int i : shown) obj[rows.column_name(i)] = json_field(rows, i);
    all.push_back(std::move(obj));
  }
  // Text that is not UTF-8 (written into the store by another program) is kept, each bad byte as
  // U+FFFD, rather than failing the whole export.
  return all.dump(1, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
}

}  // namespace granchain
