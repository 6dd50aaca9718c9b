#pragma once
// Blocking against independent replicas, level by level (analysis/blocking.hpp,
// replica_scatter_by_level): for every (engine, drive, N, kT0) and k of a store, the replicas of each
// e that keep a blocking curve, and whether their scatter is seen by the reported errors, by longer
// blocks within one run, or by neither (states that outlast the longest block).
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "analysis/blocking.hpp"
#include "reproduce/engine_pool.hpp"
#include "store/stored_rows.hpp"

namespace granchain {

using FamilyKey = std::tuple<EngineKind, DriveSpec, int, double>;  // engine, drive, N, kT0
// The family a stored run is analysed in: its engine as the pool has it, drive, N and kT0.
inline FamilyKey family_key(const RunSpec& spec, const EnginePool& pool) {
  return {pool.family_engine(spec.engine.kind), spec.drive, spec.params.N, spec.params.kT0};
}

// `rows` are the selected runs of `db`; points with two or more runs that keep a curve enter, less
// the runs in `left_out` (those the analysis left out: unsettled windows, repeated trajectories).
// Families are keyed by pool.family_engine; the replicas of a point are runs of one engine.
std::map<FamilyKey, std::map<double, CurveScatter>> blocking_against_replicas(const std::string& db, const std::vector<StoredRun>& rows,
                                                                              const std::set<std::int64_t>& left_out,
                                                                              const EnginePool& pool);
// "k = 1e6: 4 points, 12 runs, chi2/dof 1.31 with the reported errors; with 1024 .. 16 blocks: 4.2, ..., 1.05"
std::string curve_scatter_text(double k, const CurveScatter& s);
nlohmann::json curve_scatter_json(const std::map<double, CurveScatter>& by_k);

}  // namespace granchain
