#include "store/run_columns.hpp"

#include <cstdint>

#include "store/run_json.hpp"

namespace granchain {

namespace {

template <class Get>
ResultColumn real(const char* name, const char* declaration, Get get) {
  return {name, declaration, [get](SqlStatement& q, int i, const RunResult& r) { q.bind(i, static_cast<double>(get(r))); }};
}

template <class Get>
ResultColumn integer(const char* name, const char* declaration, Get get) {
  return {name, declaration, [get](SqlStatement& q, int i, const RunResult& r) { q.bind(i, static_cast<std::int64_t>(get(r))); }};
}

}  // namespace

// A real NaN is stored as NULL (SQLite's rule): an error that blocking could not give, a CPU time
// not measured.
const std::vector<ResultColumn>& run_result_columns() {
  static const std::vector<ResultColumn> columns = {
      real("damping_D", "REAL NOT NULL", [](const RunResult& r) { return r.law.D; }),  // Eq. Dd
      real("tau_c", "REAL NOT NULL", [](const RunResult& r) { return r.law.tau_c; }),  // Eq. tauc
      {"dt", "REAL",
       [](SqlStatement& q, int i, const RunResult& r) {
         if (r.time_step > 0) q.bind(i, r.time_step);
         else q.bind_null(i);  // an event-driven engine has no step
       }},
      integer("samples", "INTEGER NOT NULL", [](const RunResult& r) { return r.samples; }),
      real("n_coll", "REAL NOT NULL", [](const RunResult& r) { return r.n_coll.value; }),
      real("n_coll_err", "REAL", [](const RunResult& r) { return r.n_coll.error; }),
      integer("n_coll_blocks", "INTEGER NOT NULL", [](const RunResult& r) { return r.n_coll.blocks; }),
      integer("n_coll_converged", "INTEGER NOT NULL", [](const RunResult& r) { return r.n_coll.converged ? 1 : 0; }),
      real("floor_rate", "REAL NOT NULL", [](const RunResult& r) { return r.floor_rate.value; }),
      real("floor_rate_err", "REAL", [](const RunResult& r) { return r.floor_rate.error; }),
      real("pp_rate", "REAL NOT NULL", [](const RunResult& r) { return r.pp_rate.value; }),
      real("pp_rate_err", "REAL", [](const RunResult& r) { return r.pp_rate.error; }),
      integer("particle_collisions", "INTEGER NOT NULL", [](const RunResult& r) { return r.particle_collisions; }),
      integer("floor_hits", "INTEGER NOT NULL", [](const RunResult& r) { return r.floor_hits; }),
      integer("steps", "INTEGER NOT NULL", [](const RunResult& r) { return r.steps; }),
      integer("events", "INTEGER NOT NULL", [](const RunResult& r) { return r.events; }),
      real("wall_seconds", "REAL NOT NULL", [](const RunResult& r) { return r.wall_seconds; }),
      {"result_json", "TEXT NOT NULL", [](SqlStatement& q, int i, const RunResult& r) { q.bind(i, run_result_to_json(r).dump()); }},
      integer("stationary", "INTEGER", [](const RunResult& r) { return r.stationary() ? 1 : 0; }),
      real("cpu_seconds", "REAL", [](const RunResult& r) { return r.cpu_seconds; }),
  };
  return columns;
}

}  // namespace granchain
