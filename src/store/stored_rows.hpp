#pragma once
// Stored driven-column runs and their profiles as typed rows, for the analysis and the
// reproduction (no text in between). The selection is the export's (store/store_export.hpp).
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "engines/engine_registry.hpp"
#include "model/chain_parameters.hpp"
#include "simulation/driven_run.hpp"
#include "store/store_export.hpp"

namespace granchain {

// One row of the runs table with its point. Numbers the store holds as NULL are NaN.
struct StoredRun {
  std::int64_t id = 0;
  std::string setup;                     // "driven_column"
  RunSpec spec;                          // every stored parameter (k infinite for hard spheres); defaults where NULL
  double n_coll = 0, n_coll_err = 0;
  // Its two parts: floor (or plate) hits and pair collisions per unit time (n_coll = (floor + pairs) / N).
  double floor_rate = 0, floor_rate_err = 0, pp_rate = 0, pp_rate_err = 0;
  double wall_seconds = 0;
  double cpu_seconds = 0;                // the run's thread CPU time; NaN for runs stored before it was recorded
  std::optional<bool> stationary;        // the window's halves check; none for runs stored before it
  std::string point_key;                 // "" for a run stored outside a sweep or reproduction
  int replica = 0;                       // 0 where not stored
};

// One particle of a stored run's profiles, with the run's parameters.
struct StoredProfile {
  std::int64_t run_id = 0;
  std::string setup;
  RunSpec spec;  // the run's stored parameters the profiles export holds (engine, model, T, transient, seed, dt_factor)
  int i = 0;  // particle, 1 = bottom
  double z_std = 0, z_std_err = 0, K_mean = 0, K_err = 0;
};

// The selected runs (selection.table is ignored), in the store's order. Throws StoreError.
std::vector<StoredRun> read_runs(const std::string& db_path, ExportSelection selection);
// The selected profiles (selection.table is ignored), by run and particle. Throws StoreError.
std::vector<StoredProfile> read_profiles(const std::string& db_path, ExportSelection selection);
// The blocking curve of n_coll of every run that keeps one (simulation/driven_run.hpp; runs stored
// before the curves were kept have none), by run id. Throws StoreError.
std::map<std::int64_t, std::vector<BlockingLevel>> read_n_coll_blocking(const std::string& db_path);

}  // namespace granchain
