#pragma once
// Runs the points of a sweep on a pool of threads (and, through mpi_sweep.hpp, on MPI ranks):
// points are handed out longest first from one queue, each finished point goes to a sink (the
// results store) one at a time, and progress is reported periodically. A point whose dynamics
// turns unphysical is reported to the sink with its error and the sweep goes on.
#include <atomic>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "engines/engine.hpp"
#include "simulation/cancellation.hpp"
#include "sweep/point_run.hpp"
#include "sweep/sweep_checkpoints.hpp"
#include "sweep/sweep_grid.hpp"

namespace granchain {

struct SweepProgress {
  std::size_t done = 0;       // points finished in this invocation (failed ones included)
  std::size_t failed = 0;
  std::size_t collapsed = 0;  // of the failed: hard spheres' inelastic collapse (stored as the point's outcome)
  std::size_t total = 0;      // points to run in this invocation
  double elapsed = 0.0;       // wall seconds
  // Wall seconds left: elapsed × (cost left) / (cost done), the costs from the cost model, the
  // running points credited with the fraction of their simulated time already covered; NaN before
  // any progress.
  double eta = 0.0;
  double collisions_per_second = 0.0;  // collision events of all workers (running points included)
  bool final = false;         // the last report
};

// Called for every finished point, never concurrently: result is null when the point failed,
// with the reason in error, and collapse set when the failure was hard spheres' inelastic collapse
// (an outcome that the store keeps, ResultsStore::insert_collapsed_point). May throw (a store that cannot be written): the sweep then stops
// handing out points and run() rethrows once the running points are done.
using PointSink = std::function<void(const SweepPoint& point, const RunResult* result, const std::string& error,
                                     const InelasticCollapseError* collapse)>;
using SweepProgressCallback = std::function<void(const SweepProgress&)>;

// The margin a time limit leaves on a point's estimate (SweepRunner::set_time_limit).
inline constexpr double kTimeLimitMargin = 1.25;
// With checkpoints, the seconds from the start at which the points still running that keep one are
// saved and stopped: 5 minutes before the limit (a fifth of it below 25 minutes), time for the
// last stretch of a transient (one time unit) and the save.
double checkpoint_deadline(double limit);
// The points of todo that no invocation with this time limit can start: their estimate alone, with
// the margin, exceeds it, and they keep no checkpoint (with checkpoints, a point of a resumable
// engine runs over several invocations). Empty without a limit (limit <= 0).
std::vector<std::size_t> points_longer_than(const std::vector<SweepPoint>& points, const std::vector<std::size_t>& todo, double limit,
                                            const SweepCheckpoints* checkpoints = nullptr);
// The one-line refusal for them: "--time-limit = 60 s is shorter than the estimated run of 3 points
// ...; valid: ...".
std::string time_limit_too_short_message(const std::vector<SweepPoint>& points, const std::vector<std::size_t>& longer, double limit);

class SweepRunner {
 public:
  // todo: indices into points, in the order to hand them out.
  SweepRunner(const std::vector<SweepPoint>& points, std::vector<std::size_t> todo, PointSink sink);

  // Runs every point of todo on `threads` local threads (and whatever else calls next() and
  // record()), reporting progress every `progress_every` seconds and once at the end.
  void run(int threads, const SweepProgressCallback& progress = {}, double progress_every = 1.0,
           const std::function<void()>& also_run_on_this_thread = {});

  // The queue, for other workers (MPI ranks): the next point to run, or nothing when all are out.
  std::optional<std::size_t> next();
  // A point finished elsewhere: passes it to the sink and counts it.
  // under_lock runs first, under the lock that guards the counts.
  void record(std::size_t index, const RunResult* result, const std::string& error, const std::function<void()>& under_lock = {},
              const InelasticCollapseError* collapse = nullptr);

  SweepProgress progress() const;

  // How often (wall seconds) a running point reports how far it has got; 0.5 unless set.
  void set_point_progress_every(double seconds) { point_progress_every_ = seconds; }

