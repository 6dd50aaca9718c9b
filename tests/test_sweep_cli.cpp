// `granchain sweep`, `merge`, `export` and `analyze` as a user meets them: a 200-point sweep killed with
// kill -9 and resumed, identical numbers on 1 thread, 2 threads and 2 MPI ranks, job-array shards
// merged back, CSV export, and bad input.
#include <signal.h>
#include <sqlite3.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <sstream>
#include <thread>
#include <vector>

#include <cmath>
#include <nlohmann/json.hpp>

#include "cli_fixture.hpp"
#include "store/results_store.hpp"

namespace {

// Physics columns of every stored run, by point key, from `granchain export` CSV.
std::map<std::string, std::string> physics_by_key(const std::string& csv) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  {
    std::istringstream h(line);
    for (std::string c; std::getline(h, c, ',');) header.push_back(c);
  }
  const std::vector<std::string> wanted = {"seed",      "n_coll",  "n_coll_err",          "n_coll_blocks", "floor_rate",
                                           "pp_rate",   "samples", "particle_collisions", "floor_hits",    "events"};
  std::map<std::string, std::string> out;
  while (std::getline(in, line)) {
    std::istringstream r(line);
    std::map<std::string, std::string> row;
    std::size_t i = 0;
    for (std::string c; std::getline(r, c, ',');) row[header.at(i++)] = c;
    std::string physics;
    for (const auto& w : wanted) physics += w + "=" + row.at(w) + " ";
    EXPECT_TRUE(out.emplace(row.at("point_key"), physics).second) << "point stored twice: " << row.at("point_key");
  }
  return out;
}

// Profile rows of `granchain export --table profiles` without their store-specific run id, sorted.
std::vector<std::string> profile_rows(const std::string& csv) {
  std::istringstream in(csv);
  std::vector<std::string> rows;
  for (std::string line; std::getline(in, line);) rows.push_back(line.substr(line.find(',') + 1));
  std::sort(rows.begin(), rows.end());
  return rows;
}

class SweepCli : public Cli {
 protected:
  std::string export_csv(const std::string& db, const std::string& table = "runs") {
    const CliResult r = run("export --db " + db + " --table " + table);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return r.out;
  }
};

// 8 values of N x 5 of e x 5 replicas = 200 points, about 2 s of one core.
const std::string kGrid = "sweep --N 3:10:1 --e 0.5,0.7,0.8,0.9,0.95 --k 1e5 --T 300 --replicas 5 --seed 11 -q";

}  // namespace

