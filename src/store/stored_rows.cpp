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

}  // namespace

std::vector<StoredRun> read_runs(const std::string& db_path, ExportSelection selection) {
  selection.table = ExportTable::Runs;
  SelectedRows rows(db_path, selection);
  const int id = rows.column("id"), setup = rows.column("setup"), engine = rows.column("engine"), N = rows.column("N"),
            e = rows.column("e"), k = rows.column("k"), T0 = rows.column("T0"), m = rows.column("m"), d = rows.column("d"),
            g = rows.column("g"), T = rows.column("T"), transient = rows.column("transient"), seed = rows.column("seed"),
            dt_factor = rows.column("dt_factor"), tc = rows.column("tc"), n_coll = rows.column("n_coll"),
            n_coll_err = rows.column("n_coll_err"), wall = rows.column("wall_seconds"), cpu = rows.column("cpu_seconds"),
            stationary = rows.column("stationary"), key = rows.column("point_key"), replica = rows.column("replica");
  std::vector<StoredRun> out;
  while (rows.next()) {
    SqlStatement& r = rows.row();
    StoredRun s;
    s.id = r.column_int(id);
    s.setup = r.column_text(setup);
    s.engine.kind = engine_of(r.column_text(engine), s.id);
    s.engine.dt_factor = r.column_double(dt_factor);
    s.engine.hard.tc = r.column_double(tc);
    s.params.N = static_cast<int>(r.column_int(N));
    s.params.e = r.column_double(e);
    s.params.k = r.column_double(k);
    s.params.kT0 = r.column_double(T0);
    s.params.m = r.column_double(m);
    s.params.d = r.column_double(d);
    s.params.g = r.column_double(g);
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
  const int id = rows.column("run_id"), setup = rows.column("setup"), engine = rows.column("engine"), N = rows.column("N"),
            e = rows.column("e"), k = rows.column("k"), T0 = rows.column("T0"), m = rows.column("m"), d = rows.column("d"),
            g = rows.column("g"), i = rows.column("i"), z_std = rows.column("z_std"), z_std_err = rows.column("z_std_err"),
            K = rows.column("K_mean"), K_err = rows.column("K_err");
  std::vector<StoredProfile> out;
  while (rows.next()) {
    SqlStatement& r = rows.row();
    StoredProfile p;
    p.run_id = r.column_int(id);
    p.setup = r.column_text(setup);
    p.engine = engine_of(r.column_text(engine), p.run_id);
    p.params.N = static_cast<int>(r.column_int(N));
    p.params.e = r.column_double(e);
    p.params.k = r.column_double(k);
    p.params.kT0 = r.column_double(T0);
    p.params.m = r.column_double(m);
    p.params.d = r.column_double(d);
    p.params.g = r.column_double(g);
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