  // A time limit (wall seconds from the start of run(); a batch job's walltime): a point is handed
  // out only if it is predicted to finish within it, its cost-model estimate scaled by the ratio of
  // wall time to estimate of the points finished so far (1 before any, held within 0.25 .. 10) and
  // by the margin kTimeLimitMargin. Points that do not fit are skipped, smaller ones after them may
  // still run; the skipped ones are left for a later invocation (not_started()). A worker that
  // finds nothing that fits stops (time only runs out).
  // With checkpoints (set_checkpoints) a point that keeps one is handed out while the time is
  // before checkpoint_deadline, whether or not it can end within the limit, and saved and stopped
  // there if it has not ended.
  void set_time_limit(double seconds) { time_limit_ = seconds; }
  // Points of resumable engines keep their state in `checkpoints` (resumed from there, saved as they
  // go and when stopped, the file removed once the point is stored); points with a saved state are
  // handed out first. Set before run().
  void set_checkpoints(const SweepCheckpoints* checkpoints);
  // What stops a point running on this process: the cancel flag and the checkpoint deadline.
  PointStops stops() const;
  // Cancelling: once `flag` (simulation/cancellation.hpp) is set, from any thread, no point is
  // handed out any more and the points running are abandoned at their next progress report
  // (set_point_progress_every), neither recorded nor passed to the sink; run() then returns.
  // Points finished before are kept as usual. Null: not cancellable.
  void watch(const CancelFlag* flag) { cancel_ = flag; }
  bool cancelled() const { return cancel_requested(cancel_); }

  // A point stopped with its state saved (a cancel, the time limit): counted, not passed to the sink.
  void record_saved(std::size_t index);
  // A point abandoned unfinished and unsaved (its worker was cancelled): back in the queue, for
  // another worker or a repeat of the command.
  void put_back(std::size_t index);
  // An error that ends the sweep (a checkpoint that cannot be written, on any worker): no point is
  // handed out any more, the points running go on and are stored, and run() rethrows it once they
  // are done (after a failure of the store, which it rethrows first).
  void fail(std::exception_ptr error);

  // Points of todo never handed out (after run(): those the time limit left).
  std::size_t not_started() const;
  // Points stopped with their state saved in the checkpoints.
  std::size_t saved() const;
  double not_started_cost() const;  // their estimated cost, seconds of one core

 private:
  void worker(int slot);

  const std::vector<SweepPoint>& points_;
  std::vector<std::size_t> todo_;
  PointSink sink_;
  double total_cost_ = 0.0;

  bool fits_in_time_limit(const SweepPoint& point) const;  // under mutex_
  const SweepCheckpoints* checkpoints_ = nullptr;

  mutable std::mutex mutex_;  // guards the fields below and calls of the sink
  std::vector<char> handed_;   // per position of todo_: handed out
  std::size_t handed_out_ = 0;  // how many
  std::size_t scan_from_ = 0;   // every position before it is handed out
  double time_limit_ = std::numeric_limits<double>::infinity();
  double done_wall_ = 0.0, done_wall_cost_ = 0.0;  // wall seconds and estimates of finished points with a result
  std::size_t done_ = 0;
  std::size_t failed_ = 0, collapsed_ = 0, saved_ = 0;
  double done_cost_ = 0.0;
  std::uint64_t finished_events_ = 0;
  std::exception_ptr sink_error_;   // the store failed: nothing more is stored
  std::exception_ptr fatal_error_;  // fail(): no point is handed out any more, the running ones are still stored
  std::atomic<bool> stop_{false};
  const CancelFlag* cancel_ = nullptr;

  std::unique_ptr<std::atomic<std::uint64_t>[]> live_events_;  // per local thread, of its running point
  std::unique_ptr<std::atomic<double>[]> live_cost_;           // per local thread: cost × fraction of its point done
  int threads_ = 0;
  double point_progress_every_ = 0.5;
  double start_ = 0.0;
};

}  // namespace granchain