TEST_F(SweepCli, TwoHundredPointsSurviveKillNineAndAgreeOnThreadsAndRanks) {
  const CliResult one = run(kGrid + " --threads 1 --db one.db");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  ASSERT_EQ(query(dir_ / "one.db", "SELECT count(*) FROM runs"), 200);

  // Killed with SIGKILL part-way through, on 2 threads.
  const pid_t pid = start(kGrid + " --threads 2 --db killed.db");
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  std::int64_t at_kill = 0;
  while ((at_kill = query(dir_ / "killed.db", "SELECT count(*) FROM runs")) < 30 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_EQ(kill(pid, SIGKILL), 0);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the sweep ended before it could be killed";
  const std::int64_t after_kill = query(dir_ / "killed.db", "SELECT count(*) FROM runs");
  ASSERT_GE(after_kill, 30);
  ASSERT_LT(after_kill, 200) << "the sweep finished before the kill; the test shows nothing";
  // Every stored run is whole: its key and all its particles' profiles are there.
  EXPECT_EQ(query(dir_ / "killed.db", "SELECT count(*) FROM run_points"), after_kill);
  EXPECT_EQ(query(dir_ / "killed.db", "SELECT count(*) FROM profiles"), query(dir_ / "killed.db", "SELECT sum(N) FROM runs"));

  // The same command again finishes the sweep, reporting progress as plain lines (not a terminal).
  const CliResult resumed = run(kGrid + " --threads 2 --db killed.db --progress --progress-every 0.2");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_NE(resumed.err.find(std::to_string(after_kill) + " already in killed.db"), std::string::npos) << resumed.err;
  EXPECT_NE(resumed.err.find("sweep: " + std::to_string(200 - after_kill) + "/" + std::to_string(200 - after_kill) + " points"),
            std::string::npos)
      << resumed.err;
  EXPECT_NE(resumed.err.find("ETA"), std::string::npos);
  EXPECT_NE(resumed.err.find("collisions/s"), std::string::npos);
  EXPECT_EQ(query(dir_ / "killed.db", "SELECT count(*) FROM runs"), 200);
  EXPECT_EQ(query(dir_ / "killed.db", "SELECT count(DISTINCT point_key) FROM run_points"), 200);
  EXPECT_EQ(query(dir_ / "killed.db", "SELECT count(*) FROM profiles"), query(dir_ / "one.db", "SELECT count(*) FROM profiles"));
  // A third time there is nothing left to do.
  ASSERT_EQ(run(kGrid + " --threads 2 --db killed.db").exit_code, 0);
  EXPECT_EQ(query(dir_ / "killed.db", "SELECT count(*) FROM runs"), 200);

  const auto reference = physics_by_key(export_csv("one.db"));
  ASSERT_EQ(reference.size(), 200u);
  EXPECT_EQ(physics_by_key(export_csv("killed.db")), reference);

#if defined(GRANCHAIN_WITH_MPI) && defined(GRANCHAIN_MPIEXEC)
  // Two MPI ranks (root needs OpenMPI's explicit consent; one core may host both ranks).
  const std::string mpi = std::string("env OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 '") + GRANCHAIN_MPIEXEC +
                          "' --oversubscribe -np 2 '" + GRANCHAIN_BINARY + "' " + kGrid + " --db mpi.db";
  const int rc = std::system(("cd '" + dir_.string() + "' && " + mpi + " > mpi.txt 2>&1").c_str());
  ASSERT_EQ(rc, 0) << slurp(dir_ / "mpi.txt");
  EXPECT_EQ(physics_by_key(export_csv("mpi.db")), reference);
  // Profiles too, particle by particle.
  const auto profiles = profile_rows(export_csv("one.db", "profiles"));
  EXPECT_EQ(profiles.size(), 1u + 5u * 5u * 52u);  // header, then 5 e x 5 replicas x (3 + 4 + ... + 10) particles
  EXPECT_EQ(profile_rows(export_csv("mpi.db", "profiles")), profiles);
  EXPECT_EQ(profile_rows(export_csv("killed.db", "profiles")), profiles);
#else
  GTEST_SKIP() << "built without MPI: the 2-rank part was not run";
#endif
}

TEST_F(SweepCli, ShardsMergeIntoTheWholeSweepAndExportCsv) {
  const std::string grid = "sweep --N 3,4,5 --e 0.6:0.9:0.1 --k 1e4 --T 30 --replicas 2 -q";
  ASSERT_EQ(run(grid + " --db whole.db").exit_code, 0);
  std::string shards;
  for (int i = 1; i <= 3; ++i) {
    const CliResult r = run(grid + " --shard " + std::to_string(i) + "/3 --db shard" + std::to_string(i) + ".db");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    shards += " shard" + std::to_string(i) + ".db";
  }
  EXPECT_EQ(query(dir_ / "shard1.db", "SELECT count(*) FROM runs"), 8);  // 24 points in 3 shares
  const CliResult merged = run("merge --into all.db" + shards);
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  EXPECT_NE(merged.out.find("24 runs added, 0 already there"), std::string::npos) << merged.out;
  EXPECT_EQ(physics_by_key(export_csv("all.db")), physics_by_key(export_csv("whole.db")));
  const CliResult again = run("merge --into all.db whole.db");
  EXPECT_NE(again.out.find("0 runs added, 24 already there"), std::string::npos) << again.out;

  // A conflicting copy of a point is refused with one line, exit 2, nothing merged.
  fs::copy_file(dir_ / "shard1.db", dir_ / "bad.db");
  sqlite3* db = nullptr;
  sqlite3_open((dir_ / "bad.db").c_str(), &db);
  sqlite3_exec(db, "UPDATE runs SET n_coll = n_coll * 1.0000001", nullptr, nullptr, nullptr);
  sqlite3_close(db);
  const CliResult conflict = run("merge --into all.db bad.db");
  EXPECT_EQ(conflict.exit_code, 2);
  EXPECT_NE(conflict.err.find("conflicting results for point"), std::string::npos) << conflict.err;
  EXPECT_EQ(std::count(conflict.err.begin(), conflict.err.end(), '\n'), 1);
  EXPECT_EQ(query(dir_ / "all.db", "SELECT count(*) FROM runs"), 24);

  // Export a selection to a CSV file.
  const CliResult ex = run("export --db all.db --N 4 --e 0.7,0.8 --output n4.csv");
  ASSERT_EQ(ex.exit_code, 0) << ex.err;
  const std::string csv = slurp(dir_ / "n4.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 2 * 2);
  EXPECT_EQ(csv.rfind("id,created_utc,code_version,setup,engine,N,e,k,T0,", 0), 0u) << csv.substr(0, 200);
}

TEST_F(SweepCli, SweepFileEqualsFlagsAndBadInputIsRefused) {
  write("grid.toml", "N = [3, 4]\ne = \"0.8:0.9:0.05\"\nk = 1e4\nT = 10\nreplicas = 2\nseed = 5\n");
  write("grid.json", "{\"N\": [3, 4], \"e\": \"0.8:0.9:0.05\", \"k\": 1e4, \"T\": 10, \"replicas\": 2, \"seed\": 5}");
  const CliResult flags = run("sweep --N 3,4 --e 0.80,0.85,0.9 --k 1e4 --T 10 --replicas 2 --seed 5 --dry-run");
  ASSERT_EQ(flags.exit_code, 0) << flags.err;
  EXPECT_NE(flags.out.find("# 12 points"), std::string::npos) << flags.out;
  EXPECT_EQ(run("sweep --sweep grid.toml --dry-run").out, flags.out);
  EXPECT_EQ(run("sweep --sweep grid.json --dry-run").out, flags.out);
  EXPECT_NE(run("sweep --sweep grid.toml --seed 6 --dry-run").out, flags.out);  // flags override the file

  write("unknown.toml", "N = 3\nspeed = 2\n");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--shard 3/2", "--shard"},         {"--shard 1", "--shard"},       {"--shard 0/2", "--shard"},
      {"--replicas 0", "--replicas"},     {"--threads 0", "--threads"},   {"--e 0.5,2", "--e"},
      {"--N 0:3:1", "--N"},               {"--k 1e4:1e2:x10", "--k"},     {"--tc 0.1", "--tc"},
      {"--engine exact,warp", "--engine"}, {"--seed -1", "--seed"},       {"--sweep missing.toml", "--sweep"},
      {"--sweep unknown.toml", "speed"},  {"--progress-every 0", "--progress-every"}, {"--db nodir/x.db", "--db"}};
  for (const auto& [args, names] : cases) {
    const CliResult r = run("sweep --T 5 " + args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
    EXPECT_NE(r.err.find(names), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "granchain.db")) << args;
  }
  const CliResult fig = run("reproduce --figure fig11");
  EXPECT_EQ(fig.exit_code, 2);
  EXPECT_NE(fig.err.find("--figure"), std::string::npos) << fig.err;
  EXPECT_EQ(run("reproduce --preset slow").exit_code, 2);
  EXPECT_FALSE(fs::exists(dir_ / "reproduce.db"));
  const CliResult ex = run("export --db missing.db");
  EXPECT_EQ(ex.exit_code, 2) << ex.err;
  EXPECT_EQ(run("export --table nope").exit_code, 2);
  EXPECT_EQ(run("merge --into a.db missing.db").exit_code, 2);
  EXPECT_FALSE(fs::exists(dir_ / "a.db"));
}

// The two schematic figures are drawn from simulated trajectories: files and reports exist, and the
// three-body collapse of fig2 (e = 0.065 < e_c(3)) has intervals shrinking by about q = 0.305 per
// collision of the pair (1, 2) before the contact time stops them (the report lists the ratios).
TEST_F(SweepCli, ReproducesTheSchematicFiguresFromTrajectories) {
  const CliResult r = run("reproduce --figure fig1 --out figs -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("figure: figs/fig1.png"), std::string::npos) << r.out;
  for (const char* f : {"figs/fig1.png", "figs/fig1.pdf", "figs/fig1-trace.csv", "figs/report-fig1.md"})
    EXPECT_TRUE(fs::exists(dir_ / f)) << f;
  const CliResult r2 = run("reproduce --figure fig2 --out figs -q");
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  for (const char* f : {"figs/fig2.png", "figs/fig2.pdf", "figs/fig2-events.csv", "figs/report-fig2.md"})
    EXPECT_TRUE(fs::exists(dir_ / f)) << f;
  const std::string md = slurp(dir_ / "figs/report-fig2.md");
  const auto at = md.find("the ratios of successive t12: ");
  ASSERT_NE(at, std::string::npos) << md;
  // The third to fifth ratios: past the launch, before tau_c matters (within 0.03 of q).
  std::istringstream ratios(md.substr(at + 30));
  std::vector<double> q;
  for (double x; q.size() < 5 && ratios >> x; ratios.ignore(2)) q.push_back(x);
  ASSERT_EQ(q.size(), 5u) << md;
  for (int n = 2; n < 5; ++n) EXPECT_NEAR(q[n], 0.3053, 0.03) << n;
  EXPECT_FALSE(fs::exists(dir_ / "figs/report-all.md"));
}

// --print-sweeps prints the figure's grid as `granchain sweep` commands; run as printed, they fill
// a store from which the figure reuses every point (the keys agree).
TEST_F(SweepCli, PrintedSweepsFillTheStoreTheFigureReuses) {
  const CliResult p = run("reproduce --figure fig4 --print-sweeps");
  ASSERT_EQ(p.exit_code, 0) << p.err;
  // Each command follows a comment line with its predicted cost. The e grid: 0.05 .. 1.0 by 0.05
  // and five values around each e_c(n), n = 3 .. 7: 45 e, 4 N, 5 k, two seeds.
  const std::size_t at = p.out.find("granchain sweep");
  ASSERT_NE(at, std::string::npos) << p.out;
  EXPECT_EQ(p.out.rfind("# 1800 points, predicted ", at), 0u) << p.out;
  const std::string line = p.out.substr(at, p.out.find('\n', at) - at);
  EXPECT_EQ(line.rfind("granchain sweep --N 3,4,5,6 --e 0.05:1.0:0.05,0.0618,", 0), 0u) << line;
  EXPECT_NE(line.find(",0.0718,"), std::string::npos) << line;  // e_c(3)
  EXPECT_NE(line.find(" --k 1e4:1e8:x10 --T 1000 --T0 1 --replicas 2"), std::string::npos) << line;
  EXPECT_NE(p.out.find("# 1800 distinct points"), std::string::npos) << p.out;
  // Run as printed (1800 runs, about 40 s), then the figure finds every point stored.
  const CliResult sw = run(line.substr(std::string("granchain ").size()) + " --db s.db -q");
  ASSERT_EQ(sw.exit_code, 0) << sw.err;
  const CliResult fig = run("reproduce --figure fig4 --db s.db --out figs");
  ASSERT_EQ(fig.exit_code, 0) << fig.err;
  EXPECT_NE(fig.err.find("1800 runs, 1800 already in s.db, 0 to run"), std::string::npos) << fig.err;
  EXPECT_EQ(query(dir_ / "s.db", "SELECT count(*) FROM runs"), 1800);
  EXPECT_TRUE(fs::exists(dir_ / "figs/fig4.png"));
  EXPECT_TRUE(fs::exists(dir_ / "figs/report-fig4.md"));
}

// The smoke preset runs every figure's code path on tiny grids: all of them finish, every figure
// file and report exists, Table 1 has its eight rows, and a repeat runs nothing new.
TEST_F(SweepCli, SmokePresetDrawsEveryFigureAndTable1) {
  // In sittings of a --time-limit shorter than drawing every figure takes: each repeat after exit
  // 75 stores more (runs and counts come before any drawing), and the repeats end.
  std::int64_t stored = 0;
  CliResult r{75, "", ""};
  for (int sitting = 0; sitting < 8 && r.exit_code == 75; ++sitting) {
    r = run("reproduce --figure all --preset smoke --out figs -q --time-limit 6");
    const std::int64_t now = query(dir_ / "reproduce.db", "SELECT (SELECT count(*) FROM runs) + (SELECT count(*) FROM collapse_runs)");
    if (r.exit_code == 75) {
      EXPECT_GT(now, stored) << "sitting " << sitting << " made no progress: " << r.err;
      EXPECT_NE(r.err.find("no figure was drawn"), std::string::npos) << r.err;
    }
    stored = now;
  }
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"fig1.png", "fig2.pdf", "fig3.png", "fig4.pdf", "fig5_N25_T01_exact.png",
                        "fig6.png", "fig6.pdf", "fig7.png", "fig8.png", "fig9.png", "fig10.png", "table1.csv", "report.md",
                        "report-fig6.md", "report-fig7.md", "report-fig9.md", "report-table1.md", "report-all.md"})
    EXPECT_TRUE(fs::exists(dir_ / "figs" / f)) << f;
  // fig3 and fig4 share one sweep but draw it differently (against log k, against e): not one figure twice.
  EXPECT_NE(slurp(dir_ / "figs/fig3.png"), slurp(dir_ / "figs/fig4.png"));
  EXPECT_FALSE(fs::exists(dir_ / "figs/fig3_N3_T01_exact.png"));
  const std::string all = slurp(dir_ / "figs/report-all.md");
  // The report names the command that made it, with the flags given (no --db: the default store).
  EXPECT_EQ(all.rfind("# granchain reproduce --figure all --preset smoke --out figs\n", 0), 0u) << all.substr(0, 200);
  for (const char* fig : {"| fig1 |", "| fig6 |", "| fig7 |", "| fig8 |", "| fig9 |", "| fig10 |", "| table1 |"})
    EXPECT_NE(all.find(std::string(fig)), std::string::npos) << fig;
  EXPECT_EQ(all.find("failed"), std::string::npos) << all.substr(0, 800);
  // The runs' stored wall times are summed per figure: none for the sketches, some for fig6.
  EXPECT_NE(all.find("| its runs' CPU time, summed |"), std::string::npos);
  auto row_of = [&all](const std::string& figure) {
    const std::size_t at = all.find("| " + figure + " |");
    return at == std::string::npos ? std::string() : all.substr(at, all.find('\n', at) - at);
  };
  const std::string fig1 = row_of("fig1"), fig6 = row_of("fig6");
  ASSERT_GT(fig1.size(), 6u);
  EXPECT_EQ(fig1.substr(fig1.size() - 5), "| - |") << fig1;
  // fig6's last cell: "x.y s" (the smoke runs take well under two minutes), above zero.
  const std::size_t cell = fig6.rfind("| ", fig6.size() - 3);
  ASSERT_NE(cell, std::string::npos) << fig6;
  EXPECT_GT(std::stod(fig6.substr(cell + 2)), 0.0) << fig6;
  EXPECT_EQ(fig6.substr(fig6.size() - 4), " s |") << fig6;
  const std::string csv = slurp(dir_ / "figs/table1.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 8) << csv;
  EXPECT_EQ(csv.rfind("N,kT0,e_c1,e_c1_err,boundary_low,boundary_high,e_c2_low,e_c2_high,e_c2_sign,e_c2_sign_err,", 0), 0u) << csv;
  const CliResult again = run("reproduce --figure fig9 --preset smoke --out figs");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.err.find("already in reproduce.db, 0 to run"), std::string::npos) << again.err;
  // fig10's free-space counts are stored once and read back on a repeat, not recounted.
  const auto collapse_rows = query(dir_ / "reproduce.db", "SELECT count(*) FROM collapse_runs");
  EXPECT_GT(collapse_rows, 0);
  const CliResult fig10 = run("reproduce --figure fig10 --preset smoke --out figs");
  ASSERT_EQ(fig10.exit_code, 0) << fig10.err;
  EXPECT_EQ(fig10.err.find("launches"), std::string::npos) << fig10.err;
  EXPECT_EQ(query(dir_ / "reproduce.db", "SELECT count(*) FROM collapse_runs"), collapse_rows);
  EXPECT_EQ(all.find("limit-free"), std::string::npos);  // the group beyond is not part of all
}

