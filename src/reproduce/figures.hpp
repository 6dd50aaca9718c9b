#pragma once
// What the figures of `granchain reproduce` share: the flags, the driven-column grids a figure
// needs (run into the results store, reusing what it holds), the analysis of exactly those points,
// and the files a figure writes. One *_figures.cpp per group of figures implements them.
#include <chrono>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <set>
#include <string>
#include <vector>

#include "reproduce/store_analysis.hpp"
#include "sweep/sweep_grid.hpp"

namespace granchain {

struct ReproduceFlags {
  std::string figure = "fig5", preset = "quick", db = "reproduce.db", out = "reproduce";
  bool db_given = false, out_given = false;  // --db, --out on the command line (else the defaults above)
  int threads = 0;  // resolved to all cores before a figure runs
  bool quiet = false;
  bool print_sweeps = false;  // print the equivalent `granchain sweep` commands and run nothing
  bool stored_only = false;   // run nothing: analyse and draw the points already stored
  // --time-limit: seconds from the command's start (deadline, steady clock) within which points
  // must be predicted to end; 0: none.
  double time_limit = 0;
  // --k-min: the lower end of k in every fit (the analysis only; the runs are the preset's); 0: the
  // preset's own (1e6 for paper, 1e5 for quick, 1e4 for smoke).
  double k_min = 0;
  std::chrono::steady_clock::time_point started_at = std::chrono::steady_clock::now();
  double time_left() const;  // seconds left of the time limit (infinity without one)
  // large: the paper preset, its across-N figures (fig6, fig7, fig9) extended to N = 200 ... 1000
  // with replicas on the condensed side; every other figure as in paper.
  bool paper() const { return preset == "paper" || preset == "large"; }
  bool large() const { return preset == "large"; }
  bool smoke() const { return preset == "smoke"; }  // the pipeline check: tiny grids, meaningless numbers
};

// What a reproduction learns while its figures run, for the figures after: the points that
// turned unphysical in this command (not run again by a later figure), and what --stored-only
// found missing for the figure being drawn ("fig6 (N = 20..150): 112 of 672 runs"), for its report.
struct ReproductionLog {
  std::set<std::string> failed_keys;
  std::vector<std::string> partial;
};

// A time limit left points of a figure unstarted: the command stops, to be repeated.
struct TimeLimitReached : std::runtime_error {
  using std::runtime_error::runtime_error;
};
// --stored-only found nothing to draw a figure from (exit 2).
struct NothingStored : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// How a figure ended. Done and PointsFailed drew it (points that turned unphysical were left
// out); the others drew nothing: NothingStored (--stored-only found none of its runs), TimeLimit
// (--time-limit left runs for a repeat), StoreFailed, Unphysical (a trajectory that had to
// succeed), OutputFailed (a file or plot could not be written), Failed (its analysis could not
// be done). The command line turns these into messages and exit codes.
enum class FigureStatus { Done, PointsFailed, NothingStored, TimeLimit, StoreFailed, Unphysical, OutputFailed, Failed };

// What one figure produced: how it ended and its section of the Markdown report.
struct FigureOutcome {
  FigureStatus status = FigureStatus::Done;
  std::string markdown;
  std::string drawn;  // the figure files, for the command's output ("out/fig6.png (and .pdf)")
  // The stored CPU times of the driven-column runs it analyses (wall times for runs stored without
  // one), summed over whichever sittings ran them; negative for a figure without such runs.
  double run_seconds = -1.0;
  std::string message;  // why it ended as it did, for a status other than Done
  std::vector<std::string> failed_points;  // PointsFailed: each point left out, and why
};

// One block of a figure's driven-column grid, as texts of `granchain sweep` (lists, ranges).
struct GridBlock {
  std::string N, e, k, T, T0 = "1";
  int replicas = 1;  // independent runs (seeds) per point
  // The drive (--drive, --A, --omega): the thermal floor, or a plate of amplitude A and frequency omega.
  std::string drive = "thermal", A = "", omega = "";
  // --engine ("": the default, exact) and, for the hard engine (k empty), --start-k ("": none).
  std::string engine = "", start_k = "";
  // --transient ("": the default, T/10): longer where a column needs more than T/10 to settle.
  std::string transient = "";
};
// "granchain sweep --N ... --T0 ..." with --drive/--A/--omega for a plate and --replicas when > 1.
std::string sweep_command(const GridBlock& b);

// The command that reproduces a report of o.figure, for its "Command:" line: `granchain reproduce
// --figure F --preset P`, then --db and --out as given (paths as the user wrote them, quoted for a
// shell where needed), --stored-only and --k-min when given; not the flags that leave the report as it
// is (--threads, --time-limit, --quiet).
std::string reproduce_command_line(const ReproduceFlags& o);

// The presets' k grids and times. quick: k = 1e4..1e8, fits over k >= 1e5, T = 1000 for N < 50 and
// 100 for N >= 50; paper: k = 1e5..1e10, fits over k >= 1e6, T = 1e4 and 1e3 (the paper's);
// smoke: k = 1e4..1e6, fits over all, T = 20 and 5 (every code path in about a minute).
std::string preset_k(const ReproduceFlags& o);
double preset_k_min(const ReproduceFlags& o);
std::string preset_k_max(const ReproduceFlags& o);  // the largest k, for profiles
std::string preset_T(const ReproduceFlags& o, int N);
// The transient of a column's grid block ("": the default, T/10): N = 1000 falls onto its floor
// for about 100 time units from the initial state, so its windows start after 500 (docs/columns.md §1).
std::string settling_transient(int N);

// The points of all blocks, each key once, longest first. Throws InputError on a bad grid.
std::vector<SweepPoint> grid_points(const std::vector<GridBlock>& blocks);

// Runs the points the store does not hold yet (as a run, or as hard spheres' collapse) on o.threads
// threads (progress on stderr unless quiet) and stores each as it finishes, a collapse as a collapse;
// returns one line per point that turned otherwise unphysical (not stored), for the figure's outcome. Throws StoreError, or TimeLimitReached.
std::vector<std::string> run_missing_points(const std::vector<SweepPoint>& points, const ReproduceFlags& o, const std::string& label,
                                            ReproductionLog& log);

// A free-space collapse count as stored in o.db (ResultsStore::find_collapse), or run now (progress
// line on stderr unless quiet) and stored. Throws StoreError or UnphysicalStateError.
struct CollapseSpec;
struct CollapseResult;
// The free-space launches of Sec. III.D (defaults of granchain collapse: exact engine, a = v0 = 1,
// dv0 = 0.1, stop rule ends, seed 1) at N, e, k, run on o.threads.
CollapseSpec free_space_spec(int N, double e, double k, int launches, const ReproduceFlags& o);
// A series of free-space counts: N, e, the k list (value_list text) and the launches per count.
struct CountSeries {
  int N;
  double e;
  std::string k;
  int launches;
};
// free_space_spec for every k of every series, in order.
std::vector<CollapseSpec> count_specs(const std::vector<CountSeries>& series, const ReproduceFlags& o);
CollapseResult stored_or_run_collapse(const CollapseSpec& spec, const ReproduceFlags& o, const std::string& label);

// The analysis (`granchain analyze`) of exactly these points as stored, fits over k >= k_min.
StoreAnalysis analyze_points(const std::string& db, const std::vector<SweepPoint>& points, double k_min, const EnginePool& pool = {});

// The path of an output named `name` in --out.
std::string output_path(const ReproduceFlags& o, const std::string& name);
// Writes a whole output file (atomically); throws OutputError naming it.
void write_output(const std::string& path, const std::string& text);
// Runs plots/<script> with these arguments; throws OutputError saying what went wrong.
void draw(const std::string& script, const std::vector<std::string>& args);

// Writes out/<name>.json and draws it with plots/<script> into out/<name>.png and .pdf; returns
// "out/<name>.png (and .pdf)". Throws OutputError.
std::string draw_figure(const ReproduceFlags& o, const std::string& name, const nlohmann::json& data, const std::string& script);

// The critical region as c = N(1 - e): the paper finds 1 - e_c1 = 2.6/N and 1 - e_c2 = 3.0/N (Eq. e-fit);
// the grid reaches from deep in the power-law regime (c = 5) to well inside the uncollapsing one (1.2).
const std::vector<double>& critical_region_c();
// "c = 5, 4, 3.5, ..., 1.2" for reports.
std::string critical_region_text();
// Beyond the critical region on its condensed side, c = 6, 7, 8, 10: where the large preset looks
// for e_c2 of N >= 100, whose power-law side starts past c = 5 (docs/columns.md).
const std::vector<double>& ec2_extension_c();
// The e of the family's grid at which the profiles show the partially condensed state (a K_i dip
// with an interior hot layer above it, analysis/condensation.hpp), within the critical region and
// its extension (c <= 10).
std::vector<double> condensed_es(const StoreAnalysis& a, const analysis::FamilyAnalysis& f);
// The e grid of a critical region as a list: e = 1 - c/N for each c (12 significant digits).
std::string e_list_at_n_one_minus_e(int N, const std::vector<double>& c);

// The driven-column grids of the figures that need sweeps (o.figure picks fig3/fig4 or fig5).
std::vector<GridBlock> ncoll_grid(const ReproduceFlags& o);                 // fig3, fig4, fig5
std::vector<GridBlock> partial_condensation_grid(const ReproduceFlags& o);  // fig8
std::vector<GridBlock> across_n_grid(const ReproduceFlags& o);              // fig6, fig7, fig9
std::vector<GridBlock> table1_grid(const ReproduceFlags& o);                // table1
std::vector<GridBlock> driven_limit_grid(const ReproduceFlags& o);          // limit-driven
std::vector<GridBlock> hard_limit_grid(const ReproduceFlags& o);            // limit-hard
std::vector<GridBlock> drives_grid(const ReproduceFlags& o);                // drives-onset (all N), drives-ncoll (N = 25)
std::vector<GridBlock> contacts_grid(const ReproduceFlags& o);              // contacts

// The statements of Sec. III.B on the fine structure of n_coll(e) (N = 3..6) tested on these
// points' curves at their largest k, per seed and combined: a Markdown section ("" without data).
std::string fine_structure_report(const std::string& db, const std::vector<SweepPoint>& points);

// The figures. Each runs what it needs, draws into --out and returns its report section; throws
// StoreError (store), UnphysicalStateError (a trajectory that must not fail) or OutputError
// (an output or plot that could not be written).
FigureOutcome reproduce_model_sketch(const ReproduceFlags& o, ReproductionLog& log);        // fig1 (1dmodel)
FigureOutcome reproduce_three_body(const ReproduceFlags& o, ReproductionLog& log);          // fig2 (threebodycollapse)
FigureOutcome reproduce_ncoll_figure(const ReproduceFlags& o, ReproductionLog& log);        // fig3, fig4 (N = 3..6), fig5 (N = 25)
FigureOutcome reproduce_bifurcation(const ReproduceFlags& o, ReproductionLog& log);         // fig6 (bifurcationdiagram)
FigureOutcome reproduce_scaling_collapse(const ReproduceFlags& o, ReproductionLog& log);    // fig7 (logfitbX)
FigureOutcome reproduce_partial_condensation(const ReproduceFlags& o, ReproductionLog& log);  // fig8 (partial_cond)
FigureOutcome reproduce_alpha_vs_n(const ReproduceFlags& o, ReproductionLog& log);          // fig9 (powerexpo)
FigureOutcome reproduce_free_space_counts(const ReproduceFlags& o, ReproductionLog& log);   // fig10 (ntot)
std::vector<CollapseSpec> free_space_count_specs(const ReproduceFlags& o);  // the counts fig10 reads
FigureOutcome reproduce_table1(const ReproduceFlags& o, ReproductionLog& log);              // table1
// The vibrating plates beside the thermal floor (group `drives`, drive_figures.cpp).
FigureOutcome reproduce_drive_onset(const ReproduceFlags& o, ReproductionLog& log);     // drives-onset
FigureOutcome reproduce_drive_ncoll(const ReproduceFlags& o, ReproductionLog& log);     // drives-ncoll
FigureOutcome reproduce_drive_profiles(const ReproduceFlags& o, ReproductionLog& log);  // drives-profiles
// Beyond the paper (group `beyond`): the k -> infinity limit and the collision sequences.
FigureOutcome reproduce_free_space_exponents(const ReproduceFlags& o, ReproductionLog& log);  // limit-free
std::vector<CollapseSpec> free_space_exponent_specs(const ReproduceFlags& o);  // the counts limit-free reads
FigureOutcome reproduce_driven_exponents(const ReproduceFlags& o, ReproductionLog& log);      // limit-driven
FigureOutcome reproduce_hard_limit(const ReproduceFlags& o, ReproductionLog& log);            // limit-hard
FigureOutcome reproduce_collision_intervals(const ReproduceFlags& o, ReproductionLog& log);   // intervals
// Beyond the paper's columns (group `columns`, contact_figure.cpp): contact durations against height per N.
FigureOutcome reproduce_contacts(const ReproduceFlags& o, ReproductionLog& log);  // contacts

}  // namespace granchain
