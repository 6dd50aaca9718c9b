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
#include "config/trace_options.hpp"
#include "cli/subcommand.hpp"
#include "cli/exit_codes.hpp"
#include "engines/engine.hpp"
#include "simulation/trajectory.hpp"

namespace granchain {

namespace {

struct TraceFlags {
  std::map<std::string, std::string> values;  // run parameters and the trace's own, as given
  std::map<std::string, CLI::Option*> options;
  std::string output = "trace.csv", events_path, plot_path;
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
      "begin/end and floor hit of the window; --plot PNG draws z_i(t) (PNG and PDF) with Debian's python3.\n" +
      exit_codes_help("2 bad input (nothing written), 3 unphysical (nothing written), 4 an output could not be written"));
  for (const std::vector<Parameter>* table : {&run_parameters(), &trace_window_parameters()})
    for (const Parameter& p : *table)
      if (p.uses & kUseTrace) impl_->options[p.name] = sub_->add_option("--" + p.name, impl_->values[p.name], p.help())->type_name(p.type_name());
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
    spec = resolve_trace_spec(raw);
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