// --stored-only runs nothing: it refuses a store that does not exist, draws a figure from the part
// of its runs that is stored (saying how many are missing), leaves the store as it was, and fails
// a figure none of whose runs is stored.
TEST_F(SweepCli, StoredOnlyDrawsFromWhatIsStoredAndRunsNothing) {
  const CliResult none = run("reproduce --figure fig8 --preset smoke --db s.db --out figs --stored-only");
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.err.find("--db: 's.db' does not exist; --stored-only"), std::string::npos) << none.err;
  EXPECT_FALSE(fs::exists(dir_ / "s.db"));
  ASSERT_EQ(run("reproduce --figure fig5 --preset smoke --db s.db --out figs -q").exit_code, 0);
  const auto stored = query(dir_ / "s.db", "SELECT count(*) FROM runs");
  // fig8 shares fig5's runs at the largest k except e = 0.91 and 0.92.
  const CliResult part = run("reproduce --figure fig8 --preset smoke --db s.db --out figs --stored-only");
  ASSERT_EQ(part.exit_code, 0) << part.err;
  EXPECT_NE(part.err.find("12 runs, 10 in s.db; --stored-only: drawn from those, 2 missing"), std::string::npos) << part.err;
  EXPECT_TRUE(fs::exists(dir_ / "figs/fig8.png"));
  const std::string fig8 = slurp(dir_ / "figs/report-fig8.md");
  EXPECT_NE(fig8.find("**Partial (--stored-only): drawn from the runs stored so far — "), std::string::npos);
  // Its Command: line repeats the command, --db, --stored-only and --out as given.
  EXPECT_NE(fig8.find("Command: `granchain reproduce --figure fig8 --preset smoke --db s.db --stored-only --out figs`."),
            std::string::npos) << fig8.substr(0, 400);
  EXPECT_EQ(query(dir_ / "s.db", "SELECT count(*) FROM runs"), stored);
  const CliResult empty = run("reproduce --figure fig3 --preset smoke --db s.db --out figs --stored-only");
  EXPECT_EQ(empty.exit_code, 2);
  EXPECT_NE(empty.err.find("fig3: none of its"), std::string::npos) << empty.err;
  EXPECT_EQ(query(dir_ / "s.db", "SELECT count(*) FROM runs"), stored);
}

