#pragma once
// The analysis of a results store, shared by `granchain analyze` and `granchain reproduce`: the
// regimes and critical values of the stored n_coll(k) (analysis/regime_report), the partially
// condensed state from the stored profiles (analysis/condensation), as JSON, as text tables, and
// as the panels of Fig. cfreqlogN25 (plots/ncoll_panels.py).
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <tuple>

#include "analysis/condensation.hpp"
#include "analysis/regime_report.hpp"
#include "reproduce/engine_pool.hpp"
#include "reproduce/replica_blocking.hpp"
#include "store/output_file.hpp"
#include "store/store_export.hpp"

namespace granchain {

struct Condensation {
  double k = 0;  // the largest k stored for the point, whose profiles were used
  analysis::CondensationCheck check;
  // The profiles it was judged on (Fig. partial_cond), bottom particle first: K_i and sigma_i
  // (replicas combined), and the elastic column's sigma_0,i (empty when not available).
  std::vector<analysis::ParticleValue> K, sigma;
  std::vector<double> sigma0;
};

// One stored run's cost: its CPU time (wall time where the store has none) beside what the cost
// model predicts for it (sweep/cost_model.hpp), for the reports' cost tables.
struct RunCost {
  int N = 0;
  double seconds = 0, predicted = 0;
};

struct StoreAnalysis {
  std::size_t runs = 0;
  double run_seconds = 0;  // the runs' stored CPU times (wall times for runs stored without one), summed
  std::vector<RunCost> costs;  // per run, in the store's order
  double k_min = 0;
  EnginePool pool;  // the engines analysed as one (empty: each apart); names the families
  analysis::RegimeReport report;
  std::map<FamilyKey, std::map<double, Condensation>> condensation;  // by e
  // The replicas' scatter against their blocking curves, by family and k (reproduce/replica_blocking.hpp).
  std::map<FamilyKey, std::map<double, CurveScatter>> blocking_checks;
  nlohmann::json json;
};

// A critical value as JSON (value, error, bracket low/high, method), null when not found.
nlohmann::json critical_json(const analysis::CriticalValue& c);

// "v ± e" with `digits` decimals, or "-" when v is not finite.
std::string plus_minus(double v, double e, int digits = 3);
// A value of k as text: 1e5 rather than 1e+05 for a power of ten, %g otherwise.
std::string power_of_ten_text(double k);
// "1e5–1e6: 0.27 ± 0.01, 1e6–1e7: ..." (local exponents per interval of k), "-" when empty.
std::string local_exponents_text(const std::vector<analysis::LocalExponent>& l);
nlohmann::json local_exponents_json(const std::vector<analysis::LocalExponent>& l);

// Throws StoreError when the store cannot be read. Runs of the engines in `pool` are analysed as one
// engine (reproduce/engine_pool.hpp).
StoreAnalysis analyze_store(const std::string& db, const ExportSelection& selection, double k_min, const EnginePool& pool = {});
std::string analysis_text(const StoreAnalysis& a);
// Per N: runs, measured and predicted CPU-hours, the geometric mean of the runs' measured / predicted
// and how many lie within a factor of 2 (a Markdown table; "" when no run is stored).
std::string cost_markdown(const std::vector<RunCost>& costs);
// The runs the analysis left out, grouped by point, each with its reason ("" if none).
std::string excluded_text(const std::vector<analysis::ExcludedRun>& excluded, const EnginePool& pool);
// The same as a report section (Markdown), "" if none.
std::string excluded_markdown(const StoreAnalysis& a);
// Writes PREFIX.json and the panels PREFIX_N<N>_T0<T0>_<engine>[_<drive>_A<A>_w<omega>].png/.pdf;
// "" or what went wrong.
// `option` names the flag that chose the prefix, for messages.
std::string draw_ncoll_panels(const StoreAnalysis& a, const std::string& prefix, const std::string& option = "--plot");
// Every file draw_ncoll_panels writes: PREFIX.json, then each panel's PNG and PDF.
std::vector<std::string> ncoll_panel_files(const StoreAnalysis& a, const std::string& prefix);

}  // namespace granchain
