// The command line as a user meets it: bad input, outputs, config files, failures.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_fixture.hpp"

namespace fs = std::filesystem;

namespace {

const std::string kQuick = "run --N 4 --k 1e4 --e 0.8 --T 20 --transient 2 ";

}  // namespace

TEST_F(Cli, BadInputIsOneLineExitTwoNothingWritten) {
  write("bad.json", "{\"N\": 5, \"e\": ");
  write("unknown.toml", "N = 5\nfoo = 3\n");
  write("range.toml", "# comment\ne = 2.0\n");
  write("section.toml", "[run]\nN = 5\n");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--e 0", "--e"},           {"--e 1.5", "--e"},           {"--e -0.2", "--e"},
      {"--k 0", "--k"},           {"--k -3", "--k"},            {"--k nan", "--k"},
      {"--e inf", "--e"},         {"--N 0", "--N"},             {"--N 2.5", "--N"},
      {"--T 0", "--T"},           {"--T -1", "--T"},            {"--transient -1", "--transient"},
      {"--T0 0", "--T0"},         {"--engine warp", "--engine"}, {"--seed -4", "--seed"},
      {"--dt-factor 1", "--dt-factor"}, {"--bins 100", "--bins"}, {"--bogus 1", "--bogus"},
      {"--config missing.json", "--config"}, {"--config bad.json", "--config"},
      {"--config unknown.toml", "foo"},      {"--config range.toml", "--e"},
      {"--config section.toml", "--config"}, {"--db nowhere/x.db", "--db"},
      {"--json nowhere/x.json", "--json"},   {"--k 1e4x", "--k"},
  };
  const std::size_t before = files();
  for (const auto& [args, name] : cases) {
    // Nothing but the case's own flags: bad input must be refused before anything runs.
    const CliResult r = run("run " + args + " --json out.json");
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_TRUE(r.out.empty()) << args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
    EXPECT_NE(r.err.find(name), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(files(), before) << args << " wrote a file";
  }
  // The range is named for a value out of range.
  EXPECT_NE(run("run --e 1.5").err.find("0 < e <= 1"), std::string::npos);
  EXPECT_NE(run("run --config range.toml").err.find("config file"), std::string::npos);
  // A flag given twice: the last one counts, as in most HPC tools.
  const CliResult twice = run(kQuick + "--e 1.5 --e 0.5 --json --no-db");
  ASSERT_EQ(twice.exit_code, 0) << twice.err;
  EXPECT_EQ(nlohmann::json::parse(twice.out)["parameters"]["e"], 0.5);
}

TEST_F(Cli, RunWritesSummaryJsonAndOneStoreRow) {
  const CliResult r = run(kQuick + "--json out.json --db my.db");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("n_coll"), std::string::npos);
  EXPECT_NE(r.out.find("stored: run 1 in my.db"), std::string::npos);
  const auto j = nlohmann::json::parse(slurp(dir_ / "out.json"));
  EXPECT_EQ(j["parameters"]["N"], 4);
  EXPECT_GT(j["observables"]["n_coll"]["value"].get<double>(), 0.0);
  EXPECT_EQ(j["profiles"].size(), 4u);
  EXPECT_EQ(j["stored"]["run_id"], 1);
  const std::string count = "sqlite3 '" + (dir_ / "my.db").string() + "' 'SELECT count(*) FROM runs' > n.txt";
  ASSERT_EQ(std::system(("cd '" + dir_.string() + "' && " + count).c_str()), 0);
  EXPECT_EQ(slurp(dir_ / "n.txt"), "1\n");
  // JSON to standard output, nothing else there.
  const CliResult s = run(kQuick + "--json --no-db");
  ASSERT_EQ(s.exit_code, 0) << s.err;
  EXPECT_EQ(nlohmann::json::parse(s.out)["parameters"]["e"], 0.8);
}