// limit-free under --stored-only draws each series from the counts stored so far: with three of
// the four counts of one smoke series stored (by `collapse`, the same launches), it draws that
// series, names what each series lacks, leaves the store as it was, and with none exits 2.
TEST_F(SweepCli, StoredOnlyLimitFreeDrawsTheSeriesStoredSoFar) {
  ASSERT_EQ(run("collapse --N 10 --e 0.3 --k 1e4:1e6:x10 --realizations 10 --threads 2 --db s.db -q").exit_code, 0);
  const auto stored = query(dir_ / "s.db", "SELECT count(*) FROM collapse_runs");
  const CliResult part = run("reproduce --figure limit-free --preset smoke --db s.db --out figs --stored-only");
  ASSERT_EQ(part.exit_code, 0) << part.err;
  const std::string report = slurp(dir_ / "figs/report-limit-free.md");
  EXPECT_NE(report.find("limit-free (N = 10, e = 0.3): 3 of 4 counts"), std::string::npos) << report;
  EXPECT_NE(report.find("limit-free (N = 25, e = 0.5): 0 of 4 counts"), std::string::npos) << report;
  EXPECT_NE(report.find("Fewer than two of its counts are stored (--stored-only): not drawn."), std::string::npos);
  EXPECT_NE(report.find("| 1e6 | "), std::string::npos);
  EXPECT_TRUE(fs::exists(dir_ / "figs/limit-free.png"));
  EXPECT_EQ(query(dir_ / "s.db", "SELECT count(*) FROM collapse_runs"), stored);
  ASSERT_EQ(run("run --N 5 --e 0.9 --k 1e4 --T 1 --db t.db -q").exit_code, 0);  // a store without counts
  const CliResult none = run("reproduce --figure limit-free --preset smoke --db t.db --out figs2 --stored-only");
  EXPECT_EQ(none.exit_code, 2) << none.err;
}

