// A store whose writer was killed mid-transaction (kill -9, a power cut) keeps its committed
// state, with SQLite's rollback journal beside it: every command must roll the journal back and
// go on, never call the store "not an SQLite database". First a journal made on purpose (a
// writer killed inside a transaction that spilled pages into the file), then sweeps and merges
// killed at random moments, many times.
#include <signal.h>
#include <sqlite3.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <random>
#include <thread>

#include "cli_fixture.hpp"

namespace {

std::int64_t count_runs(const fs::path& db_path) { return query(db_path, "SELECT count(*) FROM runs"); }

class InterruptedWrites : public Cli {
 protected:
  // A child process opens the store, writes more than its page cache holds inside one
  // transaction (so pages reach the file and the journal holds their old content) and is killed
  // by SIGKILL before it commits: a hot journal, as kill -9 leaves it.
  void leave_hot_journal(const std::string& name) {
    const std::string path = (dir_ / name).string();
    const pid_t pid = fork();
    if (pid == 0) {
      sqlite3* db = nullptr;
      if (sqlite3_open(path.c_str(), &db) != SQLITE_OK) _exit(1);
      sqlite3_exec(db, "PRAGMA cache_size = 10; BEGIN IMMEDIATE; CREATE TABLE IF NOT EXISTS scratch(x TEXT)", nullptr, nullptr, nullptr);
      for (int i = 0; i < 2000; ++i)
        sqlite3_exec(db, "INSERT INTO scratch VALUES(hex(randomblob(200))); UPDATE runs SET n_coll = -1", nullptr, nullptr, nullptr);
      kill(getpid(), SIGKILL);
      _exit(1);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
    ASSERT_GT(fs::file_size(dir_ / (name + "-journal")), 0u) << "no journal was left: the test shows nothing";
  }
  // The store holds its committed state: no uncommitted n_coll = -1, no scratch table.
  void expect_committed_state(const std::string& name, std::int64_t runs) {
    EXPECT_EQ(count_runs(dir_ / name), runs);
    EXPECT_EQ(query(dir_ / name, "SELECT count(*) FROM runs WHERE n_coll < 0"), 0);
    EXPECT_EQ(query(dir_ / name, "SELECT count(*) FROM sqlite_master WHERE name = 'scratch'"), 0);
  }
};

}  // namespace

// Every command that opens a store, given one with a hot journal, rolls it back and succeeds: the
// sweep resumes, export, analyze, merge (as source and as target), reproduce --stored-only, run.
TEST_F(InterruptedWrites, EveryCommandRollsBackAHotJournalAndGoesOn) {
  const std::string sweep = "sweep --N 2 --e 0.5,0.7,0.9 --k 1e4,1e5 --T 1 --transient 0 --db s.db -q --threads 1";
  ASSERT_EQ(run(sweep).exit_code, 0);
  ASSERT_EQ(count_runs(dir_ / "s.db"), 6);
  // The first three lose their last point, so the sweep below has something to resume.
  ASSERT_EQ(query(dir_ / "s.db", "SELECT count(*) FROM runs"), 6);
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open((dir_ / "s.db").c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db, "PRAGMA foreign_keys = ON; DELETE FROM runs WHERE id = 6", nullptr, nullptr, nullptr), SQLITE_OK);
  sqlite3_close(db);

  const std::vector<std::pair<std::string, std::int64_t>> commands = {
      {"export --db s.db -o out.csv", 5},
      {"analyze --db s.db", 5},
      {"merge --into m.db s.db", 5},
      {"reproduce --figure fig1 --preset smoke --db s.db --out figs --stored-only -q", 5},
      {sweep, 6},  // resumes: the missing point is run, nothing twice
      {"run --N 2 --T 1 --transient 0 --seed 99 --db s.db -q", 7},
  };
  for (const auto& [command, runs_after] : commands) {
    SCOPED_TRACE(command);
    leave_hot_journal("s.db");
    if (HasFatalFailure()) return;
    const CliResult r = run(command);
    // reproduce --stored-only with nothing of fig1 stored exits 2 for that reason, not the journal's.
    if (command.rfind("reproduce", 0) == 0) EXPECT_EQ(r.err.find("not an SQLite database"), std::string::npos) << r.err;
    else EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "s.db-journal"));
    expect_committed_state("s.db", runs_after);
  }
  // As the target of a merge.
  leave_hot_journal("m.db");
  if (HasFatalFailure()) return;
  const CliResult m = run("merge --into m.db s.db");
  EXPECT_EQ(m.exit_code, 0) << m.err;
  expect_committed_state("m.db", 7);
}