// Flags, a JSON file and a TOML file that say the same thing give the same run bit for bit;
// a flag overrides the file.
TEST_F(Cli, ConfigFilesEqualFlagsAndFlagsOverride) {
  write("p.json", "{\"N\": 4, \"k\": 1e4, \"e\": 0.8, \"T\": 20, \"transient\": 2, \"seed\": 5}");
  write("p.toml", "N = 4\nk = 1e4   # stiffness\ne = 0.8\nT = 20\ntransient = 2\nseed = 5\nengine = \"exact\"\n");
  auto physics = [](const std::string& text) {
    auto j = nlohmann::json::parse(text);
    return j["observables"].dump() + j["profiles"].dump() + j["parameters"].dump();
  };
  const CliResult a = run(kQuick + "--seed 5 --json --no-db");
  const CliResult b = run("run --config p.json --json --no-db");
  const CliResult c = run("run --config p.toml --json --no-db");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_EQ(physics(a.out), physics(b.out));
  EXPECT_EQ(physics(a.out), physics(c.out));
  const CliResult d = run("run --config p.toml --e 0.5 --json --no-db");
  ASSERT_EQ(d.exit_code, 0) << d.err;
  EXPECT_EQ(nlohmann::json::parse(d.out)["parameters"]["e"], 0.5);
}