// --k-min re-reads the same runs over another window of k: the report names it and runs nothing
// more; a window leaving fewer than three k of the preset's grid is refused (exit 2, nothing written).
TEST_F(SweepCli, KMinReReadsTheStoredRunsOverAnotherWindow) {
  ASSERT_EQ(run("reproduce --figure fig5 --preset smoke --db s.db --out figs -q").exit_code, 0);
  EXPECT_NE(slurp(dir_ / "figs/report.md").find("fits over k >= 1e4"), std::string::npos);
  const auto stored = query(dir_ / "s.db", "SELECT count(*) FROM runs");
  const CliResult wider = run("reproduce --figure fig5 --preset smoke --db s.db --out wide --k-min 1e3 --stored-only");
  ASSERT_EQ(wider.exit_code, 0) << wider.err;
  EXPECT_NE(slurp(dir_ / "wide/report.md").find("fits over k >= 1e3"), std::string::npos);
  EXPECT_EQ(query(dir_ / "s.db", "SELECT count(*) FROM runs"), stored);
  const CliResult narrow = run("reproduce --figure fig5 --preset smoke --db s.db --out narrow --k-min 1e5");
  EXPECT_EQ(narrow.exit_code, 2);
  EXPECT_NE(narrow.err.find("--k-min = 100000 is out of range; valid range: 0 < k-min <= 1e4"), std::string::npos) << narrow.err;
  EXPECT_FALSE(fs::exists(dir_ / "narrow"));
}

// --time-limit: points whose estimate alone exceeds the limit are refused before the store is
// created (exit 2); points that fit one by one but not all together leave the rest for a repeat
// (exit 75), which runs them; reproduce refuses likewise before running anything; a bad duration
// is refused.
TEST_F(SweepCli, ATimeLimitLeavesWhatCannotEndInItForARepeat) {
  const CliResult longer = run("sweep --N 150 --e 0.5 --k 1e10 --T 1e4 --db t.db --time-limit 60 -q");
  EXPECT_EQ(longer.exit_code, 2) << longer.err;
  EXPECT_NE(longer.err.find("--time-limit = 60 s is shorter than the estimated run of 1 point"), std::string::npos) << longer.err;
  EXPECT_FALSE(fs::exists(dir_ / "t.db"));
  // 30 points of N = 25 estimated at a fraction of a second each (k = 1e6, T = 100), on one thread
  // with a limit of 2 s: a few run, the rest are left (the estimate is within a factor of 2, and the
  // ratio measured on the finished ones is held at 0.25 or more, so 30 cannot all fit).
  const std::string grid = "sweep --N 25 --e 0.5 --k 1e6 --T 100 --replicas 30 --threads 1 --db t.db -q";
  const CliResult some = run(grid + " --time-limit 2");
  EXPECT_EQ(some.exit_code, 75) << some.err;
  EXPECT_NE(some.err.find("points not started"), std::string::npos) << some.err;
  const auto first = query(dir_ / "t.db", "SELECT count(*) FROM runs");
  EXPECT_GT(first, 0);
  EXPECT_LT(first, 30);
  const CliResult rest = run(grid + " --time-limit 1h");
  EXPECT_EQ(rest.exit_code, 0) << rest.err;
  EXPECT_EQ(query(dir_ / "t.db", "SELECT count(*) FROM runs"), 30);
  const CliResult figure = run("reproduce --figure fig5 --preset paper --db t.db --out figs --time-limit 60 -q");
  EXPECT_EQ(figure.exit_code, 2) << figure.err;
  EXPECT_NE(figure.err.find("fig5: --time-limit = 60 s is shorter"), std::string::npos) << figure.err;
  EXPECT_FALSE(fs::exists(dir_ / "figs/report.md"));
  const CliResult bad = run("sweep --N 3 --T 20 --db t.db --time-limit 2x");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--time-limit = '2x' is not a duration"), std::string::npos) << bad.err;
}

