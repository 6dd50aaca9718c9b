#include "simulation/collapse_run.hpp"

#include <fmt/format.h>

#include <chrono>
#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <tuple>
#include <utility>

#include "analysis/blocking.hpp"
#include "model/floor.hpp"
#include "model/random.hpp"
#include "simulation/cancellation.hpp"

namespace granchain {

const char* setup_name(CollapseSetup s) { return s == CollapseSetup::FreeSpace ? "free_space" : "wall"; }
const char* rule_name(StopRule r) { return r == StopRule::Ends ? "ends" : "strict"; }

namespace {

// Counts collisions and asks the engine to stop whenever the last open contact closes, so that
// the driver can test the stop rule in free flight.
class CollapseObserver final : public EventSink {
 public:
  CollapseObserver(int N, int realization, bool keep_records, double wall_restitution, const CancelFlag* cancel)
      : begin_t_(N, 0.0), begin_speed_(N, 0.0), realization_(realization), keep_(keep_records),
        wall_r_(wall_restitution), cancel_(cancel) {}

  void on_event(const Event& ev) override {
    if (cancel_requested(cancel_)) {
      cancelled_ = true;
      request_stop();
    }
    switch (ev.kind) {
      case EventKind::ContactBegin:
        ++open_;
        begin_t_[ev.i] = ev.t;
        begin_speed_[ev.i] = ev.speed;
        break;
      case EventKind::ContactEnd:
        --open_;
        ++outcome.particle_collisions;
        if (keep_) {
          records.push_back({realization_, outcome.n_tot(), begin_t_[ev.i], ev.t, ev.i + 1, begin_speed_[ev.i], ev.speed});
        }
        if (open_ == 0) request_stop();
        break;
      case EventKind::FloorHit:
        ++outcome.wall_hits;
        if (keep_) records.push_back({realization_, outcome.n_tot(), ev.t, ev.t, 0, ev.speed / wall_r_, ev.speed});
        if (open_ == 0) request_stop();
        break;
      case EventKind::FloorContact:  // no plate in free space or on the wall
        break;
    }
  }
  int open_contacts() const { return open_; }
  bool cancelled() const { return cancelled_; }

  RealizationOutcome outcome;
  std::vector<CollisionRecord> records;

