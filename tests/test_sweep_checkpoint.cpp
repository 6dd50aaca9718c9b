// `granchain sweep --checkpoint-dir DIR`: points of a resumable engine keep their state in DIR, so
// a point may run longer than a batch job. Stopped by the end of --time-limit or by SIGTERM, and on
// MPI ranks, the points are saved; repeats of the command resume them, and the store ends with the
// numbers of the sweep that was never stopped, bit for bit; the spent states are removed.
#include <signal.h>

#include <chrono>
#include <thread>

#include "cli_fixture.hpp"
#include "sweep/sweep_checkpoints.hpp"
#include "sweep/sweep_runner.hpp"

using namespace granchain;

namespace {

class SweepCheckpointCli : public Cli {
 protected:
  std::map<std::string, std::string> stored(const std::string& db) {
    const CliResult r = run("export --db " + db + " --table runs");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return physics_by_key(r.out);
  }
  std::size_t saved_states(const std::string& folder) const {
    if (!fs::exists(dir_ / folder)) return 0;
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir_ / folder), fs::directory_iterator()));
  }
};

// Two points of about 4 s each on this machine (the cost model says 2.3 s): a time limit of 1 s,
// the shortest --time-limit takes, saves them 0.2 s before it, so they need about six sittings
// here and at least three on a machine up to 2.5 times faster.
const std::string kPoints = "sweep --engine reference --N 20 --e 0.5 --k 1e7 --T 200 --transient 20 --replicas 2 --seed 3 -q";

}  // namespace

TEST_F(SweepCheckpointCli, ATimeLimitSavesThePointsAndRepeatsFinishThemBitForBit) {
  ASSERT_EQ(run(kPoints + " --db whole.db").exit_code, 0);
  const auto whole = stored("whole.db");
  ASSERT_EQ(whole.size(), 2u);

  // Without checkpoints, a limit shorter than a point's estimate is refused, nothing written.
  const CliResult refused = run(kPoints + " --db cut.db --time-limit 1");
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("--time-limit = 1.0 s is shorter than the estimated run of 2 points"), std::string::npos) << refused.err;
  EXPECT_FALSE(fs::exists(dir_ / "cut.db"));

  // With them, each invocation runs until 0.2 s before the limit, saves and exits 75.
  const std::string cut = kPoints + " --db cut.db --time-limit 1 --checkpoint-dir states";
  const CliResult first = run(cut);
  ASSERT_EQ(first.exit_code, 75) << first.err;
  EXPECT_NE(first.err.find("0 points not started (estimated 0.0 s of one core), 2 stopped part-way with their states saved in states"),
            std::string::npos)
      << first.err;
  EXPECT_EQ(saved_states("states"), 2u);
  EXPECT_EQ(query(dir_ / "cut.db", "SELECT count(*) FROM runs"), 0);
  // The dry run names the saved states.
  const CliResult listed = run(cut + " --dry-run");
  EXPECT_EQ(listed.exit_code, 0) << listed.err;
  EXPECT_NE(listed.out.find("(checkpointed, saved part-way: states/"), std::string::npos) << listed.out;

  int repeats = 1;
  CliResult last = first;
  while (last.exit_code == 75 && repeats < 40) {
    last = run(cut + " --progress");
    ++repeats;
    if (last.exit_code == 75) EXPECT_NE(last.err.find("sweep: resuming driven_column engine=reference N=20"), std::string::npos) << last.err;
  }
  ASSERT_EQ(last.exit_code, 0) << last.err;
  EXPECT_GE(repeats, 3) << "the points ended within two limits: the test shows little";
  EXPECT_EQ(stored("cut.db"), whole);
  EXPECT_EQ(saved_states("states"), 0u);  // spent states are removed
}