// The group beyond on tiny grids: its four figures and reports exist, the forms are compared
// where four k are fitted, the hard-sphere launches collapse, the hard column collapses below its
// threshold and runs above it, and a repeat reuses every stored count, run and collapse.
TEST_F(SweepCli, SmokePresetDrawsTheGroupBeyond) {
  const CliResult r = run("reproduce --figure beyond --preset smoke --out figs -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"limit-free.png", "limit-free.pdf", "limit-driven.png", "intervals.png", "limit-hard.png", "report-limit-free.md",
                        "report-limit-driven.md", "report-intervals.md", "report-limit-hard.md", "report-beyond.md"})
    EXPECT_TRUE(fs::exists(dir_ / "figs" / f)) << f;
  const std::string beyond = slurp(dir_ / "figs/report-beyond.md");
  for (const char* s : {"| limit-free |", "| limit-driven |", "| intervals |", "| limit-hard |", "Local exponent:", "Verdict:",
                        "### Hard spheres, e = 0.3: 20 of 20 launches collapse", "collapse events per launch",
                        "N = 10, initial state: every replica collapses at e ≤ 0.5, none at e ≥ 0.6",
                        "N = 10, soft start (k = 1e8): every replica collapses at e ≤ 0.5, none at e ≥ 0.6"})
    EXPECT_NE(beyond.find(s), std::string::npos) << s;
  EXPECT_EQ(beyond.find("failed"), std::string::npos) << beyond.substr(0, 800);
  const auto counts = query(dir_ / "reproduce.db", "SELECT count(*) FROM collapse_runs");
  EXPECT_EQ(counts, 4 * 4);  // N = 10, 25 x e = 0.3, 0.5 x k = 1e4 ... 1e7
  const CliResult again = run("reproduce --figure limit-driven --preset smoke --out figs");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.err.find("0 to run"), std::string::npos) << again.err;
  // The hard spheres' collapses are stored outcomes: a repeat runs nothing.
  EXPECT_EQ(query(dir_ / "reproduce.db", "SELECT count(*) FROM collapsed_points"), 4);
  const CliResult hard = run("reproduce --figure limit-hard --preset smoke --out figs");
  ASSERT_EQ(hard.exit_code, 0) << hard.err;
  EXPECT_NE(hard.err.find("0 to run"), std::string::npos) << hard.err;
  ASSERT_EQ(run("reproduce --figure limit-free --preset smoke --out figs -q").exit_code, 0);
  EXPECT_EQ(query(dir_ / "reproduce.db", "SELECT count(*) FROM collapse_runs"), counts);
}

// The group columns: the contacts figure runs its two replicas per point, reports every choice of e
// and every N, and a repeat (and --stored-only) runs nothing.
TEST_F(SweepCli, SmokePresetDrawsTheGroupColumns) {
  const CliResult r = run("reproduce --figure columns --preset smoke --out figs -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"contacts.png", "contacts.pdf", "contacts.json", "report-contacts.md", "report-columns.md"})
    EXPECT_TRUE(fs::exists(dir_ / "figs" / f)) << f;
  const std::string report = slurp(dir_ / "figs/report-contacts.md");
  for (const char* s : {"### N(1 − e) = 2", "### N(1 − e) = 5", "### e = 0.3", "| 10 | 0.8 | 1e4 |", "| 25 | 0.3 | 1e4 |",
                        "12 of 12 runs stored"})
    EXPECT_NE(report.find(s), std::string::npos) << s;
  EXPECT_EQ(query(dir_ / "reproduce.db", "SELECT count(*) FROM runs"), 12);
  const CliResult again = run("reproduce --figure contacts --preset smoke --out figs");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.err.find("0 to run"), std::string::npos) << again.err;
  ASSERT_EQ(run("reproduce --figure contacts --preset smoke --stored-only --out figs2 -q").exit_code, 0);
  EXPECT_EQ(slurp(dir_ / "figs2/report-contacts.md").find("Partial"), std::string::npos);
}

