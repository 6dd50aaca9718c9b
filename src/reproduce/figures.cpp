#include "reproduce/figures.hpp"

#include "config/value_list.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <limits>
#include <filesystem>
#include <set>
#include <stdexcept>

#include "store/output_file.hpp"
#include "reproduce/plot_script.hpp"
#include "sweep/sweep_progress.hpp"
#include "store/results_store.hpp"
#include "sweep/sweep_runner.hpp"
#include "simulation/collapse_run.hpp"

namespace granchain {

std::string preset_k(const ReproduceFlags& o) { return o.paper() ? "1e5:1e10:x10" : o.smoke() ? "1e4:1e6:x10" : "1e4:1e8:x10"; }
double preset_k_min(const ReproduceFlags& o) {
  if (o.k_min > 0) return o.k_min;
  return o.paper() ? 1e6 : o.smoke() ? 1e4 : 1e5;
}
std::string preset_k_max(const ReproduceFlags& o) { return o.paper() ? "1e10" : o.smoke() ? "1e6" : "1e8"; }
std::string preset_T(const ReproduceFlags& o, int N) {
  if (o.paper()) return N < 50 ? "1e4" : "1e3";
  if (o.smoke()) return N < 50 ? "20" : "5";
  return N < 50 ? "1000" : "100";
}

std::string settling_transient(int N) { return N >= 1000 ? "500" : ""; }

std::vector<SweepPoint> grid_points(const std::vector<GridBlock>& blocks) {
  std::vector<SweepPoint> all;
  std::set<std::string> seen;
  for (const GridBlock& b : blocks) {
    SweepDefinition def;
    def.raw["N"] = {b.N, ""};
    def.raw["e"] = {b.e, ""};
    if (!b.k.empty()) def.raw["k"] = {b.k, ""};
    if (!b.engine.empty()) def.raw["engine"] = {b.engine, ""};
    if (!b.start_k.empty()) def.raw["start-k"] = {b.start_k, ""};
    def.raw["T"] = {b.T, ""};
    if (!b.transient.empty()) def.raw["transient"] = {b.transient, ""};
    def.raw["T0"] = {b.T0, ""};
    if (b.drive != "thermal") {
      def.raw["drive"] = {b.drive, ""};
      def.raw["A"] = {b.A, ""};
      def.raw["omega"] = {b.omega, ""};
    }
    def.replicas = b.replicas;
    for (SweepPoint& p : build_sweep_points(def))
      if (seen.insert(p.key).second) all.push_back(std::move(p));
  }
  std::stable_sort(all.begin(), all.end(), [](const SweepPoint& a, const SweepPoint& b) {
    return a.cost != b.cost ? a.cost > b.cost : a.key < b.key;
  });
  return all;
}

CollapseSpec free_space_spec(int N, double e, double k, int launches, const ReproduceFlags& o) {
  CollapseSpec spec;
  spec.params.N = N;
  spec.params.e = e;
  spec.params.k = k;
  spec.params.g = 0.0;
  spec.realizations = launches;
  spec.threads = o.threads;
  return spec;
}

std::vector<CollapseSpec> count_specs(const std::vector<CountSeries>& series, const ReproduceFlags& o) {
  std::vector<CollapseSpec> specs;
  for (const CountSeries& s : series)
    for (double k : parse_value_list(s.k, "--k")) specs.push_back(free_space_spec(s.N, s.e, k, s.launches, o));
  return specs;
}

namespace {

// A word as a POSIX shell reads it back: as it is when it holds only safe characters, else in single quotes.
std::string shell_word(const std::string& word) {
  const bool plain = !word.empty() && word.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789"
                                                             "_-+=.,/:@%") == std::string::npos;
  if (plain) return word;
  std::string quoted = "'";
  for (char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

}  // namespace

std::string reproduce_command_line(const ReproduceFlags& o) {
  std::string line = fmt::format("granchain reproduce --figure {} --preset {}", shell_word(o.figure), shell_word(o.preset));
  if (o.db_given) line += " --db " + shell_word(o.db);
  if (o.stored_only) line += " --stored-only";
  if (o.k_min > 0) line += " --k-min " + power_of_ten_text(o.k_min);
  if (o.out_given) line += " --out " + shell_word(o.out);
  return line;
}

double ReproduceFlags::time_left() const {
  if (!(time_limit > 0)) return std::numeric_limits<double>::infinity();
  return time_limit - std::chrono::duration<double>(std::chrono::steady_clock::now() - started_at).count();
}

namespace {

// Sets `passed` once the given seconds have gone by (never for an infinite time), unless destroyed
// first.
class Deadline {
 public:
  explicit Deadline(double seconds) {
    if (!std::isfinite(seconds)) return;
    watch_ = std::thread([this, seconds] {
      std::unique_lock lock(mu_);
      if (!wake_.wait_for(lock, std::chrono::duration<double>(std::max(0.0, seconds)), [this] { return done_; })) passed = true;
    });
  }
  ~Deadline() {
    {
      std::lock_guard lock(mu_);
      done_ = true;
    }
    wake_.notify_all();
    if (watch_.joinable()) watch_.join();
  }
  Deadline(const Deadline&) = delete;
  Deadline& operator=(const Deadline&) = delete;
  CancelFlag passed{false};

