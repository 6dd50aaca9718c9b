#include "sweep/sweep_runner.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <limits>
#include <thread>

#include "sweep/sweep_progress.hpp"


namespace granchain {

double checkpoint_deadline(double limit) { return limit - std::min(300.0, limit / 5); }

std::vector<std::size_t> points_longer_than(const std::vector<SweepPoint>& points, const std::vector<std::size_t>& todo, double limit,
                                            const SweepCheckpoints* checkpoints) {
  std::vector<std::size_t> longer;
  if (limit > 0)
    for (std::size_t i : todo)
      if (kTimeLimitMargin * points.at(i).cost > limit && !(checkpoints && SweepCheckpoints::covers(points.at(i)))) longer.push_back(i);
  return longer;
}

std::string time_limit_too_short_message(const std::vector<SweepPoint>& points, const std::vector<std::size_t>& longer, double limit) {
  double longest = 0;
  for (std::size_t i : longer) longest = std::max(longest, points.at(i).cost);
  return fmt::format("--time-limit = {} is shorter than the estimated run of {} point{} (the longest {} of one core, {} with the "
                     "margin {}); valid: a limit of at least {}, or a grid without those points",
                     format_duration(limit), longer.size(), longer.size() == 1 ? "" : "s", format_duration(longest),
                     format_duration(kTimeLimitMargin * longest), kTimeLimitMargin, format_duration(kTimeLimitMargin * longest));
}

SweepRunner::SweepRunner(const std::vector<SweepPoint>& points, std::vector<std::size_t> todo, PointSink sink)
    : points_(points), todo_(std::move(todo)), sink_(std::move(sink)), handed_(todo_.size(), 0) {
  for (std::size_t i : todo_) total_cost_ += points_.at(i).cost;
  start_ = steady_clock_seconds();
}

bool SweepRunner::fits_in_time_limit(const SweepPoint& point) const {
  if (!std::isfinite(time_limit_)) return true;
  const double elapsed = steady_clock_seconds() - start_;
  if (checkpoints_ && SweepCheckpoints::covers(point)) return elapsed < checkpoint_deadline(time_limit_);
  const double ratio = done_wall_cost_ > 0 ? std::clamp(done_wall_ / done_wall_cost_, 0.25, 10.0) : 1.0;
  return elapsed + kTimeLimitMargin * ratio * point.cost <= time_limit_;
}

void SweepRunner::set_checkpoints(const SweepCheckpoints* checkpoints) {
  checkpoints_ = checkpoints;
  if (checkpoints_)
    std::stable_partition(todo_.begin(), todo_.end(), [&](std::size_t i) { return checkpoints_->has_saved(points_[i]); });
}

PointStops SweepRunner::stops() const {
  PointStops s;
  s.cancel = cancel_;
  if (checkpoints_ && std::isfinite(time_limit_)) s.suspend_at = start_ + checkpoint_deadline(time_limit_);
  return s;
}

std::optional<std::size_t> SweepRunner::next() {
  std::lock_guard lock(mutex_);
  if (stop_ || cancelled()) return std::nullopt;
  for (std::size_t j = scan_from_; j < todo_.size(); ++j) {
    if (handed_[j] || !fits_in_time_limit(points_[todo_[j]])) continue;
    handed_[j] = 1;
    ++handed_out_;
    while (scan_from_ < todo_.size() && handed_[scan_from_]) ++scan_from_;
    return todo_[j];
  }
  return std::nullopt;
}

std::size_t SweepRunner::not_started() const {
  std::lock_guard lock(mutex_);
  return todo_.size() - handed_out_;
}

std::size_t SweepRunner::saved() const {
  std::lock_guard lock(mutex_);
  return saved_;
}

void SweepRunner::record_saved(std::size_t) {
  std::lock_guard lock(mutex_);
  ++saved_;
}

void SweepRunner::put_back(std::size_t index) {
  std::lock_guard lock(mutex_);
  const auto it = std::find(todo_.begin(), todo_.end(), index);
  const auto j = static_cast<std::size_t>(it - todo_.begin());
  if (it == todo_.end() || !handed_[j]) return;
  handed_[j] = 0;
  --handed_out_;
  scan_from_ = std::min(scan_from_, j);
}

void SweepRunner::fail(std::exception_ptr error) {
  std::lock_guard lock(mutex_);
  if (!fatal_error_) fatal_error_ = std::move(error);
  stop_ = true;
}

double SweepRunner::not_started_cost() const {
  std::lock_guard lock(mutex_);
  double cost = 0;
  for (std::size_t j = 0; j < todo_.size(); ++j)
    if (!handed_[j]) cost += points_[todo_[j]].cost;
  return cost;
}

void SweepRunner::record(std::size_t index, const RunResult* result, const std::string& error,
                         const std::function<void()>& under_lock, const InelasticCollapseError* collapse) {
  std::lock_guard lock(mutex_);
  if (under_lock) under_lock();
  ++done_;
  if (!result) ++failed_;
  if (collapse) ++collapsed_;
  done_cost_ += points_[index].cost;
  if (result) {
    finished_events_ += result->events;
    done_wall_ += result->wall_seconds;
    done_wall_cost_ += points_[index].cost;
  }
  if (sink_error_) return;  // the store already failed: nothing more is written
  try {
    sink_(points_[index], result, error, collapse);
    // Stored (a result or a collapse): a state saved of the point is spent. A failed point keeps
    // it (an error such as no memory may pass; an unphysical state comes back where it was).
    if ((result || collapse) && checkpoints_ && SweepCheckpoints::covers(points_[index])) checkpoints_->remove(points_[index]);
  } catch (...) {
    sink_error_ = std::current_exception();
    stop_ = true;
  }
}

SweepProgress SweepRunner::progress() const {
  std::lock_guard lock(mutex_);
  SweepProgress p;
  p.done = done_;
  p.failed = failed_;
  p.collapsed = collapsed_;
  p.total = todo_.size();
  p.elapsed = steady_clock_seconds() - start_;
  double covered = done_cost_;
  std::uint64_t events = finished_events_;
  for (int t = 0; t < threads_; ++t) {
    events += live_events_[t].load();
    covered += live_cost_[t].load();
  }
  p.eta = covered > 0 ? p.elapsed * std::max(total_cost_ - covered, 0.0) / covered : std::numeric_limits<double>::quiet_NaN();
  p.collisions_per_second = p.elapsed > 0 ? static_cast<double>(events) / p.elapsed : 0.0;
  return p;
}

void SweepRunner::worker(int slot) {
  while (const auto index = next()) {
    const SweepPoint& point = points_[*index];
    live_events_[slot] = 0;
    live_cost_[slot] = 0.0;
    ProgressCallback live = [this, slot, cost = point.cost](const RunProgress& rp) {
      if (cancelled()) throw RunCancelled{};
      live_events_[slot] = rp.events;
      if (rp.t_total > 0) live_cost_[slot] = cost * std::min(rp.t / rp.t_total, 1.0);
    };
    // The point's live counts are cleared under the lock that counts it done, so progress() never
    // sees a point both running and finished.
    auto clear_live = [this, slot] {
      live_events_[slot] = 0;
      live_cost_[slot] = 0.0;
    };
    PointOutcome outcome;
    try {
      outcome = run_sweep_point(point, checkpoints_, stops(), live, point_progress_every_);
    } catch (const std::exception&) {  // a checkpoint that cannot be written: the sweep stops
      clear_live();
      put_back(*index);
      fail(std::current_exception());
      return;
    }
    switch (outcome.end) {
      case PointEnd::Finished:
        record(*index, &*outcome.result, "", clear_live);
        break;
      case PointEnd::Collapsed:
        record(*index, nullptr, outcome.error, clear_live, &*outcome.collapse);
        break;
      case PointEnd::Failed:
        record(*index, nullptr, outcome.error, clear_live);
        break;
      case PointEnd::Saved:  // cancelled or out of time: taken up again by the next invocation
        clear_live();
        record_saved(*index);
        break;
      case PointEnd::Abandoned:  // watch(): not recorded, left for a repeat
        clear_live();
        put_back(*index);
        return;
    }
  }
}

void SweepRunner::run(int threads, const SweepProgressCallback& progress_cb, double progress_every,
                      const std::function<void()>& also_run_on_this_thread) {
  threads_ = threads;
  live_events_ = std::make_unique<std::atomic<std::uint64_t>[]>(static_cast<std::size_t>(threads));
  live_cost_ = std::make_unique<std::atomic<double>[]>(static_cast<std::size_t>(threads));
  for (int t = 0; t < threads; ++t) live_cost_[t] = 0.0;
  start_ = steady_clock_seconds();

  std::mutex wait_mutex;
  std::condition_variable wake;
  bool finished = false;
  std::thread reporter;
  if (progress_cb) {
    reporter = std::thread([&] {
      std::unique_lock lock(wait_mutex);
      while (!wake.wait_for(lock, std::chrono::duration<double>(progress_every), [&] { return finished; })) {
        lock.unlock();
        progress_cb(progress());
        lock.lock();
      }
    });
  }
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) pool.emplace_back([this, t] { worker(t); });
  if (also_run_on_this_thread) also_run_on_this_thread();
  for (auto& t : pool) t.join();
  if (reporter.joinable()) {
    {
      std::lock_guard lock(wait_mutex);
      finished = true;
    }
    wake.notify_all();
    reporter.join();
  }
  if (progress_cb) {
    SweepProgress p = progress();
    p.final = true;
    progress_cb(p);
  }
  if (sink_error_) std::rethrow_exception(sink_error_);
  if (fatal_error_) std::rethrow_exception(fatal_error_);
}

}  // namespace granchain