TEST_F(SweepCheckpointCli, SigtermSavesTheRunningPointsAndTheSameCommandFinishesThem) {
  ASSERT_EQ(run(kPoints + " --db whole.db").exit_code, 0);
  const std::string args = kPoints + " --db sig.db --threads 2 --checkpoint-dir states --checkpoint-every 1";
  const pid_t pid = start(args);
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  ASSERT_EQ(::kill(pid, SIGTERM), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  const std::string log = slurp(dir_ / "bg.txt");
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << "the sweep ended before the signal: " << log;
  EXPECT_NE(log.find("interrupted by SIGTERM; every point that finished is stored in sig.db, the states of 2 running points are saved in "
                     "states; repeat the same command to go on"),
            std::string::npos)
      << log;
  EXPECT_EQ(saved_states("states"), 2u);

  const CliResult r = run(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(stored("sig.db"), stored("whole.db"));
  EXPECT_EQ(saved_states("states"), 0u);
}

TEST_F(SweepCheckpointCli, RanksSaveAndResumeThroughTheSameFolder) {
#if defined(GRANCHAIN_WITH_MPI) && defined(GRANCHAIN_MPIEXEC)
  ASSERT_EQ(run(kPoints + " --db whole.db").exit_code, 0);
  const std::string mpi = std::string("env OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 '") + GRANCHAIN_MPIEXEC +
                          "' --oversubscribe -np 3 '" + GRANCHAIN_BINARY + "' " + kPoints +
                          " --db mpi.db --time-limit 2 --checkpoint-dir states > mpi.txt 2>&1";
  // Rank 0 (one worker thread) and two ranks run the two points; each saves its point at the deadline.
  const int rc = std::system(("cd '" + dir_.string() + "' && " + mpi).c_str());
  EXPECT_NE(rc, 0);
  EXPECT_NE(slurp(dir_ / "mpi.txt").find("2 stopped part-way with their states saved in states"), std::string::npos)
      << slurp(dir_ / "mpi.txt");
  EXPECT_EQ(saved_states("states"), 2u);
  int repeats = 0;
  while (std::system(("cd '" + dir_.string() + "' && " + mpi).c_str()) != 0 && repeats < 40) ++repeats;
  EXPECT_EQ(stored("mpi.db"), stored("whole.db"));
  EXPECT_EQ(saved_states("states"), 0u);
#else
  GTEST_SKIP() << "built without MPI";
#endif
}

// A state that cannot be written (a folder stands where the reference point's checkpoint goes)
// stops the sweep: the point that could not save is not stored, while the exact engine's point
// running beside it, which saves its own state, still is, and the sweep exits 4 saying so.
TEST_F(SweepCheckpointCli, AStateThatCannotBeSavedStopsTheSweepButKeepsWhatFinishes) {
  SweepDefinition def;
  def.raw = {{"engine", RawValue("reference,exact")}, {"N", RawValue("20")}, {"e", RawValue("0.5")}, {"k", RawValue("1e10")},
             {"T", RawValue("400")}, {"transient", RawValue("20")}};
  def.base_seed = 3;
  const std::vector<SweepPoint> points = build_sweep_points(def);
  ASSERT_EQ(points.size(), 2u);
  const SweepPoint& reference = points[0].spec.engine.kind == EngineKind::Reference ? points[0] : points[1];
  const SweepCheckpoints states((dir_ / "states").string(), 1);
  fs::create_directories(states.path(reference));
  const CliResult r = run("sweep --engine reference,exact --N 20 --e 0.5 --k 1e10 --T 400 --transient 20 --seed 3 -q --threads 2 "
                          "--db s.db --checkpoint-dir states --checkpoint-every 1");
  EXPECT_EQ(r.exit_code, 4) << r.err;
  EXPECT_NE(r.err.find("--checkpoint-dir: cannot write"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("the sweep stopped, every point stored so far is complete and the states saved before are kept in states"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(query(dir_ / "s.db", "SELECT count(*) FROM runs WHERE engine = 'exact'"), 1);
  EXPECT_EQ(query(dir_ / "s.db", "SELECT count(*) FROM runs WHERE engine = 'reference'"), 0);
  EXPECT_EQ(saved_states("states"), 1u);  // the folder in the reference point's place; the exact point's state is spent
  EXPECT_TRUE(fs::is_directory(states.path(reference)));
}

// Bad input: one line naming the parameter and what is valid, exit code 2, nothing written.
TEST_F(SweepCheckpointCli, WhatCannotKeepCheckpointsIsRefused) {
  struct Bad {
    std::string args, expect;
  };
  for (const Bad& b : std::vector<Bad>{
           {"--engine reference --checkpoint-every 60", "--checkpoint-every = 60: it acts only with --checkpoint-dir DIR"},
           {"--engine reference --checkpoint-dir states --checkpoint-every 0.5", "1 <= checkpoint-every <= 1e7"},
           {"--engine reference --checkpoint-dir ''", "--checkpoint-dir: the path is empty"},
       }) {
    SCOPED_TRACE(b.args);
    const CliResult r = run("sweep --N 3 --T 2 --transient 0 -q --db r.db " + b.args);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find(b.expect), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(files(), 0u);
  }
}

// The runner hands out first the points that have a saved state, a point abandoned unsaved goes
// back to the queue, and a point that keeps a state is not "longer than the limit": it runs over
// several invocations.
TEST(SweepCheckpoints, SavedPointsGoFirstAndNeedNotFitTheLimit) {
  const fs::path dir = fs::temp_directory_path() / ("granchain_sweep_states_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  SweepDefinition def;
  def.raw = {{"N", RawValue("3")}, {"e", RawValue("0.5,0.6,0.7")}, {"k", RawValue("1e4")}, {"T", RawValue("20")},
             {"engine", RawValue("reference,exact")}};
  std::vector<SweepPoint> points = build_sweep_points(def);
  ASSERT_EQ(points.size(), 6u);
  for (SweepPoint& p : points) p.cost = 1e6;
  SweepCheckpoints states(dir.string(), 600);
  states.create_folder();
  std::vector<std::size_t> all = {0, 1, 2, 3, 4, 5};
  for (std::size_t i : all) EXPECT_TRUE(SweepCheckpoints::covers(points[i])) << points[i].key;  // every engine saves
  EXPECT_EQ(points_longer_than(points, all, 3600.0).size(), 6u);
  EXPECT_EQ(points_longer_than(points, all, 3600.0, &states).size(), 0u);

  // A saved state for the last point in build order: it is handed out first.
  const std::size_t last = all.back();
  std::ofstream(states.path(points[last])) << "x";
  EXPECT_TRUE(states.has_saved(points[last]));
  EXPECT_THROW(states.saved(points[last]), CheckpointError);  // not a checkpoint
  SweepRunner runner(points, all, [](const SweepPoint&, const RunResult*, const std::string&, const InelasticCollapseError*) {});
  runner.set_checkpoints(&states);
  const auto first = runner.next();
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(*first, last);
  // A point abandoned unsaved goes back to the queue and is handed out again.
  runner.put_back(*first);
  EXPECT_EQ(runner.next(), first);
  EXPECT_EQ(runner.not_started(), 5u);
  EXPECT_TRUE(states.remove(points[last]));
  EXPECT_FALSE(states.has_saved(points[last]));
  fs::remove_all(dir);
}
