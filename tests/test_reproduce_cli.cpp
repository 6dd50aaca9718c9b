// `granchain reproduce` as a user meets it: the schematic figures from trajectories, the printed
// sweeps that fill the store a figure reuses, the smoke preset's every figure and group, drawing from
// what is stored (--stored-only, --k-min), a time limit that leaves the rest for a repeat, and the
// large preset's sweeps.
#include <sstream>
#include <string>
#include <vector>

#include "cli_fixture.hpp"

namespace {

class ReproduceCli : public Cli {};

}  // namespace

// The two schematic figures are drawn from simulated trajectories: files and reports exist, and the
// three-body collapse of fig2 (e = 0.065 < e_c(3)) has intervals shrinking by about q = 0.305 per
// collision of the pair (1, 2) before the contact time stops them (the report lists the ratios).
TEST_F(ReproduceCli, ReproducesTheSchematicFiguresFromTrajectories) {
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
TEST_F(ReproduceCli, PrintedSweepsFillTheStoreTheFigureReuses) {
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
TEST_F(ReproduceCli, SmokePresetDrawsEveryFigureAndTable1) {
  // In sittings of a --time-limit shorter than drawing every figure takes: each repeat after exit
  // 75 stores more (runs and counts come before any drawing), and the repeats end.
  std::int64_t stored = 0;
  CliResult r{75, "", ""};
  for (int sitting = 0; sitting < 20 && r.exit_code == 75; ++sitting) {  // each stores more: they end
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
TEST_F(ReproduceCli, StoredOnlyDrawsFromWhatIsStoredAndRunsNothing) {
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
TEST_F(ReproduceCli, StoredOnlyLimitFreeDrawsTheSeriesStoredSoFar) {
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
TEST_F(ReproduceCli, KMinReReadsTheStoredRunsOverAnotherWindow) {
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
TEST_F(ReproduceCli, ATimeLimitLeavesWhatCannotEndInItForARepeat) {
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
TEST_F(ReproduceCli, SmokePresetDrawsTheGroupBeyond) {
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
TEST_F(ReproduceCli, SmokePresetDrawsTheGroupColumns) {
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

// The large preset: the paper's across-N sweep extended to N = 1000 and, for N >= 100, to c = 10,
// with four replicas on the condensed side; --print-sweeps runs nothing and predicts the cost; a bad preset is refused.
TEST_F(ReproduceCli, LargePresetExtendsTheAcrossNSweepWithReplicas) {
  const CliResult r = run("reproduce --figure fig6 --preset large --print-sweeps --db l.db");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("granchain sweep --N 1000 --e 0.99,0.992,0.993,0.994,0.995,"), std::string::npos) << r.out;
  // e_c2's side beyond c = N (1 - e) = 5: c = 10, 8, 7, 6 single at N = 100, with replicas at N >= 200
  EXPECT_NE(r.out.find("granchain sweep --N 100 --e 0.9,0.92,0.93,0.94,0.95,0.96,"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("granchain sweep --N 200 --e 0.95,0.96,0.965,0.97,0.975,"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("granchain sweep --N 150 --e 0.1,0.2,0.3,0.4 --k 1e5:1e10:x10 --T 1e3 --T0 1 --replicas 4"), std::string::npos) << r.out;
  // The power-law side of N >= 500 on the paper's integrator, where it is the cheaper engine; N = 300's on the exact one.
  EXPECT_NE(r.out.find("granchain sweep --N 500 --e 0.1,0.2,0.3,0.4 --engine reference --k 1e5:1e10:x10 --T 1e3 --T0 1 --replicas 4"),
            std::string::npos) << r.out;
  EXPECT_NE(r.out.find("granchain sweep --N 1000 --e 0.1,0.2,0.3,0.4 --engine reference --k 1e5:1e10:x10 --T 1e3 --transient 500"),
            std::string::npos) << r.out;
  EXPECT_NE(r.out.find("granchain sweep --N 300 --e 0.966666666667,"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("--N 300 --e 0.1,0.2,0.3,0.4 --engine"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("granchain sweep --N 20 --e"), std::string::npos) << r.out;  // the paper's columns stay
  EXPECT_NE(r.out.find("2424 distinct points"), std::string::npos) << r.out;
  // N = 1000 settles after a longer transient than T/10 (its three sweeps), every other column not.
  std::size_t longer = 0;
  for (std::size_t at = r.out.find("--transient"); at != std::string::npos; at = r.out.find("--transient", at + 1)) {
    ++longer;
    const std::size_t line = r.out.rfind("granchain sweep", at);
    EXPECT_EQ(r.out.compare(line, 26, "granchain sweep --N 1000 -"), 0) << r.out.substr(line, at - line);
    EXPECT_EQ(r.out.compare(at, 16, "--transient 500 "), 0);
  }
  EXPECT_EQ(longer, 3u) << r.out;
  // The contacts grid too: N = 1000's points after 500, the others after T/10.
  const CliResult contacts = run("reproduce --figure contacts --preset large --print-sweeps --db l.db");
  ASSERT_EQ(contacts.exit_code, 0) << contacts.err;
  const std::size_t n1000 = contacts.out.find("granchain sweep --N 1000 ");
  ASSERT_NE(n1000, std::string::npos) << contacts.out;
  EXPECT_EQ(contacts.out.find("--transient"), contacts.out.find("--transient 500", n1000)) << contacts.out;
  EXPECT_FALSE(fs::exists(dir_ / "l.db"));
  const CliResult bad = run("reproduce --figure fig6 --preset huge --db l.db");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("valid: quick, paper, large, smoke"), std::string::npos) << bad.err;
}