// Springs too soft for the weight: the run stops with exit code 3, names time and particles,
// prints no result and writes nothing.
TEST_F(Cli, UnphysicalRunStopsWithoutResult) {
  const CliResult r = run("run --N 20 --k 1 --e 0.5 --T 100 --json out.json --db my.db");
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_TRUE(r.out.empty());
  EXPECT_NE(r.err.find("passed through"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("t = "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("particles"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "my.db"));
  EXPECT_FALSE(fs::exists(dir_ / "out.json"));
}

// A run killed at an arbitrary moment (here kill -9 after 1 s of a 100-s run) leaves no row and
// no JSON: both are written only once the run has finished, the row in one transaction.
TEST_F(Cli, KilledRunLeavesNothingBehind) {
  const CliResult first = run(kQuick + "--db my.db");
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const std::string cmd = "cd '" + dir_.string() + "' && { '" GRANCHAIN_BINARY
                          "' run --N 25 --k 1e6 --e 0.5 --T 1e4 --db my.db --json out.json --quiet & pid=$!; "
                          "sleep 1; kill -9 $pid; wait $pid; }";
  const int status = std::system(cmd.c_str());
  EXPECT_EQ(WEXITSTATUS(status), 128 + 9);
  const std::string count = "sqlite3 '" + (dir_ / "my.db").string() + "' 'SELECT count(*) FROM runs' > n.txt";
  ASSERT_EQ(std::system(("cd '" + dir_.string() + "' && " + count).c_str()), 0);
  EXPECT_EQ(slurp(dir_ / "n.txt"), "1\n");
  EXPECT_FALSE(fs::exists(dir_ / "out.json"));
}

TEST_F(Cli, HelpNamesEveryParameterAndExitsZero) {
  const CliResult r = run("run --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* flag : {"--N", "--e", "--k", "--T0", "--T ", "--transient", "--seed", "--engine", "--json", "--db", "--config"})
    EXPECT_NE(r.out.find(flag), std::string::npos) << flag;
  EXPECT_EQ(run("").exit_code, 2);  // no subcommand
}

TEST_F(Cli, TheoryPrintsTheClosedFormsAsTableAndJson) {
  const CliResult table = run("theory --N 2,3 --e 0.05");
  EXPECT_EQ(table.exit_code, 0);
  EXPECT_NE(table.out.find("0.171573"), std::string::npos);  // e_c^wall(2) = 3 - 2 sqrt 2
  EXPECT_NE(table.out.find("0.0976563"), std::string::npos);  // q(0.05) = 25/256
  const CliResult js = run("theory --N 3 --e 0.05,0.5 --json");
  ASSERT_EQ(js.exit_code, 0);
  const auto j = nlohmann::json::parse(js.out);
  EXPECT_NEAR(j["per_N"][0]["ec_free"].get<double>(), 7.0 - 4.0 * std::sqrt(3.0), 1e-15);
  EXPECT_NEAR(j["per_e"][0]["f"].get<double>(), 21.0 / 32.0, 1e-13);
  EXPECT_TRUE(j["per_e"][1]["q"].is_null());  // no three-body collapse at e = 0.5
  EXPECT_EQ(run("theory --json out.json").exit_code, 0);
  EXPECT_TRUE(fs::exists(dir_ / "out.json"));
  for (const char* bad : {"theory --N 0", "theory --e 1", "theory --e -0.1", "theory --N 2,x"}) {
    const CliResult r = run(std::string(bad) + " --json bad.json");
    EXPECT_EQ(r.exit_code, 2) << bad;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << bad;
    EXPECT_FALSE(fs::exists(dir_ / "bad.json")) << bad;
  }
}

// granchain collapse: the table, JSON, the event file and the store agree with each other; bad
// input is one line, exit 2, nothing written.
TEST_F(Cli, CollapseCountsStoresAndRecordsEveryCollision) {
  const CliResult r = run("collapse --N 3 --e 0.05 --k 1e6,1e10 --realizations 200 --threads 2 --json out.json "
                          "--events ev.csv --db t.db");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("Eq. ntot-log"), std::string::npos);
  const auto j = nlohmann::json::parse(slurp(dir_ / "out.json"));
  ASSERT_EQ(j["points"].size(), 2u);
  std::uint64_t collisions = 0;
  for (const auto& p : j["points"]) {
    EXPECT_EQ(p["observables"]["collapsed"].get<int>(), 0);
    EXPECT_GT(p["observables"]["n_tot"].get<double>(), 2.0);
    collisions += p["observables"]["particle_collisions"].get<std::uint64_t>();
  }
  EXPECT_GT(j["slopes"][0]["slope_per_log10_k"].get<double>(), 0.5);  // the three-body sequence lengthens
  // One CSV line per collision, plus the header.
  const std::string csv = slurp(dir_ / "ev.csv");
  EXPECT_EQ(static_cast<std::uint64_t>(std::count(csv.begin(), csv.end(), '\n')), collisions + 1);
  EXPECT_EQ(csv.rfind("e,k,realization,collision,t_begin,t_end,i,j,speed_in,speed_out\n", 0), 0u);
  // The store: two rows and 2 x 200 per-launch counts.
  const CliResult q = run("collapse --N 3 --e 0.05 --k 1e6 --realizations 10 --db t.db -q");
  EXPECT_EQ(q.exit_code, 0);
  EXPECT_TRUE(q.out.empty());
  for (const char* bad : {"collapse --N 1", "collapse --e 1.5", "collapse --k 0", "collapse --engine hard --k 1e6",
                          "collapse --setup wall --stop ends", "collapse --realizations 0", "collapse --k 1e4:1e2:x10",
                          "collapse --tc 1e-6", "collapse --dv0 -1"}) {
    const CliResult b = run(std::string(bad) + " --json bad.json --events bad.csv --db bad.db");
    EXPECT_EQ(b.exit_code, 2) << bad;
    EXPECT_EQ(std::count(b.err.begin(), b.err.end(), '\n'), 1) << bad << ": " << b.err;
    EXPECT_FALSE(fs::exists(dir_ / "bad.json") || fs::exists(dir_ / "bad.csv") || fs::exists(dir_ / "bad.db")) << bad;
  }
}

// The hard-sphere engine through `run` (k = infinity, reported as such) and through `collapse`,
// where a collapse is reported as such and the TC model continues past it.
TEST_F(Cli, HardSphereEngineRunsAndReportsCollapse) {
  const CliResult r = run("run --N 5 --e 0.9 --engine hard --T 50 --transient 5 --no-db --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["parameters"]["k"].is_null());  // infinity
  EXPECT_EQ(j["derived"]["tau_c"].get<double>(), 0.0);
  EXPECT_EQ(run("run --engine hard --k 1e6 --no-db").exit_code, 2);
  const CliResult c = run("collapse --N 3 --e 0.05 --engine hard --stop strict --realizations 20 --no-db --json");
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_GT(nlohmann::json::parse(c.out)["points"][0]["observables"]["collapsed"].get<int>(), 0);
  const CliResult tc = run("collapse --N 3 --e 0.05 --engine hard --stop strict --tc 1e-6 --realizations 20 --no-db --json");
  ASSERT_EQ(tc.exit_code, 0) << tc.err;
  EXPECT_EQ(nlohmann::json::parse(tc.out)["points"][0]["observables"]["collapsed"].get<int>(), 0);
}
