// A collapse count carried over sittings (ResultsStore::launch_checkpoint): launch r depends on the
// count's definition and r alone, so a count stopped anywhere and continued from the launches kept
// in the store must give the numbers of one uninterrupted count, bit for bit, without running a
// kept launch again.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <atomic>
#include <chrono>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <thread>

#include "cli_fixture.hpp"
#include "config/run_key.hpp"
#include "simulation/collapse_run.hpp"
#include "store/results_store.hpp"
#include "store/store_merge.hpp"
#include "temp_dir.hpp"

using namespace granchain;

namespace {

CollapseSpec count_spec(std::uint64_t seed = 1) {
  CollapseSpec s;
  s.params.N = 50;
  s.params.e = 0.3;
  s.params.k = 1e9;
  s.params.g = 0.0;
  s.realizations = 16;
  s.seed = seed;
  s.threads = 2;
  return s;
}

// How many launches of a count the store keeps.
int kept_count(ResultsStore& store, const CollapseSpec& spec) { return static_cast<int>(store.kept_launches(spec).done.size()); }

// Keeps the given launches of a count in a store, as a sitting that counted them would.
void keep(ResultsStore& store, const CollapseSpec& spec, std::initializer_list<int> launches, const RealizationOutcome& o) {
  LaunchCheckpoint c = store.launch_checkpoint(spec);
  for (int r : launches) c.finished(r, o);
  c.flush();
}

void expect_same_count(const CollapseResult& a, const CollapseResult& b) {
  ASSERT_EQ(a.outcomes.size(), b.outcomes.size());
  for (std::size_t r = 0; r < a.outcomes.size(); ++r) {
    EXPECT_EQ(a.outcomes[r].particle_collisions, b.outcomes[r].particle_collisions) << "launch " << r;
    EXPECT_EQ(a.outcomes[r].wall_hits, b.outcomes[r].wall_hits) << "launch " << r;
    EXPECT_EQ(a.outcomes[r].t_stop, b.outcomes[r].t_stop) << "launch " << r;
    EXPECT_EQ(a.outcomes[r].grazing_contacts, b.outcomes[r].grazing_contacts) << "launch " << r;
    EXPECT_EQ(a.outcomes[r].one_body, b.outcomes[r].one_body) << "launch " << r;
  }
  EXPECT_EQ(a.n_tot_mean, b.n_tot_mean);
  EXPECT_EQ(a.n_tot_error, b.n_tot_error);
  EXPECT_EQ(a.n_tot_min, b.n_tot_min);
  EXPECT_EQ(a.n_tot_max, b.n_tot_max);
  EXPECT_EQ(a.collisions, b.collisions);
}

}  // namespace

// Sitting 1 is cancelled once four launches are kept; sitting 2 runs only the launches missing and
// gives the uninterrupted count; storing it whole clears the kept launches.
TEST(CarriedCounts, ACountStoppedAnywhereContinuesToTheSameNumbersBitForBit) {
  const CollapseSpec spec = count_spec();
  const CollapseResult whole = run_collapse(spec);

  TempDir dir;
  ResultsStore store(dir.file("c.db"));
  CancelFlag cancel{false};
  LaunchCheckpoint first = store.launch_checkpoint(spec);
  ASSERT_TRUE(first.done.empty());
  int kept_now = 0;
  const auto keep_in_store = first.finished;
  first.finished = [&](int r, const RealizationOutcome& o) {
    keep_in_store(r, o);
    if (++kept_now == 4) cancel = true;
  };
  const CollapseResult part = run_collapse(spec, {}, {}, {}, &cancel, &first);
  ASSERT_TRUE(part.interrupted);
  const int kept = kept_count(store, spec);
  ASSERT_GE(kept, 4);
  ASSERT_LT(kept, spec.realizations) << "the first sitting finished the count: the test shows nothing";

  const LaunchCheckpoint second = store.launch_checkpoint(spec);
  EXPECT_EQ(static_cast<int>(second.done.size()), kept);
  EXPECT_GT(second.earlier_seconds, 0.0);
  std::atomic<int> run_now{0}, reported{0};
  LaunchCheckpoint counting = second;
  counting.finished = [&](int r, const RealizationOutcome& o) {
    EXPECT_EQ(second.done.count(r), 0u) << "launch " << r << " was kept and ran again";
    ++run_now;
    second.finished(r, o);
  };
  const CollapseResult resumed = run_collapse(spec, {}, [&](int, std::uint64_t) { ++reported; }, {}, nullptr, &counting);
  EXPECT_FALSE(resumed.interrupted);
  EXPECT_EQ(run_now.load(), spec.realizations - kept);
  EXPECT_EQ(reported.load(), spec.realizations - kept) << "progress reports only the launches run now";
  EXPECT_GE(resumed.wall_seconds, second.earlier_seconds);
  expect_same_count(resumed, whole);

  store.insert_collapse(resumed);
  EXPECT_EQ(kept_count(store, spec), 0);
  const std::optional<CollapseResult> stored = store.find_collapse(spec);
  ASSERT_TRUE(stored.has_value());
  EXPECT_EQ(stored->n_tot_mean, whole.n_tot_mean);
}

