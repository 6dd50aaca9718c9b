// The figure group `drives` of `granchain reproduce` (docs/drives.md): its printed sweeps hold the
// plates' parameters and fill the store its figures read, and on the smoke preset every figure is
// drawn with every drive in its report.
#include <nlohmann/json.hpp>

#include "cli_fixture.hpp"

namespace {

class DriveFigures : public Cli {};

}  // namespace

TEST_F(DriveFigures, PrintedSweepsFillTheStoreAndEveryFigureIsDrawn) {
  const CliResult p = run("reproduce --figure drives --preset smoke --print-sweeps");
  ASSERT_EQ(p.exit_code, 0) << p.err;
  // Four drives x two N: eight blocks, each of 12 e x 3 k.
  EXPECT_NE(p.out.find("# 288 distinct points"), std::string::npos) << p.out;
  EXPECT_NE(p.out.find(" --T 20 --T0 1 --drive sine --A 0.1 --omega 10\n"), std::string::npos) << p.out;
  EXPECT_NE(p.out.find(" --drive sawtooth --A 0.314159265359 --omega 10\n"), std::string::npos) << p.out;
  EXPECT_NE(p.out.find(" --drive quadratic --A 0.0785398163397 --omega 10\n"), std::string::npos) << p.out;
  // Run as printed; the figures then find every point stored.
  std::size_t at = 0;
  int blocks = 0;
  while ((at = p.out.find("\ngranchain sweep ", at)) != std::string::npos) {
    const std::size_t end = p.out.find('\n', at + 1);
    const std::string line = p.out.substr(at + 11, end - at - 11);  // after "\ngranchain "
    const CliResult sw = run(line + " --db s.db -q");
    ASSERT_EQ(sw.exit_code, 0) << line << ": " << sw.err;
    ++blocks;
    at = end;
  }
  EXPECT_EQ(blocks, 8);
  EXPECT_EQ(query(dir_ / "s.db", "SELECT count(*) FROM runs"), 288);
  EXPECT_EQ(query(dir_ / "s.db", "SELECT count(*) FROM runs WHERE drive = 'quadratic'"), 72);
  const CliResult fig = run("reproduce --figure drives --preset smoke --db s.db --out figs");
  ASSERT_EQ(fig.exit_code, 0) << fig.err;
  EXPECT_NE(fig.err.find("288 runs, 288 already in s.db, 0 to run"), std::string::npos) << fig.err;
  for (const char* f : {"drives-onset.png", "drives-onset.pdf", "drives-ncoll_N25_T01_exact.png",
                        "drives-ncoll_N25_T01_exact_sine_A0.1_w10.png", "drives-ncoll_N25_T01_exact_sawtooth_A0.314159_w10.png",
                        "drives-ncoll_N25_T01_exact_quadratic_A0.0785398_w10.pdf", "drives-profiles.png", "report-drives.md"})
    EXPECT_TRUE(fs::exists(dir_ / "figs" / f)) << f;
  const std::string report = slurp(dir_ / "figs/report-drives.md");
  EXPECT_EQ(report.find("failed"), std::string::npos) << report.substr(0, 800);
  // The profiles: each drive at both N(1 - e), the plates with their phase-resolved centre of mass.
  const nlohmann::json prof = nlohmann::json::parse(slurp(dir_ / "figs/drives-profiles.json"));
  ASSERT_EQ(prof["columns"].size(), 8u);
  for (const auto& c : prof["columns"]) {
    EXPECT_EQ(c.contains("phase"), c["drive"] != "thermal") << c["drive"];
    // The density integrates to N = 25 (every particle within the bins).
    double n = 0;
    for (const auto& v : c["density"]["value"]) n += v.get<double>();
    EXPECT_NEAR(n, 25.0, 1e-9) << c["drive"];
  }
  for (const char* d : {"| thermal |", "| sine |", "| sawtooth |", "| quadratic |"}) EXPECT_NE(report.find(d), std::string::npos) << d;
}
