#include "store/stored_rows.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "store/results_store.hpp"
#include "store/sqlite_statement.hpp"

namespace granchain {

namespace {

EngineKind engine_of(const std::string& name, std::int64_t id) {
  try {
    return stored_engine_kind(name);
  } catch (const std::invalid_argument&) {
    throw StoreError(fmt::format("results store: run {} names an engine this granchain does not know: '{}'", id, name));
  }
}

// The columns every row of runs and profiles has (the run's id, set-up, engine and the model's
// parameters), and their values in the current row.
struct RunColumns {
  int id, setup, engine, N, e, k, T0, m, d, g;
  RunColumns(SelectedRows& rows, const char* id_column)
      : id(rows.column(id_column)), setup(rows.column("setup")), engine(rows.column("engine")), N(rows.column("N")),
        e(rows.column("e")), k(rows.column("k")), T0(rows.column("T0")), m(rows.column("m")), d(rows.column("d")),
        g(rows.column("g")) {}
  void read(SqlStatement& r, std::int64_t& run_id, std::string& run_setup, EngineKind& kind, ChainParameters& p) const {
    run_id = r.column_int(id);
    run_setup = r.column_text(setup);
    kind = engine_of(r.column_text(engine), run_id);
    p.N = static_cast<int>(r.column_int(N));
    p.e = r.column_double(e);
    p.k = r.column_double(k);
    p.kT0 = r.column_double(T0);
    p.m = r.column_double(m);
    p.d = r.column_double(d);
    p.g = r.column_double(g);
  }
};

}  // namespace

std::vector<StoredRun> read_runs(const std::string& db_path, ExportSelection selection) {
  selection.table = ExportTable::Runs;
  SelectedRows rows(db_path, selection);
  const RunColumns run(rows, "id");
  const int T = rows.column("T"), transient = rows.column("transient"), seed = rows.column("seed"),
            dt_factor = rows.column("dt_factor"), tc = rows.column("tc"), n_coll = rows.column("n_coll"),
            n_coll_err = rows.column("n_coll_err"), wall = rows.column("wall_seconds"), cpu = rows.column("cpu_seconds"),
            stationary = rows.column("stationary"), key = rows.column("point_key"), replica = rows.column("replica");
  std::vector<StoredRun> out;
  while (rows.next()) {
    SqlStatement& r = rows.row();
    StoredRun s;
    run.read(r, s.id, s.setup, s.engine.kind, s.params);
    s.engine.dt_factor = r.column_double(dt_factor);
    s.engine.hard.tc = r.column_double(tc);
    s.T = r.column_double(T);
    s.transient = r.column_double(transient);
    s.seed = static_cast<std::uint64_t>(r.column_int(seed));
    s.n_coll = r.column_double(n_coll);
    s.n_coll_err = r.column_double(n_coll_err);
    s.wall_seconds = r.column_double(wall);
    s.cpu_seconds = r.column_double(cpu);
    if (r.column_type(stationary) != SQLITE_NULL) s.stationary = r.column_int(stationary) != 0;
    s.point_key = r.column_text(key);
    s.replica = r.column_type(replica) == SQLITE_NULL ? 0 : static_cast<int>(r.column_int(replica));
    out.push_back(std::move(s));
  }
  return out;
}

std::vector<StoredProfile> read_profiles(const std::string& db_path, ExportSelection selection) {
  selection.table = ExportTable::Profiles;
  SelectedRows rows(db_path, selection);
  const RunColumns run(rows, "run_id");
  const int i = rows.column("i"), z_std = rows.column("z_std"), z_std_err = rows.column("z_std_err"), K = rows.column("K_mean"),
            K_err = rows.column("K_err");
  std::vector<StoredProfile> out;
  while (rows.next()) {
    SqlStatement& r = rows.row();
    StoredProfile p;
    run.read(r, p.run_id, p.setup, p.engine, p.params);
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
