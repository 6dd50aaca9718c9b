// Every trajectory counted once. A run is a deterministic function of its parameters and seed:
// the same command run twice must not become a second sample, and the analysis must not treat
// two rows of one trajectory (a store written before this rule, or runs of one seed with other
// windows) as independent replicas. A run it cannot use is named with the reason.
#include <nlohmann/json.hpp>

#include "cli_fixture.hpp"

namespace {

std::int64_t count_runs(const fs::path& db_path) { return query(db_path, "SELECT count(*) FROM runs"); }

void exec(const fs::path& db_path, const std::string& sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(db_path.c_str(), &db), SQLITE_OK);
  char* err = nullptr;
  const int rc = sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &err);
  const std::string msg = err ? err : "";
  sqlite3_free(err);
  sqlite3_close(db);
  ASSERT_EQ(rc, SQLITE_OK) << msg;
}

// A copy of every run (and its profiles) as a second row without a point key: what a store got
// from a repeated `run` before a run's identity was checked.
void duplicate_every_run(const fs::path& db_path) {
  exec(db_path,
       "CREATE TEMP TABLE copies AS SELECT * FROM runs;"
       "UPDATE copies SET id = id + 1000;"
       "INSERT INTO runs SELECT * FROM copies;"
       "INSERT INTO profiles SELECT run_id + 1000, i, z_mean, z_mean_err, z_std, z_std_err, K, K_err FROM profiles;");
}

class CountedOnce : public Cli {};

}  // namespace

// The same run twice: the second is read back from the store (one line says so), not run or
// stored again, and gives the same numbers; another seed is another run.
TEST_F(CountedOnce, ARepeatedRunIsReadBackNotStoredTwice) {
  const std::string args = "run --N 3 --e 0.5 --k 1e5 --T 20 --db d.db --json";
  const CliResult first = run(args);
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const CliResult again = run(args);
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.err.find("run 1 of d.db is this run already"), std::string::npos) << again.err;
  EXPECT_NE(again.err.find("give another --seed"), std::string::npos) << again.err;
  EXPECT_EQ(count_runs(dir_ / "d.db"), 1);
  const auto a = nlohmann::json::parse(first.out), b = nlohmann::json::parse(again.out);
  EXPECT_EQ(a["observables"], b["observables"]);
  EXPECT_EQ(b["stored"]["run_id"], 1);
  EXPECT_EQ(b["reused"], true);
  const CliResult summary = run("run --N 3 --e 0.5 --k 1e5 --T 20 --db d.db");
  EXPECT_NE(summary.out.find("stored before and read back"), std::string::npos) << summary.out;
  // An audit asks for the run itself: it runs (and audits), and is not stored a second time.
  const CliResult audited = run("run --N 3 --e 0.5 --k 1e5 --T 20 --db d.db --audit");
  EXPECT_NE(audited.out.find("audit:"), std::string::npos) << audited.out;
  EXPECT_EQ(count_runs(dir_ / "d.db"), 1);
  ASSERT_EQ(run("run --N 3 --e 0.5 --k 1e5 --T 20 --db d.db --seed 2 -q").exit_code, 0);
  EXPECT_EQ(count_runs(dir_ / "d.db"), 2);
}

