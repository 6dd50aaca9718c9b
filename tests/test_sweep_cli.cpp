// `granchain sweep`, `merge`, `export` and `analyze` as a user meets them: a 200-point sweep killed with
// kill -9 and resumed, identical numbers on 1 thread, 2 threads and 2 MPI ranks, job-array shards
// merged back, CSV export, the analysis of stored curves, trace, hard-sphere collapses stored as
// outcomes, and bad input.
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
#include "analysis/blocking.hpp"
#include "store/results_store.hpp"

namespace {

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

// The replica check of `granchain analyze` compares the runs the analysis keeps: at k = 1e5, three
// windows after a transient of 2 that two of them fail (scattered far beyond their errors) are
// superseded by three settled ones after 50, and only those enter the check (3 runs, chi^2 small).
TEST_F(SweepCli, AnalyzeChecksBlockingOnTheRunsItKeeps) {
  {
    granchain::ResultsStore store((dir_ / "r.db").string());
    std::uint64_t seed = 0;
    const auto add = [&](double k, double n, double transient, bool settled) {
      granchain::RunResult r;
      r.spec.params.N = 25;
      r.spec.params.e = 0.3;
      r.spec.params.k = k;
      r.spec.T = 100;
      r.spec.transient = transient;
      r.spec.seed = ++seed;
      r.n_coll.value = n;
      r.n_coll.error = 0.1;
      r.n_coll_blocking = {{64, 0.1, 0.0}, {32, 0.1, 0.0}, {16, 0.1, 0.0}};
      if (!settled) r.n_coll_halves = granchain::judge_halves({n - 1.0, 0.1}, {n, 0.1});
      store.insert_run(r);
    };
    for (double n : {14.0, 20.0}) add(1e5, n, 2, false);
    add(1e5, 17.0, 2, true);
    for (double n : {10.0, 10.1, 9.9}) add(1e5, n, 50, true);
    for (double k : {1e6, 1e7, 1e8}) add(k, 10.0 + std::log10(k), 10, true);
  }
  const CliResult r = run("analyze --db r.db --k-min 1e5 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["families"].size(), 1u);
  const auto& checks = j["families"][0]["blocking_check"];
  ASSERT_EQ(checks.size(), 1u) << checks.dump();
  EXPECT_EQ(checks[0]["k"].get<double>(), 1e5);
  EXPECT_EQ(checks[0]["runs"].get<int>(), 3);
  EXPECT_NEAR(checks[0]["chi2_reported"].get<double>(), 2.0, 1e-9);  // (0.1^2 + 0.1^2) / 0.1^2
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
        // (halves 7 errors apart: a stored run is judged again from its halves)
        if (e == 0.95 && k == 1e10) r.n_coll_halves = granchain::judge_halves({10.0, 0.1}, {11.0, 0.1});
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
