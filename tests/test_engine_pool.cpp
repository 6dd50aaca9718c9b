// `granchain analyze --pool-engines`: runs of several engines analysed as one engine. A column
// measured with one engine joins the across-N lines of columns measured with another, a point with
// runs of both combines them as replicas, and what is not a pool of soft-sphere engines is refused.
#include <cmath>
#include <nlohmann/json.hpp>

#include "cli_fixture.hpp"
#include "engines/engine_registry.hpp"
#include "store/results_store.hpp"

namespace {

class EnginePoolCli : public Cli {
 protected:
  // n_coll = c(N) k^alpha(N) on the power-law side (e = 0.1 ... 0.4, k = 1e5 ... 1e9) with
  // alpha(N) = 0.1 log10 N: N = 25 and 50 by the exact engine, N = 100 by the reference only, and
  // at N = 50, k = 1e7 one more run by the reference, 0.1 above the exact run's value.
  void SetUp() override {
    Cli::SetUp();
    granchain::ResultsStore store((dir_ / "p.db").string());
    std::uint64_t seed = 0;
    const auto add = [&](granchain::EngineKind engine, int N, double e, double k, double n, double err) {
      granchain::RunResult r;
      r.spec.engine.kind = engine;
      r.spec.params.N = N;
      r.spec.params.e = e;
      r.spec.params.k = k;
      r.spec.T = 100;
      r.spec.seed = ++seed;
      r.n_coll.value = n;
      r.n_coll.error = err;
      store.insert_run(r);
    };
    for (int N : {25, 50, 100})
      for (double e : {0.1, 0.2, 0.3, 0.4})
        for (double k = 1e5; k <= 1e9; k *= 10) {
          const auto engine = N == 100 ? granchain::EngineKind::Reference : granchain::EngineKind::Exact;
          add(engine, N, e, k, (1.0 + e) * std::pow(k, 0.1 * std::log10(N)), 0.1);
        }
    add(granchain::EngineKind::Reference, 50, 0.1, 1e7, 1.1 * std::pow(1e7, 0.1 * std::log10(50.0)) + 0.1, 0.2);
  }
};

TEST_F(EnginePoolCli, PooledEnginesFormOneFamilyPerColumnAndOneLineAcrossN) {
  // Apart: four families (exact N = 25, 50; reference N = 50, 100) and no local-exponent line (two
  // columns per engine; a line needs three).
  const CliResult apart = run("analyze --db p.db --k-min 1e5 --json");
  ASSERT_EQ(apart.exit_code, 0) << apart.err;
  const auto a = nlohmann::json::parse(apart.out);
  EXPECT_EQ(a["families"].size(), 4u);
  for (const auto& across : a["across_N"]) EXPECT_TRUE(across["local_alpha_vs_log10_N"].empty()) << across.dump();

  const CliResult pooled = run("analyze --db p.db --k-min 1e5 --pool-engines exact,reference --json");
  ASSERT_EQ(pooled.exit_code, 0) << pooled.err;
  const auto p = nlohmann::json::parse(pooled.out);
  ASSERT_EQ(p["families"].size(), 3u);
  for (const auto& f : p["families"]) EXPECT_EQ(f["engine"], "exact+reference");
  // N = 50, e = 0.1, k = 1e7: the two runs combined as replicas of equal windows, mean and
  // propagated error sqrt(0.1^2 + 0.2^2) / 2.
  const double exact = 1.1 * std::pow(1e7, 0.1 * std::log10(50.0));
  bool found = false;
  for (const auto& pt : p["families"][1]["curves"][0]["n_coll_of_k"])
    if (pt["k"].get<double>() == 1e7) {
      found = true;
      EXPECT_NEAR(pt["n_coll"].get<double>(), exact + 0.05, 1e-9);
      EXPECT_NEAR(pt["error"].get<double>(), std::sqrt(0.05) / 2, 1e-12);
    }
  EXPECT_TRUE(found) << p["families"][1].dump();
  ASSERT_EQ(p["families"][1]["N"], 50);
  EXPECT_EQ(p["families"][1]["replica_check"]["runs"], 2);
  // One line through the three columns; its slope is the law's 0.1 per decade of N.
  ASSERT_EQ(p["across_N"].size(), 1u);
  EXPECT_EQ(p["across_N"][0]["engine"], "exact+reference");
  const auto& lines = p["across_N"][0]["local_alpha_vs_log10_N"];
  ASSERT_FALSE(lines.empty());
  for (const auto& l : lines) {
    EXPECT_EQ(l["N"], nlohmann::json({25, 50, 100}));
    EXPECT_NEAR(l["slope"].get<double>(), 0.1, 4 * l["slope_err"].get<double>() + 1e-3) << l.dump();
  }
  const CliResult text = run("analyze --db p.db --k-min 1e5 --pool-engines exact,reference");
  EXPECT_NE(text.out.find("engine exact+reference, N = 100"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("across N (engine exact+reference"), std::string::npos) << text.out;
}

TEST_F(EnginePoolCli, WhatIsNotAPoolOfSoftSphereEnginesIsRefused) {
  for (const std::string list : {"exact", "exact,exact", "exact,hard", "exact,nonsense", "exact,", ",reference"}) {
    const CliResult r = run("analyze --db p.db --pool-engines '" + list + "'");
    EXPECT_EQ(r.exit_code, 2) << list;
    EXPECT_TRUE(r.out.empty()) << list << ": " << r.out;
    EXPECT_NE(r.err.find("--pool-engines"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("exact, reference, reference-located"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  const CliResult both = run("analyze --db p.db --pool-engines exact,reference --engine exact");
  EXPECT_EQ(both.exit_code, 2);
  EXPECT_NE(both.err.find("--engine"), std::string::npos) << both.err;
}

}  // namespace