// Sweeps and merges killed by SIGKILL at random moments (a fixed seed for the moments), 25 times
// each: after every kill the store is readable by export, holds whole runs only, and the same
// command finishes it, every point once.
TEST_F(InterruptedWrites, SweepsAndMergesKilledAtRandomMomentsResume) {
  // 120 points of about a millisecond each: the sweep spends most of its time writing the store.
  const std::string sweep = "sweep --N 2 --e 0.2:0.9:0.1 --k 1e4,1e5,1e6 --T0 1,2,3,4,5 --T 0.5 --transient 0 --db s.db -q --threads 2";
  std::mt19937 rng(2026);
  std::uniform_int_distribution<int> delay_ms(5, 400);
  int killed = 0;
  for (int i = 0; i < 25; ++i) {
    const pid_t pid = start(sweep);
    std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms(rng)));
    killed += kill(pid, SIGKILL) == 0;
    int status = 0;
    waitpid(pid, &status, 0);
    const CliResult e = run("export --db s.db -o rows.csv");
    ASSERT_EQ(e.exit_code, 0) << "after kill " << i << ": " << e.err;
    EXPECT_EQ(query(dir_ / "s.db", "SELECT count(*) FROM runs r WHERE (SELECT count(*) FROM profiles p WHERE p.run_id = r.id) != 2"), 0);
  }
  EXPECT_GT(killed, 0) << "every sweep ended before its kill: the test shows nothing";
  const CliResult done = run(sweep);
  ASSERT_EQ(done.exit_code, 0) << done.err;
  EXPECT_EQ(count_runs(dir_ / "s.db"), 120);
  EXPECT_EQ(query(dir_ / "s.db", "SELECT count(DISTINCT point_key) FROM run_points"), 120);

  // Merges of the 120 runs into a target that holds 3 runs of its own: after each kill the target
  // holds its own 3 or all 123, never a part.
  ASSERT_EQ(run("sweep --N 2 --e 0.5 --k 1e4 --T 0.4 --transient 0 --replicas 3 --db t.db -q").exit_code, 0);
  for (int i = 0; i < 25; ++i) {
    const pid_t pid = start("merge --into t.db s.db");
    std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms(rng) / 10));
    kill(pid, SIGKILL);
    int status = 0;
    waitpid(pid, &status, 0);
    const CliResult e = run("export --db t.db -o rows.csv");
    ASSERT_EQ(e.exit_code, 0) << "after kill " << i << ": " << e.err;
    const std::int64_t n = count_runs(dir_ / "t.db");
    EXPECT_TRUE(n == 3 || n == 123) << n;
  }
  ASSERT_EQ(run("merge --into t.db s.db").exit_code, 0);
  EXPECT_EQ(count_runs(dir_ / "t.db"), 123);
}