 private:
  int open_ = 0;
  std::vector<double> begin_t_, begin_speed_;
  int realization_;
  bool keep_;
  double wall_r_;
  const CancelFlag* cancel_;
  bool cancelled_ = false;
};

bool stop_rule_holds(const CollapseSpec& spec, const ChainState& s) {
  const int N = static_cast<int>(s.v.size());
  if (spec.rule == StopRule::Ends) return s.v[N - 1] - s.v[0] > 0;
  if (spec.setup == CollapseSetup::Wall && s.v[0] < 0) return false;
  for (int i = 0; i + 1 < N; ++i)
    if (s.v[i + 1] < s.v[i]) return false;
  return true;
}

}  // namespace

bool moves_as_one_body(const CollapseSpec& spec, const ChainState& s) {
  if (spec.setup == CollapseSetup::Wall && s.v[0] < 0) return false;
  double lo = s.v[0], hi = s.v[0], fastest = 0;
  for (double v : s.v) lo = std::min(lo, v), hi = std::max(hi, v), fastest = std::max(fastest, std::abs(v));
  return hi - lo <= 1e-13 * fastest;
}

namespace {

bool any_overlap(const ChainState& s, double d) {
  for (std::size_t i = 0; i + 1 < s.z.size(); ++i)
    if (s.z[i + 1] - s.z[i] < d) return true;
  return false;
}


struct RealizationRun {
  RealizationOutcome outcome;
  std::vector<CollisionRecord> records;
  std::vector<ClosedState> states;
};

RealizationRun run_realization(const CollapseSpec& spec, int r, bool keep_records, bool keep_states, const CancelFlag* cancel) {
  ChainParameters p = spec.params;
  p.g = 0.0;
  const ChainState initial = collapse_initial_state(spec, r);
  Wall wall(p.e);  // Bernu and Mazighi's wall: the restitution of the spheres (its mirror image)
  FloorDrive* floor = spec.setup == CollapseSetup::Wall ? &wall : nullptr;
  auto engine = make_engine(spec.engine, p, initial, floor);
  CollapseObserver obs(p.N, r, keep_records, p.e, cancel);
  bool done = !any_overlap(initial, p.d) && stop_rule_holds(spec, initial);
  const bool hard = engine_info(spec.engine.kind).hard_spheres;
  std::vector<ClosedState> states;
  try {
    while (!done) {
      obs.clear_stop();
      engine->advance_to(spec.t_max, obs);
      if (obs.cancelled()) throw RunCancelled{};
      // Nothing happened up to t_max in free flight: any collision still to come is later than
      // t_max, between pairs approaching by less than ~(gap / t_max); the launch has ended.
      if (!obs.stop_requested() && obs.open_contacts() == 0) break;
      if (!obs.stop_requested()) {
        throw UnphysicalStateError(spec.t_max, 1, p.N,
                                   fmt::format("realisation {}: the stop rule did not hold by t = {:g} "
                                               "({} collisions)", r, spec.t_max, obs.outcome.n_tot()));
      }
      if (obs.open_contacts() != 0) continue;
      if (keep_states && !obs.records.empty()) states.push_back({obs.records.size() - 1, engine->state()});
      done = stop_rule_holds(spec, engine->state());
      // Soft spheres only: hard spheres that become one body are an inelastic collapse, which
      // their engine's collapse watch reports.
      if (!done && !hard && moves_as_one_body(spec, engine->state())) done = obs.outcome.one_body = true;
    }
    obs.outcome.t_stop = engine->time();
    obs.outcome.grazing_contacts = engine->below_resolution().grazing_contacts;
    obs.outcome.held_contacts = engine->below_resolution().held_contacts;
  } catch (const InelasticCollapseError& c) {
    obs.outcome.collapsed = true;
    obs.outcome.t_stop = c.time();
  }
  return {obs.outcome, std::move(obs.records), std::move(states)};
}

}  // namespace

ChainState collapse_initial_state(const CollapseSpec& spec, int r) {
  const std::uint64_t seed = derive_seed(spec.seed, static_cast<std::uint64_t>(r));
  return spec.setup == CollapseSetup::FreeSpace ? free_space_launch_state(spec.params, spec.launch, seed)
                                                : wall_throw_state(spec.params, spec.launch, seed);
}

CollapseResult run_collapse(const CollapseSpec& spec, const CollisionLog& log, const LaunchProgress& progress,
                            const ClosedStateLog& states_log, const CancelFlag* cancel, const LaunchCheckpoint* checkpoint) {
  const auto wall0 = std::chrono::steady_clock::now();
  const int R = spec.realizations;
  if (log && checkpoint && !checkpoint->done.empty())
    throw std::invalid_argument("run_collapse: a collision log needs every launch run now, not carried over from a checkpoint");
  CollapseResult res;
  res.spec = spec;
  res.law = contact_law(spec.params);
  res.outcomes.resize(R);

  // Workers take realisations in order; the calling thread hands their records to `log` in
  // realisation order, and each new launch to the checkpoint as it finishes. With a log, workers
  // stay within a window of the next record to hand over, so memory stays bounded whatever the
  // lengths of the realisations.
  const int threads = std::max(1, std::min(spec.threads, R));
  const int window = 4 * threads;
  std::vector<std::vector<CollisionRecord>> pending(R);
  std::vector<std::vector<ClosedState>> pending_states(R);
  const bool keep_states = log && states_log;
  std::vector<char> finished(R, 0), carried(R, 0);
  if (checkpoint) {
    for (const auto& [r, outcome] : checkpoint->done) {
      if (r < 0 || r >= R) continue;
      res.outcomes[r] = outcome;
      finished[r] = carried[r] = 1;
    }
  }
  std::vector<int> just_finished;  // new launches not yet handed to the checkpoint
  std::mutex mu;
  std::condition_variable cv;
  int next = 0, flushed = 0;
  std::exception_ptr failure;

  auto worker = [&] {
    for (;;) {
      int r;
      {
        std::unique_lock lock(mu);
        while (next < R && carried[next]) ++next;
        cv.wait(lock, [&] { return failure || cancel_requested(cancel) || next >= R || !log || next < flushed + window; });
        while (next < R && carried[next]) ++next;
        if (failure || cancel_requested(cancel) || next >= R) return;
        r = next++;
      }
      try {
        const auto t0 = std::chrono::steady_clock::now();
        RealizationRun run = run_realization(spec, r, static_cast<bool>(log), keep_states, cancel);
        run.outcome.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        std::lock_guard lock(mu);
        res.outcomes[r] = run.outcome;
        pending[r] = std::move(run.records);
        pending_states[r] = std::move(run.states);
        finished[r] = 1;
        just_finished.push_back(r);
      } catch (const RunCancelled&) {
        cv.notify_all();
        return;
      } catch (...) {
        std::lock_guard lock(mu);
        if (!failure) failure = std::current_exception();
      }
      cv.notify_all();
    }
  };
  // Hands the launches finished since the last call to the checkpoint (unlocking while it writes);
  // one that cannot be kept ends the count like a failed launch.
  const auto hand_over = [&](std::unique_lock<std::mutex>& lock) {
    std::vector<int> now = std::exchange(just_finished, {});
    if (!checkpoint || !checkpoint->finished || now.empty()) return;
    std::vector<RealizationOutcome> outcomes;
    for (int r : now) outcomes.push_back(res.outcomes[r]);
    lock.unlock();
    std::exception_ptr kept;
    try {
      for (std::size_t i = 0; i < now.size(); ++i) checkpoint->finished(now[i], outcomes[i]);
    } catch (...) {
      kept = std::current_exception();
    }
    lock.lock();
    if (kept && !failure) failure = kept;
  };
  std::vector<std::thread> pool;
  for (int i = 0; i < threads; ++i) pool.emplace_back(worker);
  {
    std::unique_lock lock(mu);
    while (flushed < R) {
      // A cancelled count keeps the launches 0 .. flushed-1, whose records are handed over already.
      const auto ready = [&] { return failure || finished[flushed] || !just_finished.empty() || cancel_requested(cancel); };
      if (cancel) {
        while (!cv.wait_for(lock, std::chrono::milliseconds(50), ready)) {}
      } else {
        cv.wait(lock, ready);
      }
      hand_over(lock);
      if (failure) break;
      if (!finished[flushed]) {
        if (!cancel_requested(cancel)) continue;  // a later launch finished first
        res.interrupted = true;
        break;
      }
      std::vector<CollisionRecord> records = std::move(pending[flushed]);
      std::vector<ClosedState> states = std::move(pending_states[flushed]);
      const std::uint64_t collisions = res.outcomes[flushed].particle_collisions;
      const bool report = !carried[flushed];
      ++flushed;
      cv.notify_all();
      if (report && (log || progress)) {
        lock.unlock();
        if (log) log(records);
        if (keep_states) states_log(states);
        if (progress) progress(flushed, collisions);
        lock.lock();
      }
    }
  }
  cv.notify_all();
  for (auto& t : pool) t.join();
  {
    std::unique_lock lock(mu);
    hand_over(lock);  // launches that finished after the last one handed over, or beside a failure
    if (checkpoint && checkpoint->flush) {
      try {
        checkpoint->flush();
      } catch (...) {
        if (!failure) failure = std::current_exception();
      }
    }
  }
  if (failure) std::rethrow_exception(failure);
  if (res.interrupted) {
    res.outcomes.resize(static_cast<std::size_t>(flushed));
    res.spec.realizations = flushed;
  }

  // Statistics over the realisations that did not collapse, in realisation order.
  std::vector<double> counts;
  res.n_tot_min = std::numeric_limits<std::uint64_t>::max();
  for (const RealizationOutcome& o : res.outcomes) {
    res.collisions += o.n_tot();
    res.grazing_contacts += o.grazing_contacts;
    res.held_contacts += o.held_contacts;
    res.one_body += o.one_body;
    if (o.collapsed) {
      ++res.collapsed;
      continue;
    }
    counts.push_back(static_cast<double>(o.n_tot()));
    res.n_tot_min = std::min(res.n_tot_min, o.n_tot());
    res.n_tot_max = std::max(res.n_tot_max, o.n_tot());
  }
  if (counts.empty()) res.n_tot_min = 0;
  std::tie(res.n_tot_mean, res.n_tot_error) = mean_and_error(counts);
  res.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count() +
                     (checkpoint ? checkpoint->earlier_seconds : 0.0);
  return res;
}

KSlope k_slope(const CollapseResult& a, const CollapseResult& b) {
  KSlope s;
  s.e = a.spec.params.e;
  s.k1 = a.spec.params.k;
  s.k2 = b.spec.params.k;
  const double dlog = std::log10(s.k2 / s.k1);
  std::vector<double> diff;
  for (std::size_t r = 0; r < a.outcomes.size() && r < b.outcomes.size(); ++r) {
    if (a.outcomes[r].collapsed || b.outcomes[r].collapsed) continue;
    diff.push_back((static_cast<double>(b.outcomes[r].n_tot()) - static_cast<double>(a.outcomes[r].n_tot())) / dlog);
  }
  s.launches = static_cast<int>(diff.size());
  std::tie(s.per_log10_k, s.error) = mean_and_error(diff);
  const double ln_k = std::log(s.k2 / s.k1);
  s.alpha = std::log(b.n_tot_mean / a.n_tot_mean) / ln_k;
  s.alpha_error = std::hypot(a.n_tot_error / a.n_tot_mean, b.n_tot_error / b.n_tot_mean) / ln_k;
  return s;
}

}  // namespace granchain