// `granchain analyze` on a store of runs whose n_coll(k) follow known laws: a power law
// (e = 0.3), a logarithm (e = 0.86) and a converging curve (e = 0.95); it names each regime and
// finds e_c2 between 0.3 and 0.86.
TEST_F(SweepCli, AnalyzeClassifiesStoredCurves) {
  {
    granchain::ResultsStore store((dir_ / "a.db").string());
    for (double e : {0.3, 0.86, 0.95})
      for (double k = 1e5; k <= 1e10; k *= 10) {
        granchain::RunResult r;
        r.spec.params.N = 25;
        r.spec.params.e = e;
        r.spec.params.k = k;
        r.spec.T = 100;
        r.spec.seed = static_cast<std::uint64_t>(std::log10(k));
        const double x = std::log10(k);
        r.n_coll.value = e == 0.3 ? 2.0 * std::pow(k, 0.2) : e == 0.86 ? 20.0 + x : 11.0 - 300.0 / std::sqrt(k);
        r.n_coll.error = 0.01;
        // One run whose window failed its stationarity check: the analysis flags it.
        if (e == 0.95 && k == 1e10) r.n_coll_halves.stationary = false;
        store.insert_run(r);
      }
  }
  const CliResult flagged = run("analyze --db a.db");
  EXPECT_NE(flagged.out.find("[!] window not stationary"), std::string::npos) << flagged.out;
  EXPECT_NE(flagged.out.find("(e = 0.95, k = 1e+10)"), std::string::npos) << flagged.out;
  const CliResult r = run("analyze --db a.db --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["families"].size(), 1u);
  const auto& curves = j["families"][0]["curves"];
  ASSERT_EQ(curves.size(), 3u);
  EXPECT_EQ(curves[0]["regime"], "power-law");
  EXPECT_NEAR(curves[0]["power_fit"]["alpha"].get<double>(), 0.2, 4 * curves[0]["power_fit"]["alpha_err"].get<double>());
  EXPECT_EQ(curves[1]["regime"], "logarithmic");
  EXPECT_NEAR(curves[1]["log_fit"]["b"].get<double>(), 1.0, 4 * curves[1]["log_fit"]["b_err"].get<double>());
  EXPECT_EQ(curves[2]["regime"], "uncollapsing");
  EXPECT_TRUE(curves[0]["non_stationary_k"].empty());
  ASSERT_EQ(curves[2]["non_stationary_k"].size(), 1u);
  EXPECT_EQ(curves[2]["non_stationary_k"][0].get<double>(), 1e10);
  EXPECT_EQ(j["families"][0]["e_c2"]["low"], 0.3);
  EXPECT_EQ(j["families"][0]["e_c2"]["high"], 0.86);
  const CliResult text = run("analyze --db a.db --plot fig");
  EXPECT_NE(text.out.find("power-law"), std::string::npos) << text.out;
  EXPECT_TRUE(fs::exists(dir_ / "fig_N25_T01_exact.png") && fs::exists(dir_ / "fig_N25_T01_exact.pdf")) << text.out << text.err;
  // --k chooses a window of k: only its values enter every curve (the stationarity flag of k = 1e10
  // goes with it); four k still tell a power law, two k classify nothing.
  const CliResult window = run("analyze --db a.db --k 1e5:1e8:x10 --json");
  ASSERT_EQ(window.exit_code, 0) << window.err;
  const auto w = nlohmann::json::parse(window.out)["families"][0]["curves"];
  ASSERT_EQ(w.size(), 3u);
  for (const auto& c : w) EXPECT_EQ(c["n_coll_of_k"].size(), 4u) << c["e"];
  EXPECT_EQ(w[0]["regime"], "power-law");
  EXPECT_NEAR(w[0]["power_fit"]["alpha"].get<double>(), 0.2, 4 * w[0]["power_fit"]["alpha_err"].get<double>());
  EXPECT_TRUE(w[2]["non_stationary_k"].empty());
  const auto two = nlohmann::json::parse(run("analyze --db a.db --k 1e9,1e10 --json").out)["families"][0]["curves"];
  ASSERT_EQ(two.size(), 3u);
  EXPECT_FALSE(two[0]["classified"].get<bool>());
  // --T selects by window length: every run of this store has T = 100.
  EXPECT_EQ(nlohmann::json::parse(run("analyze --db a.db --T 100 --json").out)["families"], j["families"]);
  EXPECT_EQ(run("analyze --db a.db --T 200").out.rfind("0 runs", 0), 0u);
  EXPECT_EQ(run("analyze --db a.db --k 1e5:1e3").exit_code, 2);
  EXPECT_EQ(run("analyze --db missing.db").exit_code, 2);
  EXPECT_EQ(run("analyze --db a.db --k-min -1").exit_code, 2);
}

// `granchain trace` follows the very trajectory of `granchain run` with the same seed: over the
// run's whole time it reports as many contact ends and floor hits as the run counted; no two
// particles ever overlap by more than a contact can (d/10 at this k); and it draws the diagram.
TEST_F(SweepCli, TraceFollowsTheRunsTrajectoryAndDrawsIt) {
  const CliResult runj = run("run --N 4 --e 0.8 --k 1e4 --T 20 --transient 2 --seed 3 --no-db --json");
  ASSERT_EQ(runj.exit_code, 0) << runj.err;
  const auto events = nlohmann::json::parse(runj.out)["cost"]["events"].get<long>();
  const CliResult tr = run("trace --N 4 --e 0.8 --k 1e4 --seed 3 --from 0 --to 22 --dt 0.01 --output t.csv --events ev.csv --plot t.png");
  ASSERT_EQ(tr.exit_code, 0) << tr.err;
  std::istringstream ev(slurp(dir_ / "ev.csv"));
  long ends = 0;
  for (std::string line; std::getline(ev, line);) ends += line.find("contact_end") != std::string::npos || line.find("floor_hit") != std::string::npos;
  EXPECT_EQ(ends, events);
  std::istringstream csv(slurp(dir_ / "t.csv"));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "t,z1,z2,z3,z4");
  int rows = 0;
  double worst = 1e9;
  while (std::getline(csv, line)) {
    ++rows;
    std::vector<double> v;
    std::istringstream r(line);
    for (std::string c; std::getline(r, c, ',');) v.push_back(std::stod(c));
    worst = std::min(worst, v[1] - 0.5);  // particle 1 above the floor, up to its overlap
    for (int i = 1; i < 4; ++i) worst = std::min(worst, v[i + 1] - v[i] - 1.0);
  }
  EXPECT_EQ(rows, 2201);
  EXPECT_GT(worst, -0.1);
  EXPECT_TRUE(fs::exists(dir_ / "t.png") && fs::exists(dir_ / "t.pdf"));
  EXPECT_EQ(run("trace --from 2 --to 1").exit_code, 2);
  EXPECT_EQ(run("trace --engine hard").exit_code, 2);
  EXPECT_EQ(run("trace --setup moon").exit_code, 2);
}

