#include <fmt/format.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>

#include "cli/interrupt_message.hpp"
#include "config/input_error.hpp"
#include "provenance.hpp"
#include "store/output_file.hpp"
#include "reproduce/store_analysis.hpp"
#include "cli/row_filters.hpp"
#include "cli/subcommand.hpp"
#include "cli/exit_codes.hpp"
#include "engines/engine_registry.hpp"
#include "store/results_store.hpp"

namespace granchain {

namespace {

struct AnalyzeFlags {
  std::string db = "granchain.db", engine, pool_engines, json_path, plot_prefix;
  RowFilters filters;
  double k_min = 0;
  CLI::Option* json_option = nullptr;
  bool quiet = false;
};

int execute_analyze(const std::shared_ptr<AnalyzeFlags>& impl_);

// --pool-engines: two or more distinct engines with a k axis (soft spheres), comma-separated.
EnginePool parse_engine_pool(const std::string& text) {
  const auto refuse = [&text] {
    std::string soft;
    for (const EngineInfo& e : engines())
      if (!e.hard_spheres) soft += fmt::format("{}{}", soft.empty() ? "" : ", ", e.name);
    return InputError(fmt::format("--pool-engines = '{}' is not valid; valid: two or more distinct engines of {} "
                                  "(soft spheres, comma-separated)",
                                  text, soft));
  };
  EnginePool pool;
  std::size_t from = 0;
  while (from <= text.size()) {
    const std::size_t comma = std::min(text.find(',', from), text.size());
    const EngineInfo* e = find_engine(std::string_view(text).substr(from, comma - from));
    if (e == nullptr || e->hard_spheres || pool.pools(e->kind)) throw refuse();
    pool.members.push_back(e->kind);
    from = comma + 1;
  }
  if (pool.members.size() < 2) throw refuse();
  return pool;
}

}  // namespace

Subcommand add_analyze_command(CLI::App& app) {
  auto impl_ = std::make_shared<AnalyzeFlags>();
  CLI::App* sub_ = app.add_subcommand("analyze", "Fit stored n_coll(k), classify the regimes, and find e_c1, e_c2, A and alpha(N).");
  sub_->footer(
      "Reads the driven-column runs of the store, combines runs of one (engine, N, T0, e, k) by weighted mean,\n"
      "and for every (engine, N, T0, e) with at least 3 values of k >= --k-min fits n_coll = a + b log10 k and\n"
      "c k^alpha and classifies it (uncollapsing: b not > 2 errors; power-law: b > 0 and convex against\n"
      "log10 k; logarithmic: otherwise). Per (engine, N, T0): e_c1 (root of sqrt(b) against e), e_c2 (the\n"
      "convex/concave bracket), alpha bar (mean alpha at e = 0.1..0.4). Across N: (1 - e_c) = A/N and\n"
      "alpha bar = p log10 N + q, and that line through each interval of k's local alpha, with, at the same\n"
      "e, the slopes between neighbouring N and the largest N's excess over the line through the others. Criteria and\n"
      "errors: docs/analysis.md. The filters choose the runs: --k 1e6:1e10:x10 fits one window of k at\n"
      "every N, --T one window length.\n" +
      exit_codes_help("2 bad input or no usable store (nothing written), 4 an output could not be written"));
  sub_->add_option("--db", impl_->db, "results store to read; default granchain.db")->type_name("FILE");
  impl_->filters.add_to(sub_, "runs");
  sub_->add_option("--engine", impl_->engine, "only this engine (default: all, each analysed apart)");
  sub_->add_option("--pool-engines", impl_->pool_engines,
                   "analyse the runs of these engines as one (e.g. exact,reference), where they have been shown to agree: "
                   "a point's runs of either combine as its replicas, and the families are named exact+reference")
      ->type_name("LIST");
  sub_->add_option("--k-min", impl_->k_min, "start of the asymptotic range: only k >= k-min enters the fits; default 0");
  impl_->json_option = sub_->add_option("--json", impl_->json_path, "write the analysis as JSON to FILE, or to standard output")
                           ->expected(0, 1)
                           ->type_name("[FILE]");
  sub_->add_option("--plot", impl_->plot_prefix,
                   "draw n_coll against log k, log n_coll against log k, and n_coll against e for every (engine, N, T0) to "
                   "PREFIX_N<N>_T0<T0>_<engine>.png and .pdf (plots/ncoll_panels.py; the analysis JSON goes to PREFIX.json)")
      ->type_name("PREFIX");
  sub_->add_flag("--quiet,-q", impl_->quiet, "print no tables");
  return {sub_, [impl_] { return execute_analyze(impl_); }};
}

namespace {

int execute_analyze(const std::shared_ptr<AnalyzeFlags>& impl_) {
  auto& o = *impl_;
  const bool json_requested = o.json_option->count() > 0;
  const bool json_stdout = json_requested && (o.json_path.empty() || is_standard_output(o.json_path));
  ExportSelection sel;
  EnginePool pool;
  try {
    o.filters.apply(sel);
    if (!o.engine.empty()) sel.engines = {o.engine};
    if (!o.pool_engines.empty()) {
      if (!o.engine.empty())
        throw InputError(fmt::format("--pool-engines = '{}' and --engine = '{}' exclude each other: give one of them",
                                     o.pool_engines, o.engine));
      pool = parse_engine_pool(o.pool_engines);
    }
    if (!(o.k_min >= 0 && std::isfinite(o.k_min)))
      throw InputError(fmt::format("--k-min = {} is out of range; valid range: finite k-min >= 0", o.k_min));
    if (json_requested && !json_stdout) check_output_file(o.json_path, "--json", {{"--db", o.db}});
    if (!o.plot_prefix.empty())
      check_output_file(o.plot_prefix + ".json", "--plot", {{"--db", o.db}, {"--json", json_stdout ? "" : o.json_path}});
  } catch (const InputError& e) {
    fmt::print(stderr, "granchain: error: {}\n", e.what());
    return kExitBadInput;
  }
  StoreAnalysis a;
  try {
    a = analyze_store(o.db, sel, o.k_min, pool);
  } catch (const StoreError& e) {
    fmt::print(stderr, "granchain: error: {}\n", e.what());
    return kExitBadInput;
  }
  // Every file --plot and --json write, against the store and each other, before any is written.
  try {
    std::vector<NamedPath> outputs = {{"--json", json_requested && !json_stdout ? o.json_path : ""}};
    if (!o.plot_prefix.empty())
      for (const std::string& f : ncoll_panel_files(a, o.plot_prefix)) outputs.push_back({"--plot", f});
    check_outputs(outputs, {{"--db", o.db}});
  } catch (const InputError& e) {
    fmt::print(stderr, "granchain: error: {}\n", e.what());
    return kExitBadInput;
  }
  if (!o.plot_prefix.empty()) {
    announce_on_interrupt(fmt::format("the figures were not all drawn: those of {}_* that exist are whole, the store is "
                                      "unchanged; repeat the command", o.plot_prefix),
                          o.plot_prefix + ".json.tmp" + std::to_string(::getpid()));
    const std::string problem = draw_ncoll_panels(a, o.plot_prefix);
    if (!problem.empty()) {
      fmt::print(stderr, "granchain: error: {}\n", problem);
      return kExitStoreFailed;
    }
  }
  if (json_requested) {
    nlohmann::json j = a.json;
    j["provenance"] = provenance_json();
    const std::string text = j.dump(1) + "\n";
    try {
      if (json_stdout) {
        write_standard_output(text);
        return kExitOk;
      }
      write_file_atomically(o.json_path, text);
    } catch (const std::exception& e) {
      fmt::print(stderr, "granchain: error: {}\n", e.what());
      return kExitStoreFailed;
    }
  }
  if (!o.quiet) fmt::print("{}", analysis_text(a));
  return kExitOk;
}

}  // namespace

}  // namespace granchain
