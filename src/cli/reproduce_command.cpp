// `granchain reproduce`: its flags, their validation, and the call into the reproduction layer
// (reproduce/reproduction.hpp), which runs, analyses, draws and reports the chosen figures.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <thread>
#include <unordered_set>

#include "cli/interrupt_message.hpp"
#include "cli/subcommand.hpp"
#include "cli/exit_codes.hpp"
#include "config/input_error.hpp"
#include "config/value_list.hpp"
#include "provenance.hpp"
#include "reproduce/reproduction.hpp"
#include "store/output_file.hpp"
#include "store/results_store.hpp"
#include "sweep/sweep_runner.hpp"

namespace granchain {

namespace {

// The exit code of a figure's end (cli/exit_codes.hpp).
int exit_code(FigureStatus status) {
  switch (status) {
    case FigureStatus::Done: return kExitOk;
    case FigureStatus::PointsFailed:
    case FigureStatus::Unphysical: return kExitUnphysical;
    case FigureStatus::NothingStored: return kExitBadInput;
    case FigureStatus::TimeLimit: return kExitTimeLimit;
    case FigureStatus::StoreFailed:
    case FigureStatus::OutputFailed:
    case FigureStatus::Failed: return kExitStoreFailed;
  }
  return kExitStoreFailed;
}

// The line on standard error for a figure that did not end Done ("" figure: the computing before
// the figures under --time-limit).
void report_failure(const std::string& figure, const FigureOutcome& out) {
  const std::string name = figure.empty() ? "" : figure + ": ";
  for (const std::string& f : out.failed_points) fmt::print(stderr, "granchain: error: {}run turned unphysical, not stored: {}\n", name, f);
  switch (out.status) {
    case FigureStatus::Done:
    case FigureStatus::PointsFailed: return;
    case FigureStatus::TimeLimit:
      fmt::print(stderr, "granchain: {}--time-limit: {}; every finished run is stored, {}repeat the command to resume\n", name,
                 out.message, figure.empty() ? "no figure was drawn; " : "");
      return;
    case FigureStatus::StoreFailed:
      fmt::print(stderr, "granchain: error: {}{}; repeat the command to resume\n", name, out.message);
      return;
    case FigureStatus::Unphysical:
      fmt::print(stderr, "granchain: error: {}the simulation became unphysical: {}\n", name, out.message);
      return;
    case FigureStatus::NothingStored:
    case FigureStatus::OutputFailed:
    case FigureStatus::Failed:
      fmt::print(stderr, "granchain: error: {}{}\n", name, out.message);
      return;
  }
}

// threads_text: the --threads value as given, or null when the flag was not given.
int execute_reproduce(const std::shared_ptr<ReproduceFlags>& impl_, const std::string* threads_text, const std::string* time_limit_text) {
  ReproduceFlags o = *impl_;
  o.started_at = std::chrono::steady_clock::now();
  const std::vector<const FigureEntry*> chosen = chosen_figures(o.figure);
  try {
    if (chosen.empty()) throw InputError(fmt::format("--figure = '{}' is not a figure; valid: {}all, beyond, drives, columns", o.figure, figure_names()));
    if (o.preset != "quick" && o.preset != "paper" && o.preset != "large" && o.preset != "smoke")
      throw InputError(fmt::format("--preset = '{}' is not a preset; valid: quick, paper, large, smoke", o.preset));
    // As sweep validates it; an empty value is given, and refused.
    if (threads_text) o.threads = static_cast<int>(parse_integer_in(*threads_text, "--threads", 1, 1024));
    if (time_limit_text) o.time_limit = parse_duration(*time_limit_text, "--time-limit");
    if (o.k_min != 0) {
      // At least three values of k of the preset's grid (1eA .. 1eB by x10) must remain for the fits.
      const double k_largest = std::stod(preset_k_max(o));
      const double limit = k_largest / 100.0;
      if (!(o.k_min > 0) || o.k_min > limit * (1 + 1e-9))
        throw InputError(fmt::format("--k-min = {:g} is out of range; valid range: 0 < k-min <= {} (three values of k of the {} "
                                     "preset's grid must remain for the fits)",
                                     o.k_min, power_of_ten_text(limit), o.preset));
    }
    if (o.stored_only && o.print_sweeps) throw InputError("--stored-only and --print-sweeps exclude each other: both run nothing, one draws, one prints");
    std::error_code ec;
    if (o.stored_only && !std::filesystem::exists(o.db, ec))
      throw InputError(fmt::format("--db: '{}' does not exist; --stored-only draws from the runs of an existing store", o.db));
    ResultsStore::preflight(o.db, o.stored_only ? ResultsStore::Access::ReadOnly : ResultsStore::Access::ReadWrite);
    if (o.time_limit > 0 && !o.print_sweeps && !o.stored_only) {
      // Runs that no invocation with this limit can fit are refused before anything runs.
      std::unordered_set<std::string> stored;
      if (std::filesystem::exists(o.db, ec)) stored = ResultsStore(o.db, ResultsStore::Access::ReadOnly).point_keys();
      for (const FigureEntry* f : chosen) {
        if (!f->grid) continue;
        const std::vector<SweepPoint> points = grid_points(f->grid(o));
        const std::vector<std::size_t> longer = points_longer_than(points, points_to_run(points, stored), o.time_limit);
        if (!longer.empty()) throw InputError(fmt::format("{}: {}", f->name, time_limit_too_short_message(points, longer, o.time_limit)));
      }
    }
    if (!o.print_sweeps) {  // --print-sweeps writes nothing into --out
      if (std::filesystem::exists(o.out, ec) && !std::filesystem::is_directory(o.out, ec))
        throw InputError(fmt::format("--out: '{}' is a file, not a folder; name a folder for the figures and reports", o.out));
      std::filesystem::create_directories(o.out, ec);
      if (ec) throw InputError(fmt::format("--out: cannot create the folder '{}': {}", o.out, ec.message()));
      // Every file a reproduction writes into --out is named after a figure (fig5.png, fig1-trace.csv,
      // table1.csv, limit-free.pdf, ...) or is a report: a store there under such a name would be overwritten.
      const std::filesystem::path db_path(o.db);
      const std::filesystem::path db_folder = db_path.parent_path().empty() ? "." : db_path.parent_path();
      if (std::filesystem::equivalent(db_folder, o.out, ec)) {
        const std::string name = db_path.filename().string();
        std::vector<std::string> owned = {"report"};
        for (const FigureEntry& f : figures()) owned.push_back(f.name);
        for (const std::string& stem : owned)
          if (name.rfind(stem, 0) == 0)
            throw InputError(fmt::format("--db: '{}' lies in --out '{}' under a name that the reproduction writes there "
                                         "(figures, data and reports start with a figure's name or 'report'); keep the "
                                         "store elsewhere or rename it",
                                         o.db, o.out));
      }
      for (const FigureEntry* f : chosen) check_output_file(output_path(o, report_name(f->name)), "--out", {{"--db", o.db}});
      if (is_figure_group(o.figure)) check_output_file(output_path(o, report_name(o.figure)), "--out", {{"--db", o.db}});
    }
  } catch (const std::exception& e) {
    fmt::print(stderr, "granchain: error: {}\n", e.what());
    return kExitBadInput;
  }
  if (o.print_sweeps) {
    fmt::print("{}", sweep_commands(chosen, o));
    return kExitOk;
  }
  if (o.threads == 0) o.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  set_parallelism(o.threads, 1);
  announce_on_interrupt(fmt::format("every run that finished is stored in {}, and every launch of a free-space count; repeat the same "
                                    "command to resume (stored runs and launches are reused)", o.db));
  int code = kExitOk;
  const ReproductionOutcome result = run_figures(chosen, o, [&code](const FigureReport& r) {
    const FigureOutcome& out = r.outcome;
    report_failure(r.figure->name, out);
    // A time limit stops the figures; an earlier failure's code wins over it.
    code = out.status == FigureStatus::TimeLimit && code != kExitOk ? code : std::max(code, exit_code(out.status));
    if (!out.drawn.empty()) fmt::print("figure: {}\n", out.drawn);
    if (!r.report_path.empty()) fmt::print("report: {}\n", r.report_path);
  });
  report_failure("", result.computing);
  if (result.computing.status != FigureStatus::Done) {
    fmt::print("runs:   {}\n", o.db);
    return exit_code(result.computing.status);
  }
  if (!result.group_report.empty()) fmt::print("report: {}\n", result.group_report);
  if (!result.group_report_error.empty()) {
    fmt::print(stderr, "granchain: error: {}\n", result.group_report_error);
    code = std::max<int>(code, kExitStoreFailed);
  }
  fmt::print("runs:   {}\n", o.db);
  return code;
}

}  // namespace

Subcommand add_reproduce_command(CLI::App& app) {
  auto impl_ = std::make_shared<ReproduceFlags>();
  CLI::App* sub_ = app.add_subcommand("reproduce", "Run, analyse and draw the paper's figures and Table 1, with a report beside the paper's numbers.");
  sub_->footer(
      "Runs the sweeps a figure needs into --db (points already stored are reused; a killed reproduction\n"
      "resumes), analyses exactly those points (granchain analyze), draws the figure (PNG and PDF) and writes a\n"
      "Markdown report with every measured number beside the paper's into --out (report.md for fig5,\n"
      "report-<figure>.md for the others, report-all.md for --figure all).\n"
      "  fig1  1dmodel            the model: slope flow, the driven column (a simulated snapshot) and z_i(t)\n"
      "  fig2  threebodycollapse  a three-body free-space collapse: z_i(t) and the geometric intervals (q)\n"
      "  fig3  cflogk, fig4 cfe   N = 3..6, e = 0.05..1.0: n_coll against log k and against e, with e_c(n) lines\n"
      "  fig5  cfreqlogN25        N = 25: the three regimes, e_c1, e_c2, alpha\n"
      "  fig6  bifurcationdiagram e_c1, e_c2 for N = 20..150 against 1/N with the A/N fits, condensed region\n"
      "  fig7  logfitbX           b / N^(5/2) against (1 - e) - A/N; b / N^(1/2) against N (1 - e)\n"
      "  fig8  partial_cond       sigma_i / sigma_0,i and K_i for N = 25, e = 0.82..0.92\n"
      "  fig9  powerexpo          alpha at e = 0.1..0.4 against log10 N with the fit of Eq. alphafit\n"
      "  fig10 ntot               free-space n_tot(k), N = 3 and N = 25\n"
      "  table1                   e_c1, e_c2, alpha bar for N = 25, 50 at k_B T0 = 1, 2, 4, 10\n"
      "  all                      every one of them in this order, and report-all.md\n"
      "Beyond the paper (docs/beyond.md):\n"
      "  limit-free               free-space n_tot(k) at N = 10, 25, 50, e = 0.3, 0.5: local exponents, candidate forms\n"
      "  limit-driven             driven n_coll(k) at N = 25 and 50, e = 0.1..0.5: local exponents, candidate forms\n"
      "  intervals                collision sequences of N = 25 collapses: hard-sphere approach, soft collapse events\n"
      "  limit-hard               the driven column's hard-sphere limit: where hard spheres collapse (from the initial\n"
      "                           state and from the soft column's), soft n_coll(k) to 1e30 against the hard value\n"
      "  beyond                   these four, and report-beyond.md (quick: k to 1e9/1e10; paper: free to 1e20,\n"
      "                           driven to 1e16 with T = 1e4, the hard-sphere limit to 1e30)\n"
      "Other drives (docs/drives.md):\n"
      "  drives-onset             e_c1, e_c2 for N = 10..100 against 1/N on the thermal floor and three vibrating\n"
      "                           plates (sine, sawtooth, quadratic), A/N fits per drive, one A for all?\n"
      "  drives-ncoll             n_coll(k) at N = 25 on every drive: the three regimes\n"
      "  drives-profiles          density and temperature against height, centre of mass through the plate's cycle\n"
      "  drives                   these three, and report-drives.md\n"
      "Beyond the paper's columns (docs/columns.md):\n"
      "  contacts                 contact durations in units of tau_c against height, per N, at N (1 - e) = 2, 5 and\n"
      "                           e = 0.3: are the contacts long-lived? (paper: N = 25..150, k = 1e6, 1e8, 1e10;\n"
      "                           large: and N = 300, 1000; quick: N = 25..100, k = 1e4, 1e6; smoke: N = 10, 25)\n"
      "  columns                  this one, and report-columns.md\n"
      "Presets: quick (k = 1e4..1e8, fits over k >= 1e5, T = 1000 for N < 50 and 100 for N >= 50; each figure\n"
      "under 30 minutes on two cores), paper (k = 1e5..1e10, fits over k >= 1e6,\n"
      "T = 1e4 for N < 50 and 1e3 for N >= 50: the paper's grids; about 13.5 CPU-hours in all, most of it fig6 and fig9),\n"
      "smoke (k = 1e4..1e6, T = 20 and 5, fewer free-space launches: every code path in about 35 s; the numbers\n"
      "mean nothing, it checks the pipeline).\n"
      "fig6, fig7 and fig9 share one sweep; fig5 and fig8 share points at the largest k. docs/reproduce.md.\n" +
      exit_codes_help("2 bad input (nothing run), 3 a run turned unphysical, 4 a store or output could not be written, 75 "
                      "--time-limit left runs for a repeat of the command"));
  sub_->add_option("--figure", impl_->figure, "fig1 .. fig10, table1, all, or limit-free, limit-driven, intervals, limit-hard, beyond, or drives-onset, drives-ncoll, drives-profiles, drives, or contacts, columns; default fig5");
  sub_->add_option("--preset", impl_->preset, "quick (default), paper, large (paper with fig6, fig7, fig9 and contacts to N = 1000) or smoke (a pipeline check)");
  CLI::Option* db_option = sub_->add_option("--db", impl_->db, "results store holding the runs; default reproduce.db")->type_name("FILE");
  CLI::Option* out_option = sub_->add_option("--out", impl_->out, "folder for the figures and the reports; default reproduce")->type_name("DIR");
  auto threads_text = std::make_shared<std::string>();
  CLI::Option* threads_option =
      sub_->add_option("--threads", *threads_text, "points run at once; integer 1 <= threads <= 1024; default all cores")
          ->type_name("INT");
  auto time_limit_text = std::make_shared<std::string>();
  CLI::Option* time_limit_option =
      sub_->add_option("--time-limit", *time_limit_text,
                       "a batch job's walltime: start only runs predicted to end within it (as sweep --time-limit; a free-space "
                       "count starts while any time is left, the sketches and the sequences of intervals are not limited); when "
                       "runs are left, stop before drawing that figure and exit 75 (repeat the command to resume); seconds, "
                       "90m, 2.5h or H:MM:SS")
          ->type_name("DURATION");
  sub_->add_option("--k-min", impl_->k_min,
                   "lower end of k in every fit (the analysis only: the same runs, re-read over a window; default the "
                   "preset's, 1e6 for paper, 1e5 for quick); at most the preset's largest k / 100")
      ->type_name("K");
  sub_->add_flag("--quiet,-q", impl_->quiet, "no progress");
  sub_->add_flag("--stored-only", impl_->stored_only,
                 "run no sweep and no free-space count: analyse and draw each figure from the runs already in --db, opened "
                 "read-only (a look at a long reproduction while it runs; each report says it is partial and how many runs it "
                 "used). The sketches fig1, fig2 and the sequences of intervals are recomputed as always. A figure with none of "
                 "its runs stored, or a free-space count missing, fails (exit 2)");
  sub_->add_flag("--print-sweeps", impl_->print_sweeps,
                 "print the `granchain sweep` commands of the chosen figures' driven-column runs (for mpirun or job arrays "
                 "into one store; reproduce --db STORE then reuses every point) and run nothing");
  return {sub_, [impl_, db_option, out_option, threads_option, threads_text, time_limit_option, time_limit_text] {
            impl_->db_given = db_option->count() > 0;  // for the reports' Command: lines
            impl_->out_given = out_option->count() > 0;
            return execute_reproduce(impl_, threads_option->count() > 0 ? threads_text.get() : nullptr,
                                     time_limit_option->count() > 0 ? time_limit_text.get() : nullptr);
          }};
}

}  // namespace granchain