// Hard spheres that collapse at a point are that point's outcome: kept in collapsed_points (no run,
// no n_coll), not run again by a repeated sweep, still reported with exit 3; merged with the runs,
// and a collapse against a run of the same identity is a conflict.
TEST_F(SweepCli, HardSphereCollapsesAreStoredAsOutcomesAndNotRunAgain) {
  // N = 25 on the thermal floor: e = 0.6 collapses in the first fall, e = 0.9 runs (docs/beyond.md §6).
  const std::string grid = "sweep --engine hard --N 25 --e 0.6,0.9 --T 20 --replicas 2 -q --db hard.db";
  const CliResult first = run(grid);
  EXPECT_EQ(first.exit_code, 3) << first.err;
  EXPECT_NE(first.err.find("hard spheres collapsed, kept as a collapse (no n_coll)"), std::string::npos) << first.err;
  EXPECT_EQ(query(dir_ / "hard.db", "SELECT count(*) FROM runs"), 2);
  EXPECT_EQ(query(dir_ / "hard.db", "SELECT count(*) FROM collapsed_points WHERE point_key LIKE '% e=0.6 %' AND t > 0 AND t < 20 "
                                    "AND collisions >= 1000 AND first_particle >= 1 AND last_particle <= 25"),
            2);
  const CliResult again = run(grid);
  EXPECT_EQ(again.exit_code, 3) << again.err;
  EXPECT_NE(again.err.find("kept in hard.db as a collapse"), std::string::npos) << again.err;
  EXPECT_EQ(std::count(again.err.begin(), again.err.end(), '\n'), 2) << again.err;
  EXPECT_EQ(query(dir_ / "hard.db", "SELECT count(*) FROM collapsed_points"), 2);
  const CliResult dry = run("sweep --engine hard --N 25 --e 0.6,0.9 --T 20 --replicas 2 --db hard.db --dry-run");
  EXPECT_EQ(dry.exit_code, 0) << dry.err;
  std::size_t marked = 0;
  for (std::size_t at = dry.out.find("(stored: collapsed)"); at != std::string::npos; at = dry.out.find("(stored: collapsed)", at + 1)) ++marked;
  EXPECT_EQ(marked, 2u) << dry.out;

#if defined(GRANCHAIN_WITH_MPI) && defined(GRANCHAIN_MPIEXEC)
  // Over MPI ranks the collapse crosses from a rank to rank 0 and is stored the same.
  const std::string mpi = std::string("env OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 '") + GRANCHAIN_MPIEXEC +
                          "' --oversubscribe -np 3 '" + GRANCHAIN_BINARY + "' sweep --engine hard --N 25 --e 0.6,0.9 --T 20 "
                          "--replicas 2 -q --threads 1 --db mpi.db";
  const int rc = std::system(("cd '" + dir_.string() + "' && " + mpi + " > mpi.txt 2>&1").c_str());
  EXPECT_EQ(WEXITSTATUS(rc), 3) << slurp(dir_ / "mpi.txt");
  const auto collapses = [&](const char* store) {
    return query(dir_ / store, "SELECT count(*) * 1000000000 + CAST(sum(t) * 1e6 AS INTEGER) + sum(collisions) FROM collapsed_points");
  };
  EXPECT_EQ(collapses("mpi.db"), collapses("hard.db"));
  EXPECT_EQ(query(dir_ / "mpi.db", "SELECT count(*) FROM runs"), 2);
#endif
  const CliResult merged = run("merge --into all.db hard.db");
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  EXPECT_NE(merged.out.find("2 collapsed hard-sphere points added, 0 already there"), std::string::npos) << merged.out;
  EXPECT_EQ(query(dir_ / "all.db", "SELECT count(*) FROM collapsed_points"), 2);
  const CliResult twice = run("merge --into all.db hard.db");
  EXPECT_NE(twice.out.find("0 collapsed hard-sphere points added, 2 already there"), std::string::npos) << twice.out;
  // The same identity stored as a run in the target and as a collapse in the source.
  sqlite3* db = nullptr;
  sqlite3_open((dir_ / "hard.db").c_str(), &db);
  sqlite3_exec(db, "UPDATE collapsed_points SET point_key = (SELECT point_key FROM run_points LIMIT 1) WHERE rowid = "
                   "(SELECT min(rowid) FROM collapsed_points)",
               nullptr, nullptr, nullptr);
  sqlite3_close(db);
  const CliResult conflict = run("merge --into all.db hard.db");
  EXPECT_EQ(conflict.exit_code, 2) << conflict.err;
  EXPECT_NE(conflict.err.find("and a collapse at t ="), std::string::npos) << conflict.err;
  // The other way round: a run in the source whose key the target holds as a collapse.
  ASSERT_EQ(run(grid.substr(0, grid.find(" --db")) + " --db run.db").exit_code, 3);
  sqlite3_open((dir_ / "run.db").c_str(), &db);
  sqlite3_exec(db, "DELETE FROM collapsed_points; UPDATE run_points SET point_key = 'k' || point_key;", nullptr, nullptr, nullptr);
  const std::string attach = "ATTACH DATABASE '" + (dir_ / "all.db").string() +
                             "' AS a; UPDATE run_points SET point_key = (SELECT min(point_key) FROM a.collapsed_points) "
                             "WHERE rowid = (SELECT min(rowid) FROM run_points);";
  ASSERT_EQ(sqlite3_exec(db, attach.c_str(), nullptr, nullptr, nullptr), SQLITE_OK) << sqlite3_errmsg(db);
  sqlite3_close(db);
  const CliResult reverse = run("merge --into all.db run.db");
  EXPECT_EQ(reverse.exit_code, 2) << reverse.err;
  EXPECT_NE(reverse.err.find(": a collapse at t ="), std::string::npos) << reverse.err;
}

// The large preset: the paper's across-N sweep extended to N = 1000 and, for N >= 100, to c = 10,
// with four replicas on the condensed side; --print-sweeps runs nothing and predicts the cost; a bad preset is refused.
TEST_F(SweepCli, LargePresetExtendsTheAcrossNSweepWithReplicas) {
  const CliResult r = run("reproduce --figure fig6 --preset large --print-sweeps --db l.db");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("granchain sweep --N 1000 --e 0.99,0.992,0.993,0.994,0.995,"), std::string::npos) << r.out;
  // e_c2's side beyond c = N (1 - e) = 5: c = 10, 8, 7, 6 single at N = 100, with replicas at N >= 200
  EXPECT_NE(r.out.find("granchain sweep --N 100 --e 0.9,0.92,0.93,0.94,0.95,0.96,"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("granchain sweep --N 200 --e 0.95,0.96,0.965,0.97,0.975,"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("granchain sweep --N 150 --e 0.1,0.2,0.3,0.4 --k 1e5:1e10:x10 --T 1e3 --T0 1 --replicas 4"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("granchain sweep --N 20 --e"), std::string::npos) << r.out;  // the paper's columns stay
  EXPECT_NE(r.out.find("2424 distinct points"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir_ / "l.db"));
  const CliResult bad = run("reproduce --figure fig6 --preset huge --db l.db");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("valid: quick, paper, large, smoke"), std::string::npos) << bad.err;
}
