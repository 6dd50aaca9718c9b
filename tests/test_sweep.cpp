// Sweeps: the grid, seeds that depend only on the point, shards, the thread pool, the store's
// point keys, merging stores and exporting them.
#include <cmath>
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <filesystem>
#include <map>
#include <set>

#include "config/input_error.hpp"
#include "config/run_key.hpp"
#include "reproduce/store_analysis.hpp"
#include "store/results_store.hpp"
#include "store/run_json.hpp"
#include "store/store_export.hpp"
#include "store/store_merge.hpp"
#include "sweep/cost_model.hpp"
#include "sweep/sweep_grid.hpp"
#include "sweep/sweep_runner.hpp"
#include "temp_dir.hpp"

using namespace granchain;
namespace fs = std::filesystem;

namespace {

SweepDefinition definition(std::map<std::string, std::string> values, int replicas = 1, std::uint64_t seed = 1) {
  SweepDefinition d;
  for (auto& [k, v] : values) d.raw[k] = RawValue{v, ""};
  d.replicas = replicas;
  d.base_seed = seed;
  return d;
}

// A small grid that runs in well under a second.
SweepDefinition small_grid() { return definition({{"N", "3,4"}, {"e", "0.6,0.9"}, {"k", "1e4"}, {"T", "20"}}, 2); }

std::map<std::string, RunResult> run_points(const std::vector<SweepPoint>& points, int threads) {
  std::vector<std::size_t> todo(points.size());
  for (std::size_t i = 0; i < todo.size(); ++i) todo[i] = i;
  std::map<std::string, RunResult> out;
  SweepRunner runner(points, todo, [&](const SweepPoint& p, const RunResult* r, const std::string& error, const InelasticCollapseError*) {
    ASSERT_NE(r, nullptr) << error;
    out[p.key] = *r;
  });
  runner.run(threads);
  return out;
}

void expect_same_physics(const RunResult& a, const RunResult& b) {
  EXPECT_EQ(a.n_coll.value, b.n_coll.value);
  EXPECT_EQ(a.n_coll.error, b.n_coll.error);
  EXPECT_EQ(a.particle_collisions, b.particle_collisions);
  EXPECT_EQ(a.floor_hits, b.floor_hits);
  EXPECT_EQ(a.events, b.events);
  ASSERT_EQ(a.profiles.size(), b.profiles.size());
  for (std::size_t i = 0; i < a.profiles.size(); ++i) {
    EXPECT_EQ(a.profiles[i].z_mean.value, b.profiles[i].z_mean.value);
    EXPECT_EQ(a.profiles[i].kinetic.error, b.profiles[i].kinetic.error);
  }
}

std::int64_t count(const std::string& db_path, const std::string& sql) {
  sqlite3* db = nullptr;
  sqlite3_open_v2(db_path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr);
  sqlite3_stmt* st = nullptr;
  EXPECT_EQ(sqlite3_prepare_v2(db, sql.c_str(), -1, &st, nullptr), SQLITE_OK) << sqlite3_errmsg(db);
  std::int64_t n = -1;
  if (sqlite3_step(st) == SQLITE_ROW) n = sqlite3_column_int64(st, 0);
  sqlite3_finalize(st);
  sqlite3_close(db);
  return n;
}

}  // namespace

TEST(SweepGrid, ExpandsListsRangesAndReplicasLongestFirst) {
  const auto points = build_sweep_points(
      definition({{"N", "3,5"}, {"e", "0.80:0.90:0.05"}, {"k", "1e4:1e6:x10"}, {"T", "10"}}, 2));
  EXPECT_EQ(points.size(), 2u * 3u * 3u * 2u);
  std::set<std::string> keys;
  std::set<double> es;
  for (const auto& p : points) {
    keys.insert(p.key);
    es.insert(p.spec.params.e);
    EXPECT_EQ(p.spec.transient, 1.0);  // the run's default T / 10
  }
  EXPECT_EQ(keys.size(), points.size());
  EXPECT_EQ(es, (std::set<double>{0.8, 0.85, 0.9}));  // tidied: exactly the doubles of "0.85" etc.
  for (std::size_t i = 1; i < points.size(); ++i) EXPECT_GE(points[i - 1].cost, points[i].cost);
  EXPECT_EQ(points.front().spec.params.N, 5);  // more particles cost more
}