// Kept launches belong to one definition: another seed (other launches) or another number of
// launches (another count) starts from none; a collision log, which needs every launch's records,
// refuses to skip launches.
TEST(CarriedCounts, KeptLaunchesServeOnlyTheirOwnCount) {
  TempDir dir;
  ResultsStore store(dir.file("c.db"));
  const CollapseSpec spec = count_spec();
  LaunchCheckpoint c = store.launch_checkpoint(spec);
  RealizationOutcome o;
  o.particle_collisions = 7;
  c.finished(3, o);
  c.flush();
  EXPECT_EQ(kept_count(store, spec), 1);
  EXPECT_EQ(kept_count(store, count_spec(2)), 0);
  CollapseSpec more = spec;
  more.realizations = 32;
  EXPECT_EQ(kept_count(store, more), 0);
  EXPECT_NE(collapse_key(spec), collapse_key(more));
  EXPECT_EQ(store.launch_checkpoint(spec).done.at(3).particle_collisions, 7u);
  const LaunchCheckpoint again = store.launch_checkpoint(spec);
  EXPECT_THROW(run_collapse(spec, [](const std::vector<CollisionRecord>&) {}, {}, {}, nullptr, &again), std::invalid_argument);
}

namespace {
class CarriedCountCli : public Cli {};
}  // namespace

// `granchain collapse` ended by SIGTERM (a batch job's walltime) says where its launches are kept
// (written once a second: those of the last second are lost);
// the same command then counts only the missing ones and prints the numbers of a count run in one
// go; a third run reads the stored count back.
TEST_F(CarriedCountCli, SigtermKeepsTheLaunchesAndTheSameCommandFinishesTheCount) {
  const std::string count = "collapse --N 50 --e 0.3 --k 1e11 --realizations 24 --threads 2";
  ASSERT_EQ(run(count + " --no-db -q --json whole.json").exit_code, 0);
  const pid_t pid = start(count + " --db c.db -q");
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (query(dir_ / "c.db", "SELECT count(*) FROM collapse_launches") < 3 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_EQ(kill(pid, SIGTERM), 0);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << "the count ended before the signal: the test shows nothing";
  EXPECT_NE(slurp(dir_ / "bg.txt").find("the launches that finished are kept in c.db"), std::string::npos) << slurp(dir_ / "bg.txt");
  const std::int64_t kept = query(dir_ / "c.db", "SELECT count(*) FROM collapse_launches");
  EXPECT_GE(kept, 3);
  EXPECT_EQ(query(dir_ / "c.db", "SELECT count(*) FROM collapse_runs"), 0);

  // Launches counted by another build: the resumed count names its version beside its own.
  {
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open((dir_ / "c.db").c_str(), &db), SQLITE_OK);
    // (and 1000 s each, so that the count's launch_seconds shows whether the carried times enter it)
    ASSERT_EQ(sqlite3_exec(db, "UPDATE collapse_launches SET code_version = 'an-earlier-build', seconds = 1000", nullptr, nullptr, nullptr),
              SQLITE_OK);
    sqlite3_close(db);
  }
  const CliResult resumed = run(count + " --db c.db --json resumed.json");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_NE(resumed.out.find("launches carried over from an earlier sitting"), std::string::npos) << resumed.out;
  EXPECT_NE(resumed.out.find("counted by code version an-earlier-build, this is"), std::string::npos) << resumed.out;
  const auto observables = [&](const std::string& file) { return nlohmann::json::parse(slurp(dir_ / file))["points"][0]["observables"]; };
  EXPECT_EQ(observables("resumed.json"), observables("whole.json"));
  EXPECT_EQ(query(dir_ / "c.db", "SELECT count(*) FROM collapse_launches"), 0);
  EXPECT_EQ(query(dir_ / "c.db", "SELECT count(*) FROM collapse_realizations"), 24);

  const CliResult again = run(count + " --db c.db --json again.json");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.out.find("read back, not counted again"), std::string::npos) << again.out;
  EXPECT_EQ(observables("again.json"), observables("whole.json"));
  // The JSON read back is the one written when the count was stored (its derived D, its version).
  const auto point = [&](const std::string& file) { return nlohmann::json::parse(slurp(dir_ / file))["points"][0]; };
  EXPECT_EQ(point("again.json")["derived"], point("whole.json")["derived"]);
  EXPECT_TRUE(point("again.json").contains("read_back"));
  // The launches' own times, the carried ones (1000 s each, set above) included: the new launches add
  // about what the one-go count spent on its threads, at most all of it (wide: a loaded machine).
  const double resumed_seconds = point("resumed.json")["cost"]["launch_seconds"], whole_seconds = point("whole.json")["cost"]["launch_seconds"];
  EXPECT_GT(resumed_seconds, 1000.0 * static_cast<double>(kept));
  EXPECT_LT(resumed_seconds, 1000.0 * static_cast<double>(kept) + 5.0 * whole_seconds);
  EXPECT_FALSE(point("resumed.json").contains("read_back"));

  // The hard engine's collapse watch is not a stored parameter: a count to be stored keeps its default.
  const CliResult watch = run("collapse --engine hard --N 10 --e 0.3 --realizations 4 --collapse-collisions 20 --db c.db");
  EXPECT_EQ(watch.exit_code, 2);
  EXPECT_NE(watch.err.find("--collapse-collisions = 20"), std::string::npos) << watch.err;
  EXPECT_EQ(run("collapse --engine hard --N 10 --e 0.3 --realizations 4 --collapse-collisions 20 --no-db -q").exit_code, 0);
}

