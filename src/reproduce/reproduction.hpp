#pragma once
// The paper's figures and Table 1 as a list, and the reproduction of a chosen set of them: each
// figure's runs, analysis, drawing and report (reproduce/*_figures.cpp), and the report of all.
#include <functional>
#include <string>
#include <vector>

#include "reproduce/figures.hpp"

namespace granchain {

struct FigureEntry {
  const char* name;   // --figure
  const char* label;  // the paper's LaTeX label
  FigureOutcome (*run)(const ReproduceFlags&, ReproductionLog&);
  std::vector<GridBlock> (*grid)(const ReproduceFlags&);  // its driven-column sweeps, or null
  const char* group = "all";  // all: the paper's figures; beyond: past the paper (the k -> infinity limit)
  std::vector<CollapseSpec> (*counts)(const ReproduceFlags&) = nullptr;  // its free-space counts, or null
};

// fig1 ... fig10 and table1 in the paper's order, then the group beyond (limit-free, limit-driven,
// intervals).
const std::vector<FigureEntry>& figures();
// The figures `figure` names: one figure, or a group ("all": the paper's; "beyond"); empty when it
// names none.
std::vector<const FigureEntry*> chosen_figures(const std::string& figure);
bool is_figure_group(const std::string& figure);
// "fig1, fig2, ..., table1, limit-free, ..., " for messages.
std::string figure_names();

// report.md for Fig. 5 (the main job's), report-<figure>.md for the others, report-all.md and
// report-beyond.md for the groups.
std::string report_name(const std::string& figure);

// The sweeps behind the chosen figures as `granchain sweep` commands, each grid block once,
// with their predicted CPU time, one per line.
std::string sweep_commands(const std::vector<const FigureEntry*>& chosen, const ReproduceFlags& o);

// One figure as run_figures ran it: its outcome, the report it wrote ("" if none) and its wall time.
struct FigureReport {
  const FigureEntry* figure = nullptr;
  FigureOutcome outcome;
  std::string report_path;
  double wall_seconds = 0;
};

struct ReproductionOutcome {
  // With --time-limit, the computing before any figure: a status other than Done ended the
  // command there (no figure drawn).
  FigureOutcome computing;
  std::vector<FigureReport> figures;  // in order; the last is TimeLimit when the limit stopped them
  std::string group_report;           // report-all.md or report-beyond.md for a group, when written
  std::string group_report_error;     // why it could not be written
};

// Runs the chosen figures in order (o validated, o.threads resolved): each writes its report into
// o.out and is handed to on_figure as it ends; a group's report joins them. Figures fail one by one
// (their status says how); a time limit stops the rest.
ReproductionOutcome run_figures(const std::vector<const FigureEntry*>& chosen, const ReproduceFlags& o,
                                const std::function<void(const FigureReport&)>& on_figure = {});

}  // namespace granchain