// Above k = 1e10 (the cost model's calibrated box) a collapsing column's events grow with its
// collisions, like k^alpha: its predicted cost keeps growing with k, by the same factor each decade;
// an uncollapsing column's (N (1 - e) = 1.2) falls a little, more slowly in a large column, and only
// over the five decades its runs were measured on. Nothing jumps at the box's edge.
TEST(SweepGrid, CostAboveTheCalibratedKGrowsWithTheCollisionsOfACollapsingColumn) {
  auto cost = [](double N, double e, double k) {
    const auto points = build_sweep_points(definition({{"N", std::to_string(static_cast<int>(N))},
                                                       {"e", std::to_string(e)}, {"k", std::to_string(k)}, {"T", "100"}}));
    return points.at(0).cost;
  };
  for (const double N : {100.0, 300.0}) {  // N (1 - e) = 70 and 210: the collapsing side
    const double at10 = cost(N, 0.3, 1e10), at11 = cost(N, 0.3, 1e11), at12 = cost(N, 0.3, 1e12), at20 = cost(N, 0.3, 1e20);
    EXPECT_NEAR(cost(N, 0.3, 1e10 * (1 + 1e-9)), at10, 1e-6 * at10);
    EXPECT_GT(at11 / at10, 1.5) << "N = " << N;  // the stored runs: 1.5 ... 2.0 per decade
    EXPECT_LT(at11 / at10, 2.2) << "N = " << N;
    EXPECT_NEAR(at12 / at11, at11 / at10, 1e-4);  // (up to the run's fixed overhead)
    EXPECT_NEAR(std::log(at20 / at10), 10 * std::log(at11 / at10), 1e-3);
  }
  const double e_c = 1 - 1.2 / 100;  // uncollapsing: the stored runs fall 0.85 ... 0.97 per decade
  const double c10 = cost(100, e_c, 1e10), c11 = cost(100, e_c, 1e11);
  EXPECT_LT(c11, c10);
  EXPECT_GT(c11 / c10, 0.8);
  EXPECT_NEAR(cost(100, e_c, 1e15), cost(100, e_c, 1e25), 1e-9 * c10);
  EXPECT_LT(cost(100, e_c, 1e15), cost(100, e_c, 1e14));
  // A large uncollapsing column's cost falls more slowly (the stored columns at c <= 2.8, per
  // decade: 0.90 ... 0.91 at N <= 100, 0.95 at N = 300 and 500, about 1 at N = 1000).
  const double e_large = 1 - 1.2 / 1000;
  const double large_fall = cost(1000, e_large, 1e11) / cost(1000, e_large, 1e10);
  EXPECT_GT(large_fall, c11 / c10 + 0.03);
  EXPECT_LT(large_fall, 1.0);
}

TEST(SweepGrid, HardEngineTakesNoKAndRepeatedValuesAreOnePoint) {
  const auto points = build_sweep_points(
      definition({{"N", "4,4"}, {"e", "0.9"}, {"k", "1e4,1e5"}, {"engine", "exact,hard"}, {"T", "10"}}));
  ASSERT_EQ(points.size(), 3u);  // exact at two k, hard once
  int hard = 0;
  for (const auto& p : points)
    if (p.spec.engine.kind == EngineKind::Hard) {
      ++hard;
      EXPECT_TRUE(std::isinf(p.spec.params.k));
    }
  EXPECT_EQ(hard, 1);
  EXPECT_THROW(build_sweep_points(definition({{"tc", "0.1"}})), InputError);  // TC needs the hard engine
  EXPECT_THROW(build_sweep_points(definition({{"e", "0.5,1.5"}})), InputError);
  EXPECT_THROW(build_sweep_points(definition({{"N", "3:1:1"}})), InputError);
}