// Two rows of one trajectory in a store: analyze keeps one, names the other with the reason, and
// its errors and replica check are those of the single runs (a copy would shrink every error by
// sqrt 2 and give chi2 = 0).
TEST_F(CountedOnce, AnalysisCountsOneTrajectoryOnce) {
  ASSERT_EQ(run("sweep --N 5 --e 0.5 --k 1e4,1e5,1e6 --T 200 --db d.db -q").exit_code, 0);
  const CliResult single = run("analyze --db d.db --json");
  ASSERT_EQ(single.exit_code, 0) << single.err;
  duplicate_every_run(dir_ / "d.db");
  ASSERT_EQ(count_runs(dir_ / "d.db"), 6);
  const CliResult doubled = run("analyze --db d.db --json");
  ASSERT_EQ(doubled.exit_code, 0) << doubled.err;
  const auto s = nlohmann::json::parse(single.out), d = nlohmann::json::parse(doubled.out);
  EXPECT_EQ(s["families"][0]["curves"], d["families"][0]["curves"]);
  EXPECT_TRUE(d["families"][0]["replica_check"].is_null()) << "copies were taken for replicas";
  ASSERT_EQ(d["excluded"].size(), 3u);
  for (const auto& x : d["excluded"]) {
    EXPECT_GT(x["run_id"].get<int>(), 1000);
    EXPECT_NE(x["reason"].get<std::string>().find("the same trajectory as run"), std::string::npos) << x;
  }
  const CliResult text = run("analyze --db d.db");
  EXPECT_NE(text.out.find("left out of the analysis: 3 runs"), std::string::npos) << text.out;

  // The same seed with a longer window is the same trajectory continued: the longer run is kept.
  ASSERT_EQ(run("run --N 5 --e 0.5 --k 1e4 --T 400 --seed 7 --db e.db -q").exit_code, 0);
  ASSERT_EQ(run("run --N 5 --e 0.5 --k 1e4 --T 200 --seed 7 --db e.db -q").exit_code, 0);
  const auto e = nlohmann::json::parse(run("analyze --db e.db --json").out);
  ASSERT_EQ(e["excluded"].size(), 1u);
  EXPECT_EQ(e["excluded"][0]["run_id"], 2);
  EXPECT_NE(e["excluded"][0]["reason"].get<std::string>().find("a shorter window"), std::string::npos);
}

// Runs without an error (no collision in a short window) are named with the reason, in the text
// and the JSON, instead of vanishing from the fits.
TEST_F(CountedOnce, RunsWithoutAnErrorAreNamed) {
  ASSERT_EQ(run("sweep --N 3 --e 0.5 --k 1e4,1e5,1e6 --T 50 --db d.db -q").exit_code, 0);
  exec(dir_ / "d.db", "UPDATE runs SET n_coll = 0, n_coll_err = 0 WHERE k = 100000");
  const CliResult r = run("analyze --db d.db --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["excluded"].size(), 1u);
  EXPECT_EQ(j["excluded"][0]["k"], 1e5);
  EXPECT_NE(j["excluded"][0]["reason"].get<std::string>().find("no positive error"), std::string::npos);
  EXPECT_EQ(j["families"][0]["curves"][0]["n_coll_of_k"].size(), 2u);
  const CliResult text = run("analyze --db d.db");
  EXPECT_NE(text.out.find("k = 100000: run "), std::string::npos) << text.out;
  EXPECT_NE(text.out.find(": n_coll = 0 has no positive error"), std::string::npos) << text.out;
}

// A merge whose source holds a run of the same identity but other profiles is a conflict: the
// profiles are compared, not only the scalar results.
TEST_F(CountedOnce, MergeComparesProfilesToo) {
  ASSERT_EQ(run("run --N 3 --T 20 --db a.db -q").exit_code, 0);
  fs::copy_file(dir_ / "a.db", dir_ / "b.db");
  exec(dir_ / "b.db", "UPDATE profiles SET K = K * 1.01 WHERE i = 2");
  const CliResult r = run("merge --into a.db b.db");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("profile of particle 2, K:"), std::string::npos) << r.err;
  EXPECT_EQ(count_runs(dir_ / "a.db"), 1);
}

// Two runs of one point with other seeds but results identical to the last bit are not two
// samples (zero scatter): the second is named and left out.
TEST_F(CountedOnce, ZeroScatterIsNotTwoSamples) {
  ASSERT_EQ(run("sweep --N 3 --e 0.5 --k 1e4,1e5,1e6 --T 50 --replicas 2 --db d.db -q").exit_code, 0);
  exec(dir_ / "d.db",
       "UPDATE runs SET n_coll = (SELECT n_coll FROM runs r2 WHERE r2.k = runs.k ORDER BY id LIMIT 1), "
       "n_coll_err = (SELECT n_coll_err FROM runs r2 WHERE r2.k = runs.k ORDER BY id LIMIT 1) WHERE k = 1000000");
  const auto j = nlohmann::json::parse(run("analyze --db d.db --json").out);
  ASSERT_EQ(j["excluded"].size(), 1u);
  EXPECT_EQ(j["excluded"][0]["k"], 1e6);
  EXPECT_NE(j["excluded"][0]["reason"].get<std::string>().find("zero scatter"), std::string::npos);
  EXPECT_EQ(j["families"][0]["replica_check"]["points"], 2);  // k = 1e4 and 1e5 keep their two replicas
}
