#include "store/stored_rows.hpp"

#include <fmt/format.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "config/run_options.hpp"
#include "store/results_store.hpp"
#include "store/run_json.hpp"
#include "store/sqlite_statement.hpp"

namespace granchain {

namespace {

// The run's id, set-up and every stored parameter the selection holds, read into a RunSpec by the
// parameter table (config/run_options.hpp: stored_run_parameters()). A column the selection lacks
// or a NULL (tc of a soft engine, a parameter added after the run was stored) leaves the spec's
// default.
class SpecColumns {
 public:
  SpecColumns(SelectedRows& rows, const char* id_column) : id_(rows.column(id_column)), setup_(rows.column("setup")) {
    const auto& stored = stored_run_parameters();
    for (std::size_t i = 0; i < stored.size(); ++i)
      if (const int c = rows.find_column(stored[i].parameter->store_column); c >= 0) at_.push_back({i, c});
  }
  void read(SqlStatement& r, std::int64_t& run_id, std::string& setup, RunSpec& spec) const {
    run_id = r.column_int(id_);
    setup = r.column_text(setup_);
    for (const auto& [i, c] : at_) {
      switch (r.column_type(c)) {
        case SQLITE_NULL: continue;
        case SQLITE_INTEGER: set(spec, i, static_cast<long long>(r.column_int(c)), run_id); break;
        case SQLITE_FLOAT: set(spec, i, r.column_double(c), run_id); break;
        default: set(spec, i, std::string(r.column_text(c)), run_id);
      }
    }
  }

 private:
  static void set(RunSpec& spec, std::size_t i, const TypedValue& v, std::int64_t run_id) {
    try {
      set_stored_value(spec, i, v);
    } catch (const std::exception& e) {
      throw StoreError(fmt::format("results store: run {}: the column '{}' cannot be read: {}", run_id,
                                   stored_run_parameters()[i].parameter->store_column, e.what()));
    }
  }
  int id_, setup_;
  std::vector<std::pair<std::size_t, int>> at_;  // stored parameter, selection column
};

}  // namespace

std::vector<StoredRun> read_runs(const std::string& db_path, ExportSelection selection) {
  selection.table = ExportTable::Runs;
  SelectedRows rows(db_path, selection);
  const SpecColumns run(rows, "id");
  const int n_coll = rows.column("n_coll"), n_coll_err = rows.column("n_coll_err"), wall = rows.column("wall_seconds"),
            cpu = rows.column("cpu_seconds"), stationary = rows.column("stationary"), key = rows.column("point_key"),
            replica = rows.column("replica"), floor_rate = rows.column("floor_rate"), floor_rate_err = rows.column("floor_rate_err"),
            pp_rate = rows.column("pp_rate"), pp_rate_err = rows.column("pp_rate_err");
  std::vector<StoredRun> out;
  while (rows.next()) {
    SqlStatement& r = rows.row();
    StoredRun s;
    run.read(r, s.id, s.setup, s.spec);
    s.n_coll = r.column_double(n_coll);
    s.n_coll_err = r.column_double(n_coll_err);
    s.floor_rate = r.column_double(floor_rate);
    s.floor_rate_err = r.column_double(floor_rate_err);
    s.pp_rate = r.column_double(pp_rate);
    s.pp_rate_err = r.column_double(pp_rate_err);
    s.wall_seconds = r.column_double(wall);
    s.cpu_seconds = r.column_double(cpu);
    if (r.column_type(stationary) != SQLITE_NULL) s.stationary = r.column_int(stationary) != 0;
    s.point_key = r.column_text(key);
    s.replica = r.column_type(replica) == SQLITE_NULL ? 0 : static_cast<int>(r.column_int(replica));
    out.push_back(std::move(s));
  }
  return out;
}

std::map<std::int64_t, std::vector<BlockingLevel>> read_n_coll_blocking(const std::string& db_path) {
  ResultsStore::preflight(db_path, ResultsStore::Access::ReadOnly);
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(db_path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
    sqlite3_close(db);
    throw StoreError(fmt::format("--db: cannot open '{}'", db_path));
  }
  const std::unique_ptr<sqlite3, int (*)(sqlite3*)> owner(db, sqlite3_close);
  sqlite3_busy_timeout(db, 60000);
  SqlStatement q(db, "SELECT id, json_extract(result_json, '$.blocking.n_coll') FROM runs WHERE instr(result_json, '\"blocking\"') > 0");
  std::map<std::int64_t, std::vector<BlockingLevel>> out;
  while (q.row()) {
    const std::int64_t id = q.column_int(0);
    try {
      out[id] = blocking_curve_from_json(nlohmann::json::parse(q.column_text(1)));
    } catch (const nlohmann::json::exception& e) {
      throw StoreError(fmt::format("results store: run {}: its blocking curve cannot be read: {}", id, e.what()));
    }
  }
  return out;
}

std::vector<StoredProfile> read_profiles(const std::string& db_path, ExportSelection selection) {
  selection.table = ExportTable::Profiles;
  SelectedRows rows(db_path, selection);
  const SpecColumns run(rows, "run_id");
  const int i = rows.column("i"), z_std = rows.column("z_std"), z_std_err = rows.column("z_std_err"), K = rows.column("K_mean"),
            K_err = rows.column("K_err");
  std::vector<StoredProfile> out;
  while (rows.next()) {
    SqlStatement& r = rows.row();
    StoredProfile p;
    run.read(r, p.run_id, p.setup, p.spec);
    p.i = static_cast<int>(r.column_int(i));
    p.z_std = r.column_double(z_std);
    p.z_std_err = r.column_double(z_std_err);
    p.K_mean = r.column_double(K);
    p.K_err = r.column_double(K_err);
    out.push_back(std::move(p));
  }
  return out;
}

}  // namespace granchain
