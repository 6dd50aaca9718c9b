#include "sweep/point_run.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cstdio>

#include "model/state_archive.hpp"
#include "store/output_file.hpp"
#include "version.hpp"

namespace granchain {

double steady_clock_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

PointOutcome run_sweep_point(const SweepPoint& point, const SweepCheckpoints* checkpoints, const PointStops& stops,
                             const ProgressCallback& live, double progress_every) {
  const bool keeping = checkpoints != nullptr && SweepCheckpoints::covers(point);
  std::optional<RunCheckpoint> from;
  if (keeping) {
    try {
      from = checkpoints->saved(point);
      if (from) {
        const SavedRunPlace place = saved_run_place(from->state);
        const bool other_build = from->written_by != code_version();
        if (checkpoints->announces_resumes() || other_build)
          fmt::print(stderr, "sweep: {}resuming {} at t = {:.6g} of {:.6g} ({}, saved by granchain {}{})\n", other_build ? "warning: " : "",
                     point.key, place.t, point.spec.transient + point.spec.T, place.in_window ? "measuring" : "transient", from->written_by,
                     other_build ? fmt::format("; this is {}: bit for bit the same result only if the engine and observers are unchanged",
                                               code_version())
                                 : "");
      }
    } catch (const std::exception& e) {  // CheckpointError, StateArchiveError: of no use to the point, and in its way
      fmt::print(stderr, "granchain: warning: --checkpoint-dir: {}; point {} starts anew and overwrites it\n", e.what(), point.key);
      from.reset();
    }
  }

  PointOutcome out;
  bool saved_any = false;
  RunResumption resumption;
  if (keeping) {
    resumption.resume_from = from ? &from->state : nullptr;
    resumption.every = checkpoints->every();
    resumption.save = [&](const StateArchive& state) {
      checkpoints->save(point, state);
      out.saved_t = saved_run_place(state).t;
      saved_any = true;
    };
  }
  // Stops are looked at in every progress report: every progress_every wall seconds, at a sample
  // or (in the transient) a whole time unit.
  const bool suspendable = keeping && stops.suspend_at < std::numeric_limits<double>::infinity();
  ProgressCallback watch = [&](const RunProgress& p) {
    if (cancel_requested(stops.cancel) || (suspendable && steady_clock_seconds() >= stops.suspend_at)) throw RunCancelled{};
    if (live) live(p);
  };
  try {
    try {
      out.result = run_driven_column(point.spec, watch, progress_every, resumption);
    } catch (const StateArchiveError& e) {  // a state of this key that does not fit (another build's layout)
      if (resumption.resume_from == nullptr) throw;
      fmt::print(stderr, "granchain: warning: --checkpoint-dir: {} does not fit point {} ({}); it starts anew\n", checkpoints->path(point),
                 point.key, e.what());
      resumption.resume_from = nullptr;
      out.result = run_driven_column(point.spec, watch, progress_every, resumption);
    }
    out.end = PointEnd::Finished;
  } catch (const RunCancelled&) {  // run_driven_column saved the state, where it keeps one
    out.end = saved_any ? PointEnd::Saved : PointEnd::Abandoned;
  } catch (const InelasticCollapseError& c) {  // hard spheres: an outcome of the point
    out.end = PointEnd::Collapsed;
    out.error = c.what();
    out.collapse = c;
  } catch (const OutputError&) {
    throw;
  } catch (const std::exception& e) {  // UnphysicalStateError, a state that does not fit, no memory for this point
    out.end = PointEnd::Failed;
    out.error = e.what();
  }
  return out;
}

}  // namespace granchain