 private:
  std::mutex mu_;
  std::condition_variable wake_;
  bool done_ = false;
  std::thread watch_;
};

}  // namespace

CollapseResult stored_or_run_collapse(const CollapseSpec& spec, const ReproduceFlags& o, const std::string& label) {
  if (o.stored_only) {
    ResultsStore reader(o.db, ResultsStore::Access::ReadOnly);
    if (std::optional<CollapseResult> stored = reader.find_collapse(spec)) return *stored;
    throw NothingStored(fmt::format("the free-space count N = {}, e = {:g}, k = {:g} ({} launches) is not in {} (--stored-only runs nothing)",
                                    spec.params.N, spec.params.e, spec.params.k, spec.realizations, o.db));
  }
  ResultsStore store(o.db);
  if (std::optional<CollapseResult> stored = store.find_collapse(spec)) return *stored;
  // A free-space count has no cost estimate: it starts while any time is left.
  if (!(o.time_left() > 0))
    throw TimeLimitReached(fmt::format("the time limit is reached before the free-space count N = {}, e = {:g}, k = {:g}", spec.params.N,
                                       spec.params.e, spec.params.k));
  if (!o.quiet)
    fmt::print(stderr, "reproduce {}: N = {}, e = {:g}, k = {:g}, {} launches\n", label, spec.params.N, spec.params.e, spec.params.k,
               spec.realizations);
  // Carried over sittings: the launches counted before an interruption are kept in the store. The
  // count stops where the time limit falls (its launches under way are lost, those done are kept).
  const LaunchCheckpoint checkpoint = store.launch_checkpoint(spec);
  if (!o.quiet && !checkpoint.done.empty())
    fmt::print(stderr, "reproduce {}: {} of {} launches carried over from an earlier sitting\n", label, checkpoint.done.size(), spec.realizations);
  // Progress over the launches counted now (a line rewritten on a terminal, a plain line every 10 s
  // in a batch job's log), as `granchain collapse` prints it.
  LaunchProgress progress;
  const auto started = std::chrono::steady_clock::now();
  auto last = started;
  std::size_t done = 0;
  std::uint64_t collisions = 0;
  const std::size_t to_count = static_cast<std::size_t>(spec.realizations) - checkpoint.done.size();
  const bool tty = isatty(STDERR_FILENO) != 0;
  const SweepProgressPrinter printer(tty, "reproduce " + label, "launches");
  if (!o.quiet)
    progress = [&](int, std::uint64_t c) {
      ++done;
      collisions += c;
      const auto now = std::chrono::steady_clock::now();
      if (done < to_count && std::chrono::duration<double>(now - last).count() < (tty ? 0.5 : 10.0)) return;
      last = now;
      SweepProgress p;
      p.done = done;
      p.total = to_count;
      p.elapsed = std::chrono::duration<double>(now - started).count();
      p.eta = p.elapsed / static_cast<double>(done) * static_cast<double>(to_count - done);
      p.collisions_per_second = p.elapsed > 0 ? static_cast<double>(collisions) / p.elapsed : 0.0;
      p.final = done == to_count;
      printer(p);
    };
  Deadline deadline(o.time_left());
  const CollapseResult r = run_collapse(spec, {}, progress, {}, &deadline.passed, &checkpoint);
  if (r.interrupted)
    throw TimeLimitReached(fmt::format("the time limit fell inside the free-space count N = {}, e = {:g}, k = {:g}: {} of its {} launches "
                                       "are kept in {}, and the same command continues it",
                                       spec.params.N, spec.params.e, spec.params.k, store.kept_launches(spec).done.size(), spec.realizations, o.db));
  store.insert_collapse(r);
  return r;
}

std::vector<std::string> run_missing_points(const std::vector<SweepPoint>& points, const ReproduceFlags& o, const std::string& label,
                                            ReproductionLog& log) {
  std::vector<std::string> failures;
  // A point whose hard spheres collapsed is settled too: the collapse is its stored outcome (no run;
  // a figure that wants it reads ResultsStore::collapsed_points).
  const auto settled = [&](ResultsStore& store) {
    std::unordered_set<std::string> keys = store.point_keys();
    for (const auto& [key, c] : store.collapsed_points()) keys.insert(key);
    return keys;
  };
  if (o.stored_only) {
    ResultsStore reader(o.db, ResultsStore::Access::ReadOnly);
    const std::vector<std::size_t> missing = points_to_run(points, settled(reader));
    if (missing.size() == points.size())
      throw NothingStored(fmt::format("none of its {} runs is in {} yet (--stored-only runs nothing)", points.size(), o.db));
    if (!o.quiet)
      fmt::print(stderr, "reproduce {} ({}): {} runs, {} in {}; --stored-only: drawn from those, {} missing\n", label, o.preset,
                 points.size(), points.size() - missing.size(), o.db, missing.size());
    if (!missing.empty()) log.partial.push_back(fmt::format("{}: {} of {} runs", label, points.size() - missing.size(), points.size()));
    return failures;
  }
  ResultsStore store(o.db);
  std::vector<std::size_t> todo;
  for (std::size_t i : points_to_run(points, settled(store))) {
    if (log.failed_keys.count(points[i].key)) failures.push_back(points[i].key + ": turned unphysical earlier in this command");
    else todo.push_back(i);
  }
  if (!o.quiet)
    fmt::print(stderr, "reproduce {} ({}): {} runs, {} already in {}, {} to run on {} threads\n", label, o.preset, points.size(),
               points.size() - todo.size(), o.db, todo.size(), o.threads);
  if (todo.empty()) return failures;
  SweepRunner runner(points, todo, [&](const SweepPoint& p, const RunResult* r, const std::string& error, const InelasticCollapseError* c) {
    if (r) {
      store.insert_sweep_point(*r, p.key, 1, p.replica);
    } else if (c) {
      store.insert_collapsed_point(p.key, ResultsStore::collapsed_point(*c));
    } else {
      failures.push_back(p.key + ": " + error);
      log.failed_keys.insert(p.key);
    }
  });
  const bool tty = isatty(STDERR_FILENO) != 0;
  SweepProgressCallback cb;
  if (!o.quiet) cb = SweepProgressPrinter(tty, "reproduce " + label);
  if (o.time_limit > 0) runner.set_time_limit(std::max(o.time_left(), 0.0));
  runner.run(o.threads, cb, tty ? 0.5 : 30.0);
  if (const std::size_t left = runner.not_started(); left > 0)
    throw TimeLimitReached(fmt::format("{} of its points not started (estimated {} of one core)", left,
                                       format_duration(runner.not_started_cost())));
  return failures;
}

StoreAnalysis analyze_points(const std::string& db, const std::vector<SweepPoint>& points, double k_min, const EnginePool& pool) {
  ExportSelection sel;
  for (const SweepPoint& p : points) sel.point_keys.push_back(p.key);
  return analyze_store(db, sel, k_min, pool);
}

std::string output_path(const ReproduceFlags& o, const std::string& name) {
  return (std::filesystem::path(o.out) / name).string();
}

void write_output(const std::string& path, const std::string& text) { write_file_atomically(path, text, "--out"); }

void draw(const std::string& script, const std::vector<std::string>& args) {
  const std::string problem = run_plot_script(script, args);
  if (!problem.empty()) throw OutputError(problem);
}

std::string draw_figure(const ReproduceFlags& o, const std::string& name, const nlohmann::json& data, const std::string& script) {
  const std::string prefix = output_path(o, name);
  write_output(prefix + ".json", data.dump(1) + "\n");
  draw(script, {prefix + ".json", prefix});
  return prefix + ".png (and .pdf)";
}

std::string sweep_command(const GridBlock& b) {
  std::string line = fmt::format("granchain sweep --N {} --e {}", b.N, b.e);
  if (!b.engine.empty()) line += " --engine " + b.engine;
  if (!b.k.empty()) line += " --k " + b.k;
  if (!b.start_k.empty()) line += " --start-k " + b.start_k;
  line += fmt::format(" --T {}", b.T);
  if (!b.transient.empty()) line += " --transient " + b.transient;
  line += fmt::format(" --T0 {}", b.T0);
  if (b.drive != "thermal") line += fmt::format(" --drive {} --A {} --omega {}", b.drive, b.A, b.omega);
  if (b.replicas > 1) line += fmt::format(" --replicas {}", b.replicas);
  return line;
}

const std::vector<double>& critical_region_c() {
  static const std::vector<double> c = {5.0, 4.0, 3.5, 3.2, 3.0, 2.8, 2.6, 2.4, 2.2, 2.0, 1.6, 1.2};
  return c;
}
const std::vector<double>& ec2_extension_c() {
  static const std::vector<double> c = {10.0, 8.0, 7.0, 6.0};
  return c;
}
std::string critical_region_text() {
  std::string out;
  for (double c : critical_region_c()) out += fmt::format("{}{:g}", out.empty() ? "c = " : ", ", c);
  return out;
}

std::vector<double> condensed_es(const StoreAnalysis& a, const analysis::FamilyAnalysis& f) {
  std::vector<double> out;
  const auto fc = a.condensation.find({f.engine, f.drive, f.N, f.kT0});
  if (fc == a.condensation.end()) return out;
  for (const auto& [e, c] : fc->second)
    if (c.check.state == analysis::CondensedState::Partial && f.N * (1.0 - e) <= ec2_extension_c().front() + 1e-9) out.push_back(e);
  return out;
}

std::string e_list_at_n_one_minus_e(int N, const std::vector<double>& c) {
  std::string out;
  for (double ci : c) out += fmt::format("{}{:.12g}", out.empty() ? "" : ",", 1.0 - ci / N);
  return out;
}

}  // namespace granchain
