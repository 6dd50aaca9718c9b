// Outputs and stores under the conditions of real use: a store shared by concurrent writers or
// held locked by another process, a store on a read-only file, an interrupted sweep or run, and a
// run whose JSON cannot be written (the run and its JSON are kept together or not at all).
#include <signal.h>
#include <sqlite3.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <thread>

#include <nlohmann/json.hpp>

#include "cli_fixture.hpp"

namespace {

std::int64_t count_runs(const fs::path& db_path) { return query(db_path, "SELECT count(*) FROM runs"); }

class OutputsAndStores : public Cli {
 protected:
  static int wait_exit(pid_t pid) {
    int status = 0;
    waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
  }
};

}  // namespace

// Two sweeps into one store at once both finish, every point of both stored once.
TEST_F(OutputsAndStores, TwoSweepsIntoOneStoreBothFinish) {
  // 18 points of about 0.1 s each: the two sweeps write into the store for a second or two at once.
  const std::string grid = "sweep --N 10,12 --e 0.1:0.9:0.1 --k 1e5 --T 300 --db s.db -q --threads 1";
  const pid_t a = start(grid + " --seed 1", "a.txt"), b = start(grid + " --seed 2", "b.txt");
  EXPECT_EQ(wait_exit(a), 0) << slurp(dir_ / "a.txt");
  EXPECT_EQ(wait_exit(b), 0) << slurp(dir_ / "b.txt");
  EXPECT_EQ(count_runs(dir_ / "s.db"), 36);
}

// A store that another process holds under BEGIN EXCLUSIVE is waited for: `run` and `export`
// succeed once it is released (after 2 s), instead of calling it "not an SQLite database".
TEST_F(OutputsAndStores, AStoreHeldLockedIsWaitedFor) {
  ASSERT_EQ(run("run --N 3 --T 5 --db s.db -q").exit_code, 0);
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open((dir_ / "s.db").c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db, "BEGIN EXCLUSIVE", nullptr, nullptr, nullptr), SQLITE_OK);
  std::thread release([db] {
    std::this_thread::sleep_for(std::chrono::seconds(2));
    sqlite3_exec(db, "COMMIT", nullptr, nullptr, nullptr);
  });
  const auto t0 = std::chrono::steady_clock::now();
  const CliResult r = run("run --N 3 --T 5 --seed 2 --db s.db -q");
  const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  release.join();
  sqlite3_close(db);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_GT(waited, 1.0);
  EXPECT_EQ(count_runs(dir_ / "s.db"), 2);
  const CliResult e = run("export --db s.db");
  EXPECT_EQ(e.exit_code, 0) << e.err;
}

// A store held locked for longer than writers wait (60 s) is reported as busy, exit 2, untouched.
TEST_F(OutputsAndStores, AStoreHeldLockedForLongIsReportedBusy) {
  ASSERT_EQ(run("run --N 3 --T 5 --db s.db -q").exit_code, 0);
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open((dir_ / "s.db").c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db, "BEGIN EXCLUSIVE", nullptr, nullptr, nullptr), SQLITE_OK);
  const CliResult r = run("run --N 3 --T 5 --db s.db -q");
  sqlite3_exec(db, "COMMIT", nullptr, nullptr, nullptr);
  sqlite3_close(db);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--db: 's.db' is busy"), std::string::npos) << r.err;
  EXPECT_EQ(count_runs(dir_ / "s.db"), 1);
}

// Commands that only read a store need only read permission (a store on a read-only mount; as
// root, which ignores permission bits, this checks only that nothing asks for write access).
TEST_F(OutputsAndStores, ReadingCommandsOpenTheStoreReadOnly) {
  ASSERT_EQ(run("run --N 3 --T 5 --db s.db -q").exit_code, 0);
  ASSERT_EQ(chmod((dir_ / "s.db").c_str(), 0444), 0);
  EXPECT_EQ(run("export --db s.db").exit_code, 0);
  EXPECT_EQ(run("analyze --db s.db").exit_code, 0);
  const CliResult m = run("merge --into m.db s.db");
  EXPECT_EQ(m.exit_code, 0) << m.err;
  EXPECT_EQ(count_runs(dir_ / "m.db"), 1);
}

