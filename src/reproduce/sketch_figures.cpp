// `granchain reproduce` for the paper's two schematic figures, drawn here from simulated
// trajectories: Fig. 1dmodel (fig1: the driven column) and Fig. threebodycollapse (fig2: three
// particles collapsing in free space, with the geometric intervals of Eq. deltat12).
#include <fmt/format.h>

#include <cmath>
#include <map>

#include "reproduce/figures.hpp"
#include "model/chain_parameters.hpp"
#include "simulation/trajectory.hpp"
#include "theory/collapse_theory.hpp"

namespace granchain {

namespace {

// A trajectory of N particles (e, k, seed 1, exact engine) sampled every dt over [from, to].
TraceSpec window_of(int N, double e, double k, double from, double to, double dt) {
  TraceSpec spec;
  spec.run.params.N = N;
  spec.run.params.e = e;
  spec.run.params.k = k;
  spec.run.seed = 1;
  spec.t_from = from;
  spec.t_to = to;
  spec.dt = dt;
  return spec;
}

}  // namespace

// Fig. 1dmodel: the slope flow reduced to one line perpendicular to the slope (a sketch), a snapshot
// of a simulated column of N = 25 above its thermal floor, and that column's z_i(t).
FigureOutcome reproduce_model_sketch(const ReproduceFlags& o, ReproductionLog&) {
  const TraceSpec spec = window_of(25, 0.9, 1e6, 40, 50, 0.005);
  const Trajectory tr = record_trajectory(spec);
  const std::string prefix = output_path(o, "fig1");
  write_output(prefix + "-trace.csv", samples_csv(tr));
  draw("model_sketch.py", {prefix + "-trace.csv", prefix});
  int floor_hits = 0, contacts = 0;
  for (const Event& e : tr.events) {
    floor_hits += e.kind == EventKind::FloorHit;
    contacts += e.kind == EventKind::ContactEnd;
  }
  FigureOutcome out{FigureStatus::Done, "", prefix + ".png (and .pdf)", -1.0, "", {}};
  out.markdown = fmt::format(
      "Command: `{}`. The paper's Fig. 1 is a schematic. Here: (a) a sketch of the slope flow and "
      "the line z perpendicular to the slope, (b) the model — N = 25 spheres of diameter d = 1 on a vertical line under gravity "
      "g = 1, the bottom one driven by a thermal floor at k_B T0 = 1 — as a snapshot at t = {:g} of a simulated column "
      "(e = 0.9, k = 1e6, seed 1, exact engine), (c) z_i(t) of that column for {:g} ≤ t ≤ {:g}: {} collisions between "
      "neighbours and {} floor hits in the window. Data: `fig1-trace.csv`.\n",
      reproduce_command_line(o), spec.t_to, spec.t_from, spec.t_to, contacts, floor_hits);
  return out;
}

// Fig. threebodycollapse: N = 3 in free space (launch 0 of Sec. III.D) at e = 0.065 < e_c(3) and
// k = 1e14: z_i(t), and the intervals between successive collisions of the pair (1, 2), which
// shrink by the factor q of Eq. (def_q) until they reach the contact time.
FigureOutcome reproduce_three_body(const ReproduceFlags& o, ReproductionLog&) {
  TraceSpec spec = window_of(3, 0.065, 1e14, 0, 2.5, 1e-3);
  spec.free_space = true;  // launch 0 of Sec. III.D, no gravity
  spec.run.params.g = 0.0;
  spec.realization = 0;
  const Trajectory tr = record_trajectory(spec);
  const std::string prefix = output_path(o, "fig2");
  write_output(prefix + "-trace.csv", samples_csv(tr));
  write_output(prefix + "-events.csv", events_csv(tr));
  const double q = theory::q_ratio(spec.run.params.e);
  const double tau_c = contact_time(spec.run.params.k, damping_constant(spec.run.params.k, spec.run.params.e, 1.0), 1.0);
  draw("three_body.py", {prefix + "-trace.csv", prefix + "-events.csv", prefix, fmt::format("{:.17g}", q), fmt::format("{:.17g}", tau_c)});
  // The measured ratios of successive (1, 2) intervals, for the report.
  std::vector<double> t12;
  for (const Event& e : tr.events)
    if (e.kind == EventKind::ContactEnd && e.i == 0) t12.push_back(e.t);
  std::string ratios;
  for (std::size_t n = 2; n < t12.size() && n < 14; ++n)
    ratios += fmt::format("{}{:.4f}", ratios.empty() ? "" : ", ", (t12[n] - t12[n - 1]) / (t12[n - 1] - t12[n - 2]));
  int ends = 0;
  for (const Event& e : tr.events) ends += e.kind == EventKind::ContactEnd;
  FigureOutcome out{FigureStatus::Done, "", prefix + ".png (and .pdf)", -1.0, "", {}};
  out.markdown = fmt::format(
      "Command: `{}`. The paper's Fig. 2 is a schematic. Here a simulated three-body collapse in free "
      "space: launch 0 of Sec. III.D (a = v0 = 1, dv0 = 0.1, seed 1), e = 0.065 < e_c(3) = {:.4f}, k = 1e14 (τ_c = {:.3g}), exact "
      "engine: (a) z_i(t), (b) the intervals t12 between successive collisions of the pair (1, 2) against their index, with "
      "the ratio q = {:.4f} of Eq. (def_q) and τ_c. {} collisions in all; the ratios of successive t12: {}. They approach q "
      "and stop once t12 nears τ_c. Data: `fig2-trace.csv`, `fig2-events.csv`.\n",
      reproduce_command_line(o), theory::ec3(), tau_c, q, ends, ratios.empty() ? "-" : ratios);
  return out;
}

}  // namespace granchain