// merge carries kept launches into the target, so that the count continues there: launches the
// target lacks are added, those it has are kept once, those of a count it holds whole are not
// copied (and its own such leftovers are dropped), and one with other numbers is a conflict.
TEST(CarriedCounts, MergeCarriesKeptLaunchesIntoTheTarget) {
  TempDir dir;
  const CollapseSpec open = count_spec(), whole = count_spec(2);
  RealizationOutcome o;
  o.particle_collisions = 11;
  o.t_stop = 2.5;
  {
    ResultsStore source(dir.file("s.db"));
    keep(source, open, {0, 2}, o);
    keep(source, whole, {1}, o);
  }
  {
    ResultsStore target(dir.file("t.db"));
    keep(target, open, {2}, o);
    CollapseResult w;
    w.spec = whole;
    w.outcomes.resize(static_cast<std::size_t>(whole.realizations));
    target.insert_collapse(w);
    keep(target, whole, {0}, o);  // a leftover beside the whole count
    ASSERT_EQ(kept_count(target, whole), 1);
  }
  const MergeReport r = merge_stores(dir.file("t.db"), {dir.file("s.db")});
  EXPECT_EQ(r.launches_added, 1);          // launch 0 of the open count
  EXPECT_EQ(r.launches_already_there, 2);  // its launch 2, and the whole count's launch 1
  ResultsStore target(dir.file("t.db"));
  EXPECT_EQ(kept_count(target, open), 2);
  EXPECT_EQ(kept_count(target, whole), 0);
  EXPECT_EQ(target.launch_checkpoint(open).done.at(0).t_stop, 2.5);

  {
    ResultsStore other(dir.file("o.db"));
    RealizationOutcome changed = o;
    changed.particle_collisions = 12;
    keep(other, open, {0}, changed);
  }
  EXPECT_THROW(merge_stores(dir.file("t.db"), {dir.file("o.db")}), MergeConflict);
  EXPECT_EQ(kept_count(target, open), 2);
}

// reproduce --time-limit stops a free-space count where the limit falls (exit 75), keeps its
// finished launches, says how many, and the next sitting goes on from them. (A limit may also fall
// between two counts; the sittings repeat until one falls inside a count.)
TEST_F(CarriedCountCli, ATimeLimitInsideACountKeepsItsLaunches) {
  const std::string figure = "reproduce --figure limit-free --preset quick --out figs -q --time-limit 3";
  const std::string said = "the time limit fell inside the free-space count";
  bool inside = false;
  for (int sitting = 0; sitting < 8 && !inside; ++sitting) {
    const std::int64_t counts = query(dir_ / "reproduce.db", "SELECT count(*) FROM collapse_runs");
    const std::int64_t launches = query(dir_ / "reproduce.db", "SELECT count(*) FROM collapse_launches");
    const CliResult r = run(figure);
    ASSERT_EQ(r.exit_code, 75) << r.err;
    EXPECT_TRUE(query(dir_ / "reproduce.db", "SELECT count(*) FROM collapse_runs") > counts ||
                query(dir_ / "reproduce.db", "SELECT count(*) FROM collapse_launches") > launches)
        << "sitting " << sitting << " made no progress: " << r.err;
    const std::size_t at = r.err.find(said);
    if (at == std::string::npos) continue;
    inside = true;
    const long kept = std::stol(r.err.substr(r.err.find(": ", at) + 2));
    EXPECT_EQ(query(dir_ / "reproduce.db", "SELECT count(*) FROM collapse_launches"), kept) << r.err;
  }
  EXPECT_TRUE(inside) << "no limit fell inside a count: the test shows nothing";
}

// An empty file is a store awaiting its first writer: a count goes into it as into a new one.
TEST_F(CarriedCountCli, AnEmptyFileTakesTheCount) {
  write("empty.db", "");
  const CliResult r = run("collapse --N 3 --e 0.05 --k 1e6 --realizations 4 --db empty.db -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(query(dir_ / "empty.db", "SELECT count(*) FROM collapse_runs"), 1);
}
