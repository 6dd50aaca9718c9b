#pragma once
// How a sweep runs one of its points, on a thread of rank 0 or on another MPI rank: the driven
// run, resumed from its checkpoint and saved as it goes where the sweep keeps checkpoints
// (sweep/sweep_checkpoints.hpp) and the point's engine can save, and stopped early when the sweep
// is cancelled (a signal) or its time limit draws near. A finished point gives its result, a
// failed one its error (a collapse of hard spheres kept as such); a stopped one is saved (and
// taken up again by the next invocation) or, without a checkpoint, abandoned.
#include <limits>
#include <optional>
#include <string>

#include "engines/engine.hpp"
#include "simulation/cancellation.hpp"
#include "simulation/driven_run.hpp"
#include "sweep/sweep_checkpoints.hpp"

namespace granchain {

struct PointStops {
  const CancelFlag* cancel = nullptr;  // once set: stop now, saving the point if it has a checkpoint
  // Steady-clock seconds (steady_clock_seconds()) at which a point with a checkpoint still
  // running is saved and stopped (the end of a --time-limit draws near); infinity: never.
  double suspend_at = std::numeric_limits<double>::infinity();
};

enum class PointEnd { Finished, Failed, Collapsed, Saved, Abandoned };

struct PointOutcome {
  PointEnd end = PointEnd::Abandoned;
  std::optional<RunResult> result;                 // Finished
  std::string error;                               // Failed, Collapsed
  std::optional<InelasticCollapseError> collapse;  // Collapsed
  double saved_t = 0.0;                            // Saved: the simulated time it had reached
};

// Seconds of the steady clock since an arbitrary fixed moment (the one clock of PointStops).
double steady_clock_seconds();

// Runs the point; `live` (if set) receives its progress about every progress_every wall seconds.
// A checkpoint that cannot be written throws OutputError (the sweep cannot go on keeping states); a
// file in the checkpoint's place that is not this point's checkpoint is reported on standard
// error and overwritten, the point starting from t = 0.
PointOutcome run_sweep_point(const SweepPoint& point, const SweepCheckpoints* checkpoints, const PointStops& stops,
                             const ProgressCallback& live = {}, double progress_every = 0.5);

}  // namespace granchain