TEST(SweepGrid, SeedDependsOnlyOnBaseSeedParametersAndReplica) {
  const auto small = build_sweep_points(definition({{"N", "4"}, {"e", "0.9"}, {"T", "10"}}, 2, 7));
  const auto large = build_sweep_points(definition({{"N", "3,4,5"}, {"e", "0.5,0.9"}, {"T", "10"}}, 3, 7));
  for (const auto& p : small) {
    const auto same = std::find_if(large.begin(), large.end(), [&](const SweepPoint& q) { return q.key == p.key; });
    ASSERT_NE(same, large.end()) << "a point's key and seed must not depend on the rest of the grid";
    EXPECT_EQ(same->replica, p.replica);
  }
  EXPECT_NE(small[0].spec.seed, small[1].spec.seed);  // replicas differ
  const auto other_base = build_sweep_points(definition({{"N", "4"}, {"e", "0.9"}, {"T", "10"}}, 2, 8));
  EXPECT_NE(other_base[0].spec.seed, small[0].spec.seed);
  for (const auto& p : large) EXPECT_LT(p.spec.seed, 1ULL << 63);
}

TEST(SweepGrid, ShardsPartitionTheGrid) {
  const auto points = build_sweep_points(definition({{"N", "3:9:1"}, {"e", "0.5,0.7,0.9"}, {"T", "10"}}));
  std::multiset<std::string> joined;
  for (int i = 1; i <= 4; ++i)
    for (const auto& p : shard_points(points, i, 4)) joined.insert(p.key);
  EXPECT_EQ(joined.size(), points.size());
  for (const auto& p : points) EXPECT_EQ(joined.count(p.key), 1u);
  EXPECT_EQ(shard_points(points, 1, 1).size(), points.size());
}

TEST(SweepRunner, ResultsDoNotDependOnThreadCount) {
  const auto points = build_sweep_points(small_grid());
  const auto one = run_points(points, 1);
  const auto two = run_points(points, 2);
  ASSERT_EQ(one.size(), points.size());
  ASSERT_EQ(two.size(), points.size());
  for (const auto& [key, r] : one) expect_same_physics(r, two.at(key));
  // And a point run on its own, as `granchain run --seed` would, gives the same again.
  const RunResult alone = run_driven_column(points.back().spec);
  expect_same_physics(alone, one.at(points.back().key));
  EXPECT_EQ(point_key(alone.spec), points.back().key);
}

TEST(SweepRunner, AnUnphysicalPointIsReportedAndTheOthersRun) {
  // Hard spheres at e = 0.5, N = 25 collapse inelastically within T = 100 (docs/engines.md).
  const auto points = build_sweep_points(
      definition({{"N", "25,3"}, {"e", "0.5"}, {"engine", "hard"}, {"T", "100"}}));
  ASSERT_EQ(points.size(), 2u);
  std::vector<std::size_t> todo = {0, 1};
  int ok = 0, failed = 0;
  SweepRunner runner(points, todo, [&](const SweepPoint& p, const RunResult* r, const std::string& error, const InelasticCollapseError*) {
    if (r) {
      ++ok;
      EXPECT_EQ(p.spec.params.N, 3);
    } else {
      ++failed;
      EXPECT_EQ(p.spec.params.N, 25);
      EXPECT_NE(error.find("inelastic collapse"), std::string::npos) << error;
    }
  });
  std::vector<SweepProgress> reports;
  runner.run(2, [&](const SweepProgress& p) { reports.push_back(p); }, 10.0);
  EXPECT_EQ(ok, 1);
  EXPECT_EQ(failed, 1);
  ASSERT_FALSE(reports.empty());
  EXPECT_TRUE(reports.back().final);
  EXPECT_EQ(reports.back().done, 2u);
  EXPECT_EQ(reports.back().failed, 1u);
}

// The ETA credits a running point with the simulated time it has covered: a sweep of one point
// (a fraction of a second or more) has a finite, positive ETA before the point is done, the point
// reporting its progress every millisecond (0 once the point has covered its whole time, which a
// report may catch before the point is recorded).
TEST(SweepRunner, EtaCountsTheRunningPointsProgress) {
  const auto points = build_sweep_points(definition({{"N", "25"}, {"e", "0.5"}, {"k", "1e7"}, {"T", "400"}}));
  ASSERT_EQ(points.size(), 1u);
  SweepRunner runner(points, {0}, [](const SweepPoint&, const RunResult* r, const std::string& error, const InelasticCollapseError*) { ASSERT_NE(r, nullptr) << error; });
  runner.set_point_progress_every(0.001);
  std::vector<SweepProgress> reports;
  runner.run(1, [&](const SweepProgress& p) { reports.push_back(p); }, 0.01);
  bool positive_before_done = false;
  for (const SweepProgress& p : reports)
    if (p.done == 0 && std::isfinite(p.eta)) {
      positive_before_done = positive_before_done || p.eta > 0.0;
      EXPECT_GE(p.eta, 0.0);
    }
  EXPECT_TRUE(positive_before_done) << reports.size() << " reports";
  ASSERT_FALSE(reports.empty());
  EXPECT_EQ(reports.back().done, 1u);
  EXPECT_EQ(reports.back().eta, 0.0);
}

