#include <fmt/format.h>

#include <filesystem>

#include <memory>

#include <cmath>
#include <map>

#include <unistd.h>

#include "cli/interrupt_message.hpp"
#include "config/input_error.hpp"
#include "store/output_file.hpp"
#include "reproduce/plot_script.hpp"
#include "config/run_options.hpp"
#include "cli/subcommand.hpp"
#include "engines/engine.hpp"
#include "simulation/trajectory.hpp"

namespace granchain {

namespace {

struct TraceFlags {
  std::map<std::string, std::string> values;  // run parameters given as flags
  std::map<std::string, CLI::Option*> options;
  std::string setup = "driven", output = "trace.csv", events_path, plot_path;
  double from = 0, to = 1, dt = 1e-3, a = 1, v0 = 1, dv0 = 0.1;
  long long realization = 0;
};

int execute_trace(const std::shared_ptr<TraceFlags>& impl_);

}  // namespace

Subcommand add_trace_command(CLI::App& app) {
  auto impl_ = std::make_shared<TraceFlags>();
  CLI::App* sub_ = app.add_subcommand("trace", "Record the heights z_i(t) of every particle over a time window (space-time diagram).");
  sub_->footer(
      "Driven column (default): the trajectory of `granchain run` with the same parameters and seed.\n"
      "--setup free: launch --realization of `granchain collapse` (free space, Sec. III.D).\n"
      "Writes CSV (t, z1, ..., zN) sampled every --dt in [--from, --to]; --events FILE adds every contact\n"
      "begin/end and floor hit of the window; --plot PNG draws z_i(t) (PNG and PDF) with Debian's python3.");
  for (const Parameter& p : run_parameters())
    if (p.uses & kUseTrace) impl_->options[p.name] = sub_->add_option("--" + p.name, impl_->values[p.name], p.help())->type_name(p.type_name());
  sub_->add_option("--setup", impl_->setup, "driven (default) or free");
  sub_->add_option("--from", impl_->from, "start of the window; >= 0; default 0");
  sub_->add_option("--to", impl_->to, "end of the window; > from; default 1");
  sub_->add_option("--dt", impl_->dt, "sampling interval; > 0, at most 1e7 samples; default 1e-3");
  sub_->add_option("--a", impl_->a, "free space: initial spacing; default 1");
  sub_->add_option("--v0", impl_->v0, "free space: launch speed; default 1");
  sub_->add_option("--dv0", impl_->dv0, "free space: random velocity amplitude; default 0.1");
  sub_->add_option("--realization", impl_->realization, "free space: launch number; >= 0; default 0");
  sub_->add_option("--output,-o", impl_->output, "CSV file of the samples; default trace.csv")->type_name("FILE");
  sub_->add_option("--events", impl_->events_path, "CSV file of the window's events")->type_name("FILE");
  sub_->add_option("--plot", impl_->plot_path, "draw the space-time diagram to this PNG (and a PDF beside it)")->type_name("FILE");
  return {sub_, [impl_] { return execute_trace(impl_); }};
}

namespace {

int execute_trace(const std::shared_ptr<TraceFlags>& impl_) {
  auto& o = *impl_;
  TraceSpec spec;
  try {
    std::map<std::string, RawValue> raw;
    for (const auto& [name, opt] : o.options)
      if (opt->count() > 0) raw[name] = RawValue{o.values[name], ""};
    if (o.setup != "driven" && o.setup != "free")
      throw InputError(fmt::format("--setup = '{}' is not a set-up; valid: driven, free", o.setup));
    const EngineInfo* named = raw.count("engine") ? find_engine(raw["engine"].text()) : nullptr;
    if (named != nullptr && named->hard_spheres)
      throw InputError("--engine: trace needs a soft engine (exact or reference); hard spheres have no overlaps to draw");
    spec.run = resolve_run_options(raw).spec;
    spec.free_space = o.setup == "free";
    spec.launch = {o.a, o.v0, o.dv0};
    spec.realization = static_cast<int>(o.realization);
    spec.t_from = o.from;
    spec.t_to = o.to;
    spec.dt = o.dt;
    if (!(o.from >= 0 && o.from < 1e15)) throw InputError(fmt::format("--from = {} is out of range; valid range: 0 <= from < 1e15", o.from));
    if (!(o.to > o.from && o.to <= 1e15))
      throw InputError(fmt::format("--to = {} is out of range; valid range: from = {} < to <= 1e15", o.to, o.from));
    // Samples and contacts must be resolved by the clock at --to, as a run's are at transient + T.
    if (!(o.dt >= shortest_resolved_time(o.to)))
      throw InputError(fmt::format("--dt = {} is out of range; valid range: dt >= {:.3g} at to = {} (1e6 times the clock's "
                                   "resolution there)", o.dt, shortest_resolved_time(o.to), o.to));
    const bool fine = engine_info(spec.run.engine.kind).fine_clock;
    if (!engine_info(spec.run.engine.kind).hard_spheres &&
        !(spec.run.params.k <= largest_resolved_k(spec.run.params.m, spec.run.params.e, o.to, fine)))
      throw InputError(fmt::format("--to = {} is out of range at k = {:g}: a contact must last at least 1e6 times the engine's "
                                   "clock resolution at to; valid range: k <= {:.3g} there", o.to, spec.run.params.k,
                                   largest_resolved_k(spec.run.params.m, spec.run.params.e, o.to, fine)));
    if (!(o.dt > 0) || (o.to - o.from) / o.dt > 1e7)
      throw InputError(fmt::format("--dt = {} is out of range; valid range: dt > 0 with (to - from)/dt <= 1e7", o.dt));
    // The trace holds every height in memory (and in its CSV): at most 1e8 values.
    if (spec.run.params.N * ((o.to - o.from) / o.dt + 1) > 1e8)
      throw InputError(fmt::format("--dt = {} is out of range; valid range: dt >= N (to - from) / 1e8 = {:.3g} (at most 1e8 heights "
                                   "in the trace)", o.dt, spec.run.params.N * (o.to - o.from) / 1e8));
    if (o.realization < 0 || o.realization > 1000000000)
      throw InputError(fmt::format("--realization = {} is out of range; valid range: 0 <= realization <= 1e9", o.realization));
    if (spec.free_space && !(o.v0 > 0 && o.a >= 0 && o.dv0 >= 0 && std::isfinite(o.v0) && std::isfinite(o.a) && std::isfinite(o.dv0)))
      throw InputError("--a, --v0, --dv0: valid ranges a >= 0, v0 > 0, dv0 >= 0");
    std::string plot_pdf;  // plots/spacetime.py writes the PNG and a PDF beside it
    if (!o.plot_path.empty()) {
      const std::filesystem::path png(o.plot_path);
      if (png.extension() != ".png" || png.stem().empty())
        throw InputError(fmt::format("--plot: '{}' must name a PNG file (NAME.png); the PDF is written beside it", o.plot_path));
      plot_pdf = std::filesystem::path(png).replace_extension(".pdf").string();
    }
    check_outputs({{"--output", o.output}, {"--events", o.events_path}, {"--plot", o.plot_path}, {"--plot (its PDF)", plot_pdf}}, {});
  } catch (const InputError& e) {
    fmt::print(stderr, "granchain: error: {}\n", e.what());
    return kExitBadInput;
  }
  const std::string tmp_suffix = ".tmp" + std::to_string(::getpid());
  announce_on_interrupt(fmt::format("the trace was not finished; {} was not written", o.output),
                        {o.output + tmp_suffix, o.events_path.empty() ? "" : o.events_path + tmp_suffix});
  Trajectory tr;
  try {
    tr = record_trajectory(spec);
  } catch (const UnphysicalStateError& e) {
    fmt::print(stderr, "granchain: error: the simulation became unphysical: {}; nothing was written\n", e.what());
    return kExitUnphysical;
  }
  try {  // both files or neither: each is written in full before either is put in place
    PendingFile samples(o.output, samples_csv(tr), "--output");
    std::unique_ptr<PendingFile> events;
    if (!o.events_path.empty()) events = std::make_unique<PendingFile>(o.events_path, events_csv(tr), "--events");
    samples.commit();
    if (events) events->commit();
    announce_on_interrupt(fmt::format("the trace is written ({}{}); the figure may be missing or incomplete", o.output,
                                      o.events_path.empty() ? "" : ", " + o.events_path));
  } catch (const std::exception& e) {
    fmt::print(stderr, "granchain: error: {}\n", e.what());
    return kExitStoreFailed;
  }
  fmt::print("{} samples of {} particles in [{:g}, {:g}], {} events: {}\n", tr.t.size(), spec.run.params.N, spec.t_from,
             spec.t_to, tr.events.size(), o.output);
  if (!o.plot_path.empty()) {
    const std::string title = fmt::format("N = {}, e = {:g}, k = {:g}, {}{}", spec.run.params.N, spec.run.params.e,
                                          spec.run.params.k, spec.free_space ? "free space" : "driven column",
                                          fmt::format(", seed {}", spec.run.seed));
    const std::string problem = run_plot_script("spacetime.py", {o.output, o.plot_path, title});
    if (!problem.empty()) {
      fmt::print(stderr, "granchain: error: --plot: {}; the CSV is written\n", problem);
      return kExitStoreFailed;
    }
    fmt::print("plot: {} (and PDF)\n", o.plot_path);
  }
  return kExitOk;
}

}  // namespace

}  // namespace granchain
