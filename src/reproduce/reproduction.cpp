// The reproduction of the paper's figures: the list of figures, their sweeps as commands, and
// running a chosen set with its reports. The figures themselves live in sketch_figures.cpp (fig1,
// fig2), ncoll_figures.cpp (fig3, fig4, fig5, fig8), across_n_figures.cpp (fig6, fig7, fig9,
// table1), free_space_figures.cpp (fig10), and past the paper hard_limit_figures.cpp (limit-free,
// limit-driven), interval_figures.cpp (intervals) and driven_hard_limit_figure.cpp (limit-hard), the
// vibrating plates in drive_figures.cpp and the contacts of the columns in contact_figure.cpp.
#include "reproduce/reproduction.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <set>

#include "store/output_file.hpp"
#include "engines/engine.hpp"
#include "store/results_store.hpp"
#include "sweep/sweep_progress.hpp"

namespace granchain {

const std::vector<FigureEntry>& figures() {
  static const std::vector<FigureEntry> list = {
      {"fig1", "1dmodel", reproduce_model_sketch, nullptr},
      {"fig2", "threebodycollapse", reproduce_three_body, nullptr},
      {"fig3", "cflogk", reproduce_ncoll_figure, ncoll_grid},
      {"fig4", "cfe", reproduce_ncoll_figure, ncoll_grid},
      {"fig5", "cfreqlogN25", reproduce_ncoll_figure, ncoll_grid},
      {"fig6", "bifurcationdiagram", reproduce_bifurcation, across_n_grid},
      {"fig7", "logfitbX", reproduce_scaling_collapse, across_n_grid},
      {"fig8", "partial_cond", reproduce_partial_condensation, partial_condensation_grid},
      {"fig9", "powerexpo", reproduce_alpha_vs_n, across_n_grid},
      {"fig10", "ntot", reproduce_free_space_counts, nullptr, "all", free_space_count_specs},
      {"table1", "table1", reproduce_table1, table1_grid},
      {"limit-free", "beyond: free-space n_tot as k -> infinity", reproduce_free_space_exponents, nullptr, "beyond",
       free_space_exponent_specs},
      {"limit-driven", "beyond: driven n_coll as k -> infinity", reproduce_driven_exponents, driven_limit_grid, "beyond"},
      {"intervals", "beyond: collision-interval sequences", reproduce_collision_intervals, nullptr, "beyond"},
      {"limit-hard", "beyond: the driven column's hard-sphere limit", reproduce_hard_limit, hard_limit_grid, "beyond"},
      {"drives-onset", "drives: e_c1, e_c2 against N per drive", reproduce_drive_onset, drives_grid, "drives"},
      {"drives-ncoll", "drives: n_coll(k) at N = 25 per drive", reproduce_drive_ncoll, drives_grid, "drives"},
      {"drives-profiles", "drives: density, temperature and centre of mass of the vibrated column", reproduce_drive_profiles, nullptr,
       "drives"},
      {"contacts", "columns: contact durations against height per N", reproduce_contacts, contacts_grid, "columns"},
  };
  return list;
}

std::vector<const FigureEntry*> chosen_figures(const std::string& figure) {
  std::vector<const FigureEntry*> chosen;
  for (const FigureEntry& f : figures())
    if (figure == f.name || figure == f.group) chosen.push_back(&f);
  return chosen;
}

bool is_figure_group(const std::string& figure) { return figure == "all" || figure == "beyond" || figure == "drives" || figure == "columns"; }

std::string figure_names() {
  std::string names;
  for (const FigureEntry& f : figures()) names += fmt::format("{}, ", f.name);
  return names;
}

std::string report_name(const std::string& figure) { return figure == "fig5" ? "report.md" : "report-" + figure + ".md"; }

namespace {

// Runs one figure and writes its report; a typed failure ends it with that status and message.
FigureOutcome run_one(const FigureEntry& f, ReproduceFlags o, ReproductionLog& log) {
  o.figure = f.name;
  log.partial.clear();
  const auto failed = [](FigureStatus status, const std::exception& e) {
    FigureOutcome out;
    out.status = status;
    out.message = e.what();
    return out;
  };
  try {
    FigureOutcome out = f.run(o, log);
    std::string partial;
    for (const std::string& p : log.partial) partial += (partial.empty() ? "" : "; ") + p;
    if (!partial.empty())
      out.markdown = fmt::format("**Partial (--stored-only): drawn from the runs stored so far — {}. Not a result.**\n\n", partial) +
                     out.markdown;
    out.markdown = fmt::format("# {} ({}), preset {}\n\n", f.name, f.label, o.preset) + out.markdown;
    write_output(output_path(o, report_name(f.name)), out.markdown);
    return out;
  } catch (const NothingStored& e) {
    return failed(FigureStatus::NothingStored, e);
  } catch (const TimeLimitReached& e) {
    return failed(FigureStatus::TimeLimit, e);
  } catch (const StoreError& e) {
    return failed(FigureStatus::StoreFailed, e);
  } catch (const UnphysicalStateError& e) {
    return failed(FigureStatus::Unphysical, e);
  } catch (const OutputError& e) {
    return failed(FigureStatus::OutputFailed, e);
  } catch (const std::exception& e) {  // its analysis could not be done (too few points for a fit, ...)
    return failed(FigureStatus::Failed, e);
  }
}

}  // namespace

// The sweeps behind the chosen figures as `granchain sweep` commands, each grid block once.
std::string sweep_commands(const std::vector<const FigureEntry*>& chosen, const ReproduceFlags& flags) {
  std::string text;
  std::set<std::string> seen;
  std::vector<GridBlock> blocks;
  ReproduceFlags o = flags;
  for (const FigureEntry* f : chosen) {
    if (!f->grid) continue;
    o.figure = f->name;
    for (const GridBlock& b : f->grid(o)) {
      const std::string line = sweep_command(b);
      if (!seen.insert(line).second) continue;
      blocks.push_back(b);
      double seconds = 0.0;
      const std::vector<SweepPoint> points = grid_points({b});
      for (const SweepPoint& p : points) seconds += p.cost;
      text += fmt::format("# {} points, predicted {:.2g} CPU-hours (sweep/cost_model.hpp)\n{}\n", points.size(), seconds / 3600, line);
    }
  }
  double total = 0.0;
  const std::vector<SweepPoint> all = blocks.empty() ? std::vector<SweepPoint>{} : grid_points(blocks);
  for (const SweepPoint& p : all) total += p.cost;
  text += fmt::format("# {} distinct points, predicted {:.2g} CPU-hours in all; add --db STORE (and mpirun -np P, or --shard i/n and granchain merge), then: "
             "granchain reproduce --figure {} --preset {} --db STORE\n",
             all.size(), total / 3600, flags.figure, flags.preset);
  return text;
}


namespace {

// With --time-limit, every run and count the chosen figures need is computed before any figure is
// drawn, so that the limit is spent on computing only: a repeat after a time limit always stores
// what the last one could not, never redraws finished figures in the time it needs. Done when
// everything is stored; TimeLimit when the limit came first; StoreFailed or Unphysical.
FigureOutcome compute_within_time_limit(const std::vector<const FigureEntry*>& chosen, const ReproduceFlags& o, ReproductionLog& log) {
  FigureOutcome out;
  try {
    for (const FigureEntry* f : chosen)
      if (f->grid) {
        ReproduceFlags fo = o;
        fo.figure = f->name;
        for (std::string& p : run_missing_points(grid_points(f->grid(fo)), fo, f->name, log)) out.failed_points.push_back(std::move(p));
      }
    for (const FigureEntry* f : chosen)
      if (f->counts) {
        ReproduceFlags fo = o;
        fo.figure = f->name;
        for (const CollapseSpec& spec : f->counts(fo)) stored_or_run_collapse(spec, fo, f->name);
      }
  } catch (const TimeLimitReached& e) {
    out.status = FigureStatus::TimeLimit;
    out.message = e.what();
  } catch (const StoreError& e) {
    out.status = FigureStatus::StoreFailed;
    out.message = e.what();
  } catch (const UnphysicalStateError& e) {
    out.status = FigureStatus::Unphysical;
    out.message = e.what();
  }
  return out;
}

}  // namespace

ReproductionOutcome run_figures(const std::vector<const FigureEntry*>& chosen, const ReproduceFlags& o,
                                const std::function<void(const FigureReport&)>& on_figure) {
  ReproductionOutcome result;
  ReproductionLog log;
  if (o.time_limit > 0 && !o.stored_only) {
    result.computing = compute_within_time_limit(chosen, o, log);
    if (result.computing.status != FigureStatus::Done) return result;
  }
  std::string all = fmt::format("# {}\n\n"
      "| figure | label | result | wall time | its runs' CPU time, summed |\n|---|---|---|---|---|\n", reproduce_command_line(o));
  std::string sections;
  for (const FigureEntry* f : chosen) {
    const auto start = std::chrono::steady_clock::now();
    FigureReport report{f, run_one(*f, o, log), "", 0.0};
    report.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const FigureOutcome& out = report.outcome;
    if (!out.markdown.empty()) report.report_path = output_path(o, report_name(f->name));
    result.figures.push_back(report);
    if (on_figure) on_figure(report);
    if (out.status == FigureStatus::TimeLimit) return result;  // the later figures wait for the repeat too
    const bool drawn = out.status == FigureStatus::Done || out.status == FigureStatus::PointsFailed;
    all += fmt::format("| {} | {} | {} | {} | {} |\n", f->name, f->label,
                       !drawn ? "failed" : out.status == FigureStatus::Done ? "done" : "done, points failed",
                       format_duration(report.wall_seconds), out.run_seconds >= 0 ? format_duration(out.run_seconds) : "-");
    // One level down: the figure's title becomes a section of the whole report.
    if (!out.markdown.empty()) sections += "\n#" + out.markdown;
  }
  if (is_figure_group(o.figure)) {
    if (o.stored_only)
      all += "\n--stored-only: nothing was run; each figure is drawn from those of its runs that were stored (its section "
             "gives how many).\n";
    all += "\nWall time: this command's, for the figure (runs already stored are only read). Its runs' CPU time: the "
           "stored CPU time of each driven-column run the figure analyses (the wall time for runs stored before CPU time "
           "was recorded: stretched where the machine was loaded), summed over the sittings that ran them; figures that "
           "share runs (fig6, fig7, fig9 and Table 1's k_B T0 = 1; fig5 and fig8; drives-onset and drives-ncoll's N = 25) "
           "count them in each.\n";
    try {
      write_output(output_path(o, report_name(o.figure)), all + sections);
      result.group_report = output_path(o, report_name(o.figure));
    } catch (const OutputError& e) {
      result.group_report_error = e.what();
    }
  }
  return result;
}

}  // namespace granchain