// With a time limit only the points predicted to end within it are handed out: two points whose
// estimate is a million seconds are skipped, the small ones after them run, and the skipped ones
// are counted for the repeat; points_longer_than names the ones no invocation can fit.
TEST(SweepRunner, ATimeLimitSkipsPointsThatCannotEndWithinIt) {
  auto points = build_sweep_points(definition({{"N", "3"}, {"e", "0.5,0.6,0.7,0.8"}, {"k", "1e4"}, {"T", "20"}}));
  ASSERT_EQ(points.size(), 4u);
  for (std::size_t i = 0; i < points.size(); ++i) points[i].cost = i % 2 == 0 ? 1e6 : 1e-3;
  std::vector<std::size_t> ran;
  SweepRunner runner(points, {0, 1, 2, 3}, [&](const SweepPoint& p, const RunResult* r, const std::string& error, const InelasticCollapseError*) {
    ASSERT_NE(r, nullptr) << error;
    ran.push_back(static_cast<std::size_t>(&p - points.data()));
  });
  runner.set_time_limit(3600.0);
  runner.run(2);
  std::sort(ran.begin(), ran.end());
  EXPECT_EQ(ran, (std::vector<std::size_t>{1, 3}));
  EXPECT_EQ(runner.not_started(), 2u);
  EXPECT_DOUBLE_EQ(runner.not_started_cost(), 2e6);
  EXPECT_EQ(points_longer_than(points, {0, 1, 2, 3}, 3600.0), (std::vector<std::size_t>{0, 2}));
  EXPECT_TRUE(points_longer_than(points, {0, 1, 2, 3}, 0.0).empty());
  // Without a limit every point is handed out.
  SweepRunner all(points, {0, 1, 2, 3}, [](const SweepPoint&, const RunResult*, const std::string&, const InelasticCollapseError*) {});
  all.run(1);
  EXPECT_EQ(all.not_started(), 0u);
}

// A run records the CPU time of its thread beside its wall time (at most the wall time: one thread),
// the JSON keeps it, and a run stored before it was recorded reads back as NaN.
TEST(RunJson, CpuTimeIsRecordedAndReadBack) {
  const auto points = build_sweep_points(definition({{"N", "25"}, {"e", "0.5"}, {"k", "1e6"}, {"T", "50"}}));
  const RunResult r = run_driven_column(points.front().spec);
  EXPECT_GT(r.cpu_seconds, 0.0);
  EXPECT_LE(r.cpu_seconds, r.wall_seconds + 0.01);
  nlohmann::json j = run_result_to_json(r);
  EXPECT_EQ(run_result_from_json(nlohmann::json::parse(j.dump())).cpu_seconds, r.cpu_seconds);
  j["cost"].erase("cpu_seconds");
  EXPECT_TRUE(std::isnan(run_result_from_json(j).cpu_seconds));
}

