#include "reproduce/replica_blocking.hpp"

#include <fmt/format.h>

#include "config/run_key.hpp"
#include "reproduce/store_analysis.hpp"

namespace granchain {

std::map<FamilyKey, std::map<double, CurveScatter>> blocking_against_replicas(const std::string& db, const std::vector<StoredRun>& rows,
                                                                              const std::set<std::int64_t>& left_out,
                                                                              const EnginePool& pool) {
  const std::map<std::int64_t, std::vector<BlockingLevel>> curves = read_n_coll_blocking(db);
  if (curves.empty()) return {};
  // Runs of one point differ only in their seeds (point_key_without_seed); by family and k.
  std::map<FamilyKey, std::map<double, std::map<std::string, std::vector<ReplicaRun>>>> points;
  for (const StoredRun& r : rows) {
    const auto c = curves.find(r.id);
    if (c == curves.end() || r.setup != "driven_column" || left_out.count(r.id)) continue;
    const FamilyKey f = family_key(r.spec, pool);
    points[f][r.spec.params.k][point_key_without_seed(r.spec)].push_back({r.n_coll, r.n_coll_err, c->second});
  }
  std::map<FamilyKey, std::map<double, CurveScatter>> out;
  for (const auto& [f, by_k] : points)
    for (const auto& [k, by_point] : by_k) {
      std::vector<std::vector<ReplicaRun>> groups;
      for (const auto& [key, runs] : by_point)
        if (runs.size() >= 2) groups.push_back(runs);
      if (groups.empty()) continue;
      const CurveScatter s = replica_scatter_by_level(groups);
      if (s.dof > 0) out[f][k] = s;
    }
  return out;
}

std::string curve_scatter_text(double k, const CurveScatter& s) {
  std::string levels;
  for (const LevelScatter& l : s.levels) levels += fmt::format("{}{}: {:.2f}", levels.empty() ? "" : ", ", l.blocks, l.chi2 / s.dof);
  return fmt::format("k = {}: {} points, {} runs, chi2/dof = {:.2f} with the reported errors; with the errors of blocks of "
                     "(window / blocks) {}",
                     power_of_ten_text(k), s.groups, s.runs, s.chi2_reported / s.dof, levels);
}

nlohmann::json curve_scatter_json(const std::map<double, CurveScatter>& by_k) {
  nlohmann::json j = nlohmann::json::array();
  for (const auto& [k, s] : by_k) {
    nlohmann::json levels = nlohmann::json::array();
    for (const LevelScatter& l : s.levels) levels.push_back({{"blocks", l.blocks}, {"chi2", l.chi2}});
    j.push_back({{"k", k}, {"points", s.groups}, {"runs", s.runs}, {"dof", s.dof}, {"chi2_reported", s.chi2_reported}, {"levels", levels}});
  }
  return j;
}

}  // namespace granchain
