// The driven column's hard-sphere limit (docs/beyond.md, section 6). At N = 25 hard spheres on the
// thermal floor collapse for e below about 0.77 and run regularly above it; there the exact engine's
// n_coll, which grows with k through the paper's window, settles on the hard-sphere engine's value.
#include <gtest/gtest.h>

#include <cmath>

#include "engines/engine.hpp"
#include "simulation/driven_run.hpp"

using namespace granchain;

namespace {

RunResult driven(double e, EngineKind engine, double k, double T) {
  RunSpec spec;
  spec.params = ChainParameters{.N = 25, .k = k, .e = e};
  spec.engine.kind = engine;
  spec.T = T;
  spec.transient = 0.1 * T;
  spec.seed = 3;
  return run_driven_column(spec);
}

}  // namespace

TEST(DrivenHardLimit, HardSpheresCollapseBelowTheThresholdAndRunAboveIt) {
  EXPECT_THROW(driven(0.76, EngineKind::Hard, 1e5, 100.0), InelasticCollapseError);
  EXPECT_NO_THROW(driven(0.80, EngineKind::Hard, 1e5, 100.0));
}

TEST(DrivenHardLimit, SoftColumnSettlesOnTheHardSphereValue) {
  // e = 0.85 lies in the paper's power-law regime at N = 25 (below e_c2), above the hard threshold.
  const RunResult hard = driven(0.85, EngineKind::Hard, 1e5, 200.0);
  const RunResult soft = driven(0.85, EngineKind::Exact, 1e16, 200.0);
  const RunResult window = driven(0.85, EngineKind::Exact, 1e8, 200.0);  // the paper's window
  const auto combined = [](const RunResult& a, const RunResult& b) { return std::hypot(a.n_coll.error, b.n_coll.error); };
  EXPECT_NEAR(soft.n_coll.value, hard.n_coll.value, 4 * combined(soft, hard))
      << "k = 1e16: " << soft.n_coll.value << " ± " << soft.n_coll.error << ", hard " << hard.n_coll.value << " ± " << hard.n_coll.error;
  // Within the paper's window the column is far from its limit: the test can tell.
  EXPECT_GT(hard.n_coll.value - window.n_coll.value, 10 * combined(window, hard))
      << "k = 1e8: " << window.n_coll.value << " ± " << window.n_coll.error;
}