// A run keeps the blocking curves behind its errors: every level from the bins down to 16 blocks,
// the reported n_coll error one of them, and the JSON (so the store) carries them exactly.
TEST(RunJson, BlockingCurvesAreKeptAndHoldTheReportedError) {
  const auto points = build_sweep_points(definition({{"N", "25"}, {"e", "0.5"}, {"k", "1e6"}, {"T", "50"}}));
  const RunResult r = run_driven_column(points.front().spec);
  ASSERT_FALSE(r.n_coll_blocking.empty());
  ASSERT_EQ(r.height_blocking.size(), r.n_coll_blocking.size());
  EXPECT_EQ(r.n_coll_blocking.front().blocks, static_cast<int>(r.spec.bins));
  for (std::size_t l = 1; l < r.n_coll_blocking.size(); ++l)
    EXPECT_EQ(r.n_coll_blocking[l].blocks * 2, r.n_coll_blocking[l - 1].blocks);
  EXPECT_EQ(r.n_coll_blocking.back().blocks, 16);
  bool found = false;
  for (const BlockingLevel& l : r.n_coll_blocking)
    if (l.blocks == r.n_coll.blocks) {
      found = true;
      EXPECT_EQ(l.error, r.n_coll.error);
    }
  EXPECT_TRUE(found) << "the reported error is a level of the curve";
  for (const BlockingLevel& l : r.height_blocking) EXPECT_GT(l.error, 0.0);
  nlohmann::json j = run_result_to_json(r);
  const RunResult back = run_result_from_json(nlohmann::json::parse(j.dump()));
  ASSERT_EQ(back.n_coll_blocking.size(), r.n_coll_blocking.size());
  for (std::size_t l = 0; l < r.n_coll_blocking.size(); ++l) {
    EXPECT_EQ(back.n_coll_blocking[l].error, r.n_coll_blocking[l].error);
    EXPECT_EQ(back.height_blocking[l].lag1, r.height_blocking[l].lag1);
  }
  j.erase("blocking");  // a run stored before the curves were kept
  EXPECT_TRUE(run_result_from_json(j).n_coll_blocking.empty());
}

TEST(RunJson, RoundTripIsExact) {
  const auto points = build_sweep_points(small_grid());
  const RunResult r = run_driven_column(points.front().spec);
  const RunResult back = run_result_from_json(nlohmann::json::parse(run_result_to_json(r).dump()));
  expect_same_physics(r, back);
  EXPECT_EQ(point_key(back.spec), point_key(r.spec));
  EXPECT_EQ(back.law.tau_c, r.law.tau_c);
  EXPECT_EQ(back.floor_rate.error, r.floor_rate.error);
  EXPECT_EQ(back.profiles.back().z_std.error, r.profiles.back().z_std.error);
}