// SIGTERM ends analyze --plot and merge with one line saying what was kept, and leaves no
// unfinished file (the plot script, ended with granchain, removes its own).
TEST_F(InterruptedWrites, InterruptedAnalyzeAndMergeSayWhatWasKept) {
  ASSERT_EQ(run("sweep --N 3 --e 0.5 --k 1e4,1e5,1e6 --T 20 --db s.db -q").exit_code, 0);
  const auto files_before = files();
  const pid_t pid = start("analyze --db s.db --plot q -q", "log.txt");
  // Once the plot script runs (a child that is python3), SIGTERM.
  const std::string children = "/proc/" + std::to_string(pid) + "/task/" + std::to_string(pid) + "/children";
  pid_t child = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (child == 0 && std::chrono::steady_clock::now() < deadline) {
    std::ifstream f(children);
    if (!(f >> child) || slurp("/proc/" + std::to_string(child) + "/cmdline").find("python3") == std::string::npos) child = 0;
    if (child == 0) std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ASSERT_NE(child, 0) << "no plot script was started: " << slurp(dir_ / "log.txt");
  std::this_thread::sleep_for(std::chrono::milliseconds(800));  // into matplotlib's work
  ASSERT_EQ(kill(pid, SIGTERM), 0);
  int status = 0;
  waitpid(pid, &status, 0);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM);
  EXPECT_NE(slurp(dir_ / "log.txt").find("interrupted by SIGTERM; the figures were not all drawn"), std::string::npos)
      << slurp(dir_ / "log.txt");
  for (int i = 0; i < 100 && fs::exists("/proc/" + std::to_string(child) + "/cmdline"); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));  // the script ends on its parent's death
  for (const auto& entry : fs::directory_iterator(dir_))
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path() << " was left behind";
  EXPECT_GE(files(), files_before);

  // A merge waiting for a target that another process holds locked, ended by SIGTERM.
  ASSERT_EQ(run("run --N 3 --T 5 --seed 9 --db t.db -q").exit_code, 0);
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open((dir_ / "t.db").c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db, "BEGIN EXCLUSIVE", nullptr, nullptr, nullptr), SQLITE_OK);
  const pid_t merge = start("merge --into t.db s.db", "merge.txt");
  std::this_thread::sleep_for(std::chrono::milliseconds(700));
  ASSERT_EQ(kill(merge, SIGTERM), 0);
  waitpid(merge, &status, 0);
  sqlite3_exec(db, "COMMIT", nullptr, nullptr, nullptr);
  sqlite3_close(db);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM);
  EXPECT_NE(slurp(dir_ / "merge.txt").find("interrupted by SIGTERM; nothing was merged"), std::string::npos) << slurp(dir_ / "merge.txt");
  EXPECT_EQ(count_runs(dir_ / "t.db"), 1);
}

// A reader without write access (another user's store, read-only media) reads a store that has no
// journal, and is told, not misled, when a hot journal needs a writer. As root the test runs the
// reader as the user nobody (setpriv); elsewhere it is skipped.
TEST_F(InterruptedWrites, AReaderWithoutWriteAccess) {
  if (geteuid() != 0 || std::system("command -v setpriv > /dev/null") != 0) GTEST_SKIP() << "needs root and setpriv";
  // The user nobody must be able to run a program at all: not so in a chroot whose root directory
  // is private (mode 0700, as mktemp makes it), where no shared library can be opened.
  if (std::system("setpriv --reuid=65534 --regid=65534 --clear-groups /bin/true 2> /dev/null") != 0)
    GTEST_SKIP() << "the user nobody cannot run programs on this system (its root directory is not searchable)";
  ASSERT_EQ(run("run --N 2 --T 1 --transient 0 --db s.db -q").exit_code, 0);
  ASSERT_EQ(chmod(dir_.c_str(), 0755), 0);
  ASSERT_EQ(chmod((dir_ / "s.db").c_str(), 0644), 0);
  const std::string as_nobody = "cd '" + dir_.string() + "' && setpriv --reuid=65534 --regid=65534 --clear-groups '" GRANCHAIN_BINARY
                                "' export --db s.db -o /dev/null 2> nobody.txt";
  int status = std::system(as_nobody.c_str());
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << slurp(dir_ / "nobody.txt");
  leave_hot_journal("s.db");
  if (HasFatalFailure()) return;
  ASSERT_EQ(chmod((dir_ / "s.db-journal").c_str(), 0644), 0);
  status = std::system(as_nobody.c_str());
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 2);
  EXPECT_NE(slurp(dir_ / "nobody.txt").find("has the journal of an interrupted write beside it"), std::string::npos)
      << slurp(dir_ / "nobody.txt");
  EXPECT_EQ(run("export --db s.db -o rows.csv").exit_code, 0);  // a writer rolls it back
  expect_committed_state("s.db", 1);
}
