// The driven column's hard-sphere limit (docs/beyond.md, section 6). At N = 25 hard spheres on the
// thermal floor collapse for e below about 0.77 and run regularly above it; there the exact engine's
// n_coll, which grows with k through the paper's window, settles on the hard-sphere engine's value.
#include <gtest/gtest.h>

#include <cmath>

#include "engines/engine.hpp"
#include "model/floor.hpp"
#include "simulation/driven_run.hpp"

using namespace granchain;

namespace {

RunResult driven(double e, EngineKind engine, double k, double T, double start_k = 0.0) {
  RunSpec spec;
  spec.params = ChainParameters{.N = 25, .k = k, .e = e};
  spec.engine.kind = engine;
  spec.engine.start_k = start_k;
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

// The hard engine started from the soft column's state (--start-k): above the threshold its n_coll
// is the one from the initial state (the stationary state does not remember its start); below it the
// hard column collapses from the stationary state too, after the transient that the exact engine ran.
TEST(DrivenHardLimit, HardSpheresStartedFromTheSoftColumnAgreeAboveTheThresholdAndCollapseBelowIt) {
  const RunResult from_initial = driven(0.80, EngineKind::Hard, 1e5, 200.0);
  const RunResult from_soft = driven(0.80, EngineKind::Hard, 1e5, 200.0, 1e10);
  EXPECT_NEAR(from_soft.n_coll.value, from_initial.n_coll.value, 4 * std::hypot(from_soft.n_coll.error, from_initial.n_coll.error))
      << "soft start " << from_soft.n_coll.value << " ± " << from_soft.n_coll.error << ", initial state " << from_initial.n_coll.value
      << " ± " << from_initial.n_coll.error;
  // Not the same trajectory: the floor's speeds are drawn by the soft transient, not by hard spheres.
  EXPECT_NE(from_soft.particle_collisions, from_initial.particle_collisions);
  try {
    driven(0.72, EngineKind::Hard, 1e5, 200.0, 1e10);
    ADD_FAILURE() << "hard spheres at e = 0.72 ran through the window";
  } catch (const InelasticCollapseError& c) {
    EXPECT_GE(c.time(), 20.0) << "the collapse came before the hard spheres took over";
  }
}

// The state handed over: no pair overlaps, particle 1 stands on the plate's surface at least,
// velocities unchanged, each centre raised by no more than the overlaps below it.
TEST(DrivenHardLimit, HardSphereStartClosesEveryOverlapFromTheBottomUp) {
  const ChainParameters p{.N = 4, .k = 1e8, .e = 0.5};
  const PlateMotion motion(DriveKind::Sine, 0.1, 2.0, 0.3);
  const VibratingPlate plate(motion, p.e);
  ChainState soft{.t = 1.7, .z = {motion.z(1.7) + 0.5 - 1e-9, 1.5 - 2e-9, 2.6, 3.6 - 1e-8}, .v = {0.1, -0.2, 0.3, -0.4}};
  const ChainState hard = hard_sphere_start(soft, p, plate);
  EXPECT_EQ(hard.t, soft.t);
  EXPECT_EQ(hard.v, soft.v);
  EXPECT_GE(hard.z[0] - 0.5 * p.d, motion.z(1.7));
  double raised = 0.0;
  for (int i = 0; i < 4; ++i) {
    if (i > 0) EXPECT_GE(hard.z[i] - hard.z[i - 1], p.d) << "pair " << i;
    EXPECT_GE(hard.z[i], soft.z[i]);
    raised = std::max(raised, hard.z[i] - soft.z[i]);
  }
  EXPECT_LT(raised, 2e-8);
  EXPECT_EQ(hard.z[2], soft.z[2]) << "a pair with a gap is left as it was";
}