TEST(SweepStore, PointsAreStoredOnceMergedOnceAndConflictsRefused) {
  TempDir dir;
  const auto points = build_sweep_points(small_grid());
  const auto results = run_points(points, 2);
  const std::string a = dir.file("a.db"), b = dir.file("b.db"), all = dir.file("all.db");
  {
    ResultsStore sa(a), sb(b);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const RunResult& r = results.at(points[i].key);
      EXPECT_TRUE(sa.insert_sweep_point(r, points[i].key, 1, points[i].replica).inserted);
      EXPECT_FALSE(sa.insert_sweep_point(r, points[i].key, 1, points[i].replica).inserted);  // never twice
      if (i % 2 == 0) sb.insert_sweep_point(r, points[i].key, 1, points[i].replica);         // b: half, overlapping
    }
    EXPECT_EQ(sa.point_keys().size(), points.size());
  }
  EXPECT_EQ(count(a, "SELECT count(*) FROM runs"), static_cast<std::int64_t>(points.size()));

  MergeReport m = merge_stores(all, {a, b});
  EXPECT_EQ(m.runs_added, static_cast<std::int64_t>(points.size()));
  EXPECT_EQ(m.runs_already_there, static_cast<std::int64_t>((points.size() + 1) / 2));
  m = merge_stores(all, {b});  // again: nothing new
  EXPECT_EQ(m.runs_added, 0);
  EXPECT_EQ(count(all, "SELECT count(*) FROM runs"), static_cast<std::int64_t>(points.size()));
  EXPECT_EQ(count(all, "SELECT count(*) FROM profiles"), count(a, "SELECT count(*) FROM profiles"));
  EXPECT_EQ(count(all, "SELECT count(DISTINCT point_key) FROM run_points"), static_cast<std::int64_t>(points.size()));

  // A store whose copy of one point differs in one collision count: the merge refuses it whole.
  fs::copy_file(b, dir.file("c.db"));
  sqlite3* db = nullptr;
  sqlite3_open(dir.file("c.db").c_str(), &db);
  ASSERT_EQ(sqlite3_exec(db, "UPDATE runs SET particle_collisions = particle_collisions + 1 WHERE id = 1", nullptr,
                         nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(db);
  const std::string fresh = dir.file("fresh.db");
  try {
    merge_stores(fresh, {a, dir.file("c.db")});
    FAIL() << "a conflicting duplicate was merged";
  } catch (const MergeConflict& e) {
    EXPECT_NE(std::string(e.what()).find("particle_collisions"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(fresh)) << "a failed merge must leave no new file";
  EXPECT_THROW(merge_stores(all, {dir.file("c.db")}), MergeConflict);
  EXPECT_EQ(count(all, "SELECT count(*) FROM runs"), static_cast<std::int64_t>(points.size()));
}

// The reports' cost table: each stored run's CPU time beside the cost model's prediction for the
// same run, summed per N, with the geometric mean of the ratios.
TEST(SweepStore, CostTableSetsEachRunsCpuTimeBesideTheModelsPrediction) {
  TempDir dir;
  const auto points = build_sweep_points(small_grid());
  const auto results = run_points(points, 2);
  const std::string db = dir.file("a.db");
  {
    ResultsStore s(db);
    for (const SweepPoint& p : points) s.insert_sweep_point(results.at(p.key), p.key, 1, p.replica);
  }
  const StoreAnalysis a = analyze_store(db, ExportSelection{}, 1e3);
  ASSERT_EQ(a.costs.size(), points.size());
  std::map<int, double> predicted;
  for (const SweepPoint& p : points) predicted[p.spec.params.N] += estimate_cost_seconds(p.spec);
  std::map<int, double> stored;
  for (const RunCost& c : a.costs) {
    EXPECT_GT(c.seconds, 0);
    stored[c.N] += c.predicted;
  }
  for (const auto& [N, sec] : predicted) EXPECT_NEAR(stored[N], sec, 1e-9 * sec) << "N = " << N;

  // The arithmetic: N = 50 runs at twice and half their prediction (sums 1.25, geometric mean 1,
  // both within 2); N = 200 at three times (outside); a run without a time is left out.
  const std::string md = cost_markdown({{50, 7200, 3600}, {50, 1800, 3600}, {200, 10800, 3600}, {200, 0, 3600}});
  EXPECT_NE(md.find("| 50 | 2 | 2.5 | 2 | 1.25 | 1.00 | 2 of 2 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 200 | 1 | 3 | 1 | 3.00 | 3.00 | 0 of 1 |"), std::string::npos) << md;
  EXPECT_EQ(cost_markdown({}), "");
}

TEST(SweepStore, ExportSelectsByValueEngineAndCondition) {
  TempDir dir;
  const auto points = build_sweep_points(small_grid());
  const std::string path = dir.file("s.db");
  {
    ResultsStore s(path);
    for (const auto& [key, r] : run_points(points, 2)) {
      const auto p = std::find_if(points.begin(), points.end(), [&](const SweepPoint& q) { return q.key == key; });
      s.insert_sweep_point(r, key, 1, p->replica);
    }
  }
  auto lines = [](const std::string& text) { return std::count(text.begin(), text.end(), '\n'); };
  ExportSelection sel;
  EXPECT_EQ(lines(export_results(path, sel, ExportFormat::Csv)), 1 + 8);
  sel.values["N"] = {3};
  sel.values["e"] = {0.9};
  EXPECT_EQ(lines(export_results(path, sel, ExportFormat::Csv)), 1 + 2);
  const auto j = nlohmann::json::parse(export_results(path, sel, ExportFormat::Json));
  ASSERT_EQ(j.size(), 2u);
  EXPECT_EQ(j[0]["N"], 3);
  EXPECT_TRUE(j[0].contains("point_key") && j[0].contains("replica") && j[0].contains("n_coll_err"));
  sel.table = ExportTable::Profiles;
  EXPECT_EQ(lines(export_results(path, sel, ExportFormat::Csv)), 1 + 2 * 3);  // 2 runs of 3 particles
  sel.values.clear();
  sel.table = ExportTable::Runs;
  sel.where = "replica = 1 AND N = 4";
  EXPECT_EQ(lines(export_results(path, sel, ExportFormat::Csv)), 1 + 2);
  sel.engines = {"reference"};
  EXPECT_EQ(lines(export_results(path, sel, ExportFormat::Csv)), 1);
  sel.where = "no_such_column > 1";
  EXPECT_THROW(export_results(path, sel, ExportFormat::Csv), StoreError);
}