// SIGTERM and SIGINT end a sweep and a run by that signal (status 143, 130 in a shell) with one
// line saying what was kept and how to resume; the interrupted sweep's points are whole.
TEST_F(OutputsAndStores, InterruptedSweepAndRunSayWhatWasKept) {
  const pid_t pid = start("sweep --N 30 --e 0.5,0.6,0.7,0.8,0.9 --k 1e5 --T 300 --replicas 4 --db s.db -q --threads 1", "log.txt");
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (count_runs(dir_ / "s.db") < 2 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_EQ(kill(pid, SIGTERM), 0);
  EXPECT_EQ(wait_exit(pid), -SIGTERM);
  const std::string log = slurp(dir_ / "log.txt");
  EXPECT_NE(log.find("granchain: interrupted by SIGTERM; every point that finished is stored in s.db; repeat the same command"),
            std::string::npos)
      << log;
  const std::int64_t kept = count_runs(dir_ / "s.db");
  EXPECT_GE(kept, 2);
  EXPECT_LT(kept, 20) << "the sweep finished before the signal; the test shows nothing";

  const pid_t r = start("run --N 30 --T 100000 --no-db -q", "run.txt");
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  ASSERT_EQ(kill(r, SIGINT), 0);
  EXPECT_EQ(wait_exit(r), -SIGINT);
  EXPECT_NE(slurp(dir_ / "run.txt").find("interrupted by SIGINT; the run did not finish; nothing was stored or written"),
            std::string::npos)
      << slurp(dir_ / "run.txt");
}

// A run's store row and its JSON file are written together: when the JSON cannot be written the
// run is not stored either. The JSON's folder exists when the run starts (so the check before the
// run passes) and is removed while it runs (about 2.5 s; removed after 0.3 s).
TEST_F(OutputsAndStores, RunAndItsJsonAreKeptTogether) {
  ASSERT_EQ(run("run --N 3 --T 5 --db s.db -q").exit_code, 0);
  fs::create_directories(dir_ / "out");
  const pid_t pid = start("run --N 25 --T 5000 --db s.db --json out/r.json -q", "log.txt");
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  fs::remove_all(dir_ / "out");
  const int code = wait_exit(pid);
  const std::string log = slurp(dir_ / "log.txt");
  ASSERT_NE(code, 0) << "the run finished before its output folder was removed: " << log;
  EXPECT_EQ(code, 4) << log;
  EXPECT_NE(log.find("--json: cannot write 'out/r.json'"), std::string::npos) << log;
  EXPECT_NE(log.find("nothing was stored or written"), std::string::npos) << log;
  EXPECT_EQ(count_runs(dir_ / "s.db"), 1);
}

// Standard output that cannot be written (a full disk: /dev/full) is exit 4 with one line saying
// so (and, for `run`, that the run is stored); the device is still a device afterwards (outputs to
// a device are written into it, never renamed over it).
TEST_F(OutputsAndStores, StandardOutputThatCannotBeWrittenIsExitFour) {
  ASSERT_EQ(run("run --N 3 --T 5 --db s.db -q").exit_code, 0);
  auto to_full = [&](const std::string& args) {
    const std::string cmd = "cd '" + dir_.string() + "' && '" GRANCHAIN_BINARY "' " + args + " > /dev/full 2> err.txt";
    const int status = std::system(cmd.c_str());
    return CliResult{WIFEXITED(status) ? WEXITSTATUS(status) : -1, "", slurp(dir_ / "err.txt")};
  };
  for (const char* args : {"export --db s.db", "export --db s.db --format json", "theory --N 3,4", "analyze --db s.db",
                           "run --N 3 --T 5 --no-db"}) {
    const CliResult r = to_full(args);
    EXPECT_EQ(r.exit_code, 4) << args << ": " << r.err;
    EXPECT_NE(r.err.find("cannot write standard output: No space left on device"), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
  }
  const CliResult j = to_full("run --N 3 --T 5 --seed 2 --db s.db --json");
  EXPECT_EQ(j.exit_code, 4) << j.err;
  EXPECT_NE(j.err.find("the run is stored (run 2 in s.db)"), std::string::npos) << j.err;
  struct stat st {};
  ASSERT_EQ(stat("/dev/full", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode)) << "/dev/full was replaced";
}

// A new store that cannot be set up on a full file system (a 16 KiB tmpfs) is exit 4 and leaves no
// empty file behind. Mounting needs root: elsewhere the test is skipped.
TEST_F(OutputsAndStores, ANewStoreOnAFullDiskLeavesNoFile) {
  fs::create_directories(dir_ / "small");
  if (std::system(("mount -t tmpfs -o size=16k tmpfs '" + (dir_ / "small").string() + "' 2> /dev/null").c_str()) != 0)
    GTEST_SKIP() << "cannot mount a tmpfs here (needs root)";
  const CliResult r = run("run --N 3 --T 5 --db small/new.db -q");
  const bool left = fs::exists(dir_ / "small/new.db");
  std::system(("umount '" + (dir_ / "small").string() + "'").c_str());
  EXPECT_EQ(r.exit_code, 4) << r.err;
  EXPECT_NE(r.err.find("disk is full; nothing was stored or written"), std::string::npos) << r.err;
  EXPECT_FALSE(left);
}

// The plot scripts die with granchain: a reproduction killed with kill -9 while it draws leaves no
// python3 drawing behind it.
TEST_F(OutputsAndStores, PlotScriptsDieWithGranchain) {
  const pid_t pid = start("reproduce --figure fig1 --preset smoke --db r.db --out figs -q", "log.txt");
  const std::string children = "/proc/" + std::to_string(pid) + "/task/" + std::to_string(pid) + "/children";
  pid_t child = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (child == 0 && std::chrono::steady_clock::now() < deadline) {  // a child that runs python3
    std::ifstream f(children);
    if (!(f >> child) || slurp("/proc/" + std::to_string(child) + "/cmdline").find("python3") == std::string::npos) child = 0;
    if (child == 0) std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ASSERT_NE(child, 0) << "no plot script was started: " << slurp(dir_ / "log.txt");
  ASSERT_EQ(kill(pid, SIGKILL), 0);
  EXPECT_EQ(wait_exit(pid), -SIGKILL);
  // The script had only just started (importing matplotlib alone takes longer than this): gone
  // within 0.2 s means it was killed, not that it finished.
  // Gone: no such process, or a zombie (dead, waiting to be reaped by whoever adopted it).
  auto dead = [&] {
    std::ifstream stat("/proc/" + std::to_string(child) + "/stat");
    std::string pid_field, name, state;
    return !(stat >> pid_field >> name >> state) || state == "Z" || state == "X";
  };
  bool gone = false;
  for (int i = 0; i < 40 && !gone; ++i) {
    gone = dead();
    if (!gone) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  EXPECT_TRUE(gone) << "python3 (pid " << child << ") outlived granchain";
  if (!gone) kill(child, SIGKILL);
}

// Every JSON output and every stored run records where it came from: the command line, host,
// threads and ranks, the build's settings (also printed by --version), the code version, units.
TEST_F(OutputsAndStores, ResultsRecordTheirProvenance) {
  const CliResult v = run("--version");
  ASSERT_EQ(v.exit_code, 0);
  EXPECT_NE(v.out.find("build type "), std::string::npos) << v.out;
  EXPECT_NE(v.out.find("compiler "), std::string::npos) << v.out;
  EXPECT_NE(v.out.find("MPI "), std::string::npos) << v.out;
  const CliResult r = run("run --N 3 --T 2 --db s.db --json r.json -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(dir_ / "r.json"));
  const auto& p = j.at("provenance");
  EXPECT_NE(p.at("command_line").get<std::string>().find(" run --N 3 --T 2 --db s.db --json r.json -q"), std::string::npos);
  EXPECT_FALSE(p.at("host").get<std::string>().empty());
  EXPECT_EQ(p.at("threads"), 1);
  EXPECT_EQ(p.at("ranks"), 1);
  EXPECT_NE(v.out.find(p.at("build").get<std::string>()), std::string::npos) << "--version and the JSON disagree";
  EXPECT_EQ(p.at("code_version"), j.at("code_version"));
  EXPECT_NE(p.at("units").get<std::string>().find("k_B T0"), std::string::npos);
  // The stored run holds the same record.
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open_v2((dir_ / "s.db").c_str(), &db, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
  sqlite3_stmt* st = nullptr;
  ASSERT_EQ(sqlite3_prepare_v2(db, "SELECT json_extract(result_json, '$.provenance.command_line') FROM runs", -1, &st, nullptr), SQLITE_OK);
  ASSERT_EQ(sqlite3_step(st), SQLITE_ROW);
  EXPECT_EQ(reinterpret_cast<const char*>(sqlite3_column_text(st, 0)), p.at("command_line").get<std::string>());
  sqlite3_finalize(st);
  sqlite3_close(db);
  // A sweep records its threads.
  ASSERT_EQ(run("sweep --N 3 --e 0.5,0.6 --T 2 --threads 2 --db s.db -q").exit_code, 0);
  EXPECT_EQ(query(dir_ / "s.db", "SELECT max(json_extract(result_json, '$.provenance.threads')) FROM runs"), 2);
}

// `collapse --progress` reports launches done, elapsed time, ETA and collisions/s on standard
// error (plain lines off a terminal), ending with every launch of every point done.
TEST_F(OutputsAndStores, CollapseReportsProgress) {
  const CliResult r = run("collapse --N 10 --e 0.3,0.5 --k 1e6,1e7 --realizations 100 --no-db --progress -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_NE(r.err.find("collapse: 400/400 launches, elapsed "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("collisions/s"), std::string::npos) << r.err;
}
