// The free-space collapse counts of the results store (granchain collapse, reproduce): one row
// per count in collapse_runs, identified by its definition (collapse_identity_columns()), and one per
// launch in collapse_realizations.
#include <fmt/format.h>
#include <sqlite3.h>

#include "config/collapse_options.hpp"
#include "store/collapse_json.hpp"
#include "store/results_store.hpp"
#include "store/sqlite_statement.hpp"
#include "version.hpp"

namespace granchain {

namespace {

// The values of collapse_identity_columns() for a collapse count, in that order, from index c on.
void bind_collapse_definition(SqlStatement& q, int& c, const CollapseSpec& s) {
  for (const TypedValue& v : stored_collapse_values(s)) q.bind(c++, v);  // k = +inf for hard spheres (SQLite keeps it as Inf)
}

// The id of the first stored count with this definition, if any.
std::optional<std::int64_t> stored_collapse_id(sqlite3* db, const CollapseSpec& spec) {
  std::string where;
  for (const std::string& c : collapse_identity_columns()) where += fmt::format("{}{} = ?", where.empty() ? "" : " AND ", c);
  SqlStatement find(db, ("SELECT id FROM collapse_runs WHERE " + where + " ORDER BY id LIMIT 1").c_str());
  int f = 1;
  bind_collapse_definition(find, f, spec);
  if (!find.row()) return std::nullopt;
  return find.column_int(0);
}

}  // namespace

std::vector<std::string> collapse_identity_columns() {
  std::vector<std::string> columns;
  for (const Parameter* p : stored_collapse_parameters()) columns.push_back(p->store_column);
  return columns;
}

std::optional<CollapseResult> ResultsStore::find_collapse(const CollapseSpec& spec) {
  const std::optional<std::int64_t> id = stored_collapse_id(db_, spec);
  if (!id) return std::nullopt;
  SqlStatement find(db_, "SELECT tau_c, n_tot, n_tot_err, n_tot_min, n_tot_max, collapsed, wall_seconds FROM collapse_runs WHERE id = ?");
  find.bind(1, *id);
  find.row();
  CollapseResult r;
  r.spec = spec;
  r.law.tau_c = find.column_double(0);
  r.n_tot_mean = find.column_double(1);
  r.n_tot_error = find.column_double(2);
  r.n_tot_min = static_cast<std::uint64_t>(find.column_int(3));
  r.n_tot_max = static_cast<std::uint64_t>(find.column_int(4));
  r.collapsed = static_cast<int>(find.column_int(5));
  r.wall_seconds = find.column_double(6);
  SqlStatement real(db_, "SELECT particle_collisions, wall_hits, collapsed, t_stop FROM collapse_realizations WHERE run_id = ? ORDER BY realization");
  real.bind(1, *id);
  while (real.row()) {
    RealizationOutcome o;
    o.particle_collisions = static_cast<std::uint64_t>(real.column_int(0));
    o.wall_hits = static_cast<std::uint64_t>(real.column_int(1));
    o.collapsed = real.column_int(2) != 0;
    o.t_stop = real.column_double(3);
    r.collisions += o.particle_collisions;
    r.outcomes.push_back(o);
  }
  if (static_cast<int>(r.outcomes.size()) != spec.realizations) return std::nullopt;  // an incomplete row is not the count
  return r;
}

std::int64_t ResultsStore::insert_collapse(const CollapseResult& r) {
  return in_transaction([&] {
    if (const std::optional<std::int64_t> stored = stored_collapse_id(db_, r.spec)) return *stored;  // the same count is already stored
    std::string names = "created_utc, code_version", marks = "?,?";
    for (const std::string& c : collapse_identity_columns()) {
      names += ", " + c;
      marks += ",?";
    }
    SqlStatement row(db_, fmt::format("INSERT INTO collapse_runs({}, tau_c, n_tot, n_tot_err, n_tot_min, n_tot_max, collapsed, "
                                      "wall_seconds, result_json) VALUES({},?,?,?,?,?,?,?,?)", names, marks).c_str());
    const CollapseSpec& s = r.spec;
    int c = 1;
    row.bind(c++, utc_now());
    row.bind(c++, std::string(code_version()));
    bind_collapse_definition(row, c, s);
    row.bind(c++, r.law.tau_c);
    row.bind(c++, r.n_tot_mean);  // NaN (no realisation finished) is stored as NULL
    row.bind(c++, r.n_tot_error);
    row.bind(c++, static_cast<std::int64_t>(r.n_tot_min));
    row.bind(c++, static_cast<std::int64_t>(r.n_tot_max));
    row.bind(c++, static_cast<std::int64_t>(r.collapsed));
    row.bind(c++, r.wall_seconds);
    row.bind(c++, collapse_result_to_json(r).dump());
    row.run();
    const std::int64_t id = sqlite3_last_insert_rowid(db_);
    SqlStatement real(db_, "INSERT INTO collapse_realizations(run_id, realization, particle_collisions, wall_hits, collapsed, t_stop) VALUES(?,?,?,?,?,?)");
    for (std::size_t i = 0; i < r.outcomes.size(); ++i) {
      const RealizationOutcome& o = r.outcomes[i];
      real.bind(1, id);
      real.bind(2, static_cast<std::int64_t>(i));
      real.bind(3, static_cast<std::int64_t>(o.particle_collisions));
      real.bind(4, static_cast<std::int64_t>(o.wall_hits));
      real.bind(5, static_cast<std::int64_t>(o.collapsed));
      real.bind(6, o.t_stop);
      real.run();
    }
    return id;
  });
}

}  // namespace granchain
