// Dynamical similarity of a column on a plate. On a plate k_B T0 sets only the initial velocities,
// and d only offsets the centres (the forces depend on the overlaps), so a column driven at (A, omega)
// with stiffness k is the column at (A / 4, 2 omega) with stiffness 4k seen with times halved and
// lengths quartered: every rate doubles (n_coll, the plate's hits), the gaps and the spread of a
// height quarter, and m v^2 quarters. The test runs both through the exact engine on each plate
// (their initial states are not similar, their stationary statistics are) and asks each ratio to
// hold within four combined errors:
// a time or stiffness scale taken wrongly anywhere in a plate's events breaks it.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <utility>

#include "model/plate_motion.hpp"
#include "simulation/driven_run.hpp"

using namespace granchain;

namespace {

RunResult plate_run(DriveKind kind, double A, double omega, double k, double T) {
  RunSpec spec;
  spec.params = ChainParameters{.N = 10, .k = k, .e = 0.7};
  spec.drive = DriveSpec{kind, A, omega};
  spec.T = T;
  spec.transient = 0.1 * T;
  spec.seed = 11;
  return run_driven_column(spec);
}

// a / b against the expected ratio, within four combined standard errors.
void expect_ratio(const Estimate& a, const Estimate& b, double ratio, const char* what, DriveKind kind) {
  const double r = a.value / b.value;
  const double err = std::abs(r) * std::hypot(a.error / a.value, b.error / b.value);
  EXPECT_NEAR(r, ratio, 4 * err) << drive_name(kind) << ": " << what << " " << a.value << " ± " << a.error << " over "
                                 << b.value << " ± " << b.error;
}

}  // namespace

TEST(PlateSimilarity, HalvingTimesAndQuarteringLengthsLeavesAColumnOnAPlateTheSame) {
  const double omega = 5.0, k = 1e5, T = 2000.0;
  for (const auto& [kind, A] : {std::pair{DriveKind::Sine, 0.2}, std::pair{DriveKind::Sawtooth, 0.2 * std::numbers::pi},
                                std::pair{DriveKind::Quadratic, 0.05 * std::numbers::pi}}) {
    const RunResult slow = plate_run(kind, A, omega, k, T);
    const RunResult fast = plate_run(kind, A / 4, 2 * omega, 4 * k, T / 2);
    expect_ratio(fast.n_coll, slow.n_coll, 2.0, "n_coll", kind);
    expect_ratio(fast.floor_rate, slow.floor_rate, 2.0, "plate hits per unit time", kind);
    const int N = slow.spec.params.N;
    for (int i : {0, N / 2, N - 1}) {
      // The height of particle i above its place in a column of touching spheres, (i + 1/2) d.
      const auto lift = [i](const RunResult& r) {
        Estimate e = r.profiles[i].z_mean;
        e.value -= (i + 0.5) * r.spec.params.d;
        return e;
      };
      expect_ratio(lift(fast), lift(slow), 0.25, "mean lift", kind);
      expect_ratio(fast.profiles[i].z_std, slow.profiles[i].z_std, 0.25, "height spread", kind);
      expect_ratio(fast.profiles[i].kinetic, slow.profiles[i].kinetic, 0.25, "kinetic energy", kind);
    }
  }
}
