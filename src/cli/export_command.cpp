#include "cli/row_filters.hpp"
#include "cli/subcommand.hpp"
#include "cli/exit_codes.hpp"

#include <fmt/format.h>

#include <unistd.h>

#include "cli/interrupt_message.hpp"
#include "config/input_error.hpp"
#include "store/output_file.hpp"
#include "config/value_list.hpp"
#include "store/results_store.hpp"
#include "store/store_export.hpp"

namespace granchain {

namespace {

struct ExportFlags {
  std::string db = "granchain.db", table = "runs", format, output, where, engine;
  RowFilters filters;
};

int execute_export(const std::shared_ptr<ExportFlags>& impl_);

}  // namespace

Subcommand add_export_command(CLI::App& app) {
  auto impl_ = std::make_shared<ExportFlags>();
  CLI::App* sub_;
  sub_ = app.add_subcommand("export", "Write a selection of stored results as CSV or JSON, with all their parameters.");
  sub_->footer(
      "Tables: runs (one row per driven-column run: parameters, n_coll, rates with errors, cost, point key,\n"
      "sweep seed and replica), profiles (one row per particle of each run: <z_i>, sigma_i, K_i with errors,\n"
      "beside the run's parameters), collapse (one row per collapse count), realizations (one row per\n"
      "launch of a collapse count). Filters combine with AND; values match within 1e-12 relative.\n"
      "Examples:  granchain export --N 25 --e 0.8:0.9:0.002 --output n25.csv\n"
      "           granchain export --table profiles --where \"e > 0.85 AND k >= 1e8\" --format json\n" +
      exit_codes_help("2 bad input (nothing written), 4 the output could not be written"));
  auto& o = *impl_;
  sub_->add_option("--db", o.db, "results store to read; default granchain.db")->type_name("FILE");
  sub_->add_option("--table", o.table, "runs (default), profiles, collapse or realizations");
  sub_->add_option("--format", o.format, "csv or json; default from the --output extension, else csv");
  sub_->add_option("--output,-o", o.output, "write to FILE (whole or not at all) instead of standard output")->type_name("FILE");
  o.filters.add_to(sub_, "rows");
  sub_->add_option("--engine", o.engine, "only rows of these engines (comma list)")->type_name("LIST");
  sub_->add_option("--where", o.where, "only rows meeting this SQL condition on the exported columns")->type_name("SQL");
  return {sub_, [impl_] { return execute_export(impl_); }};
}

namespace {

int execute_export(const std::shared_ptr<ExportFlags>& impl_) {
  auto& o = *impl_;
  ExportSelection sel;
  ExportFormat format = ExportFormat::Csv;
  try {
    const std::map<std::string, ExportTable> tables = {{"runs", ExportTable::Runs}, {"profiles", ExportTable::Profiles},
                                                       {"collapse", ExportTable::Collapse},
                                                       {"realizations", ExportTable::Realizations}};
    if (!tables.count(o.table))
      throw InputError(fmt::format("--table = '{}' is not a table; valid: runs, profiles, collapse, realizations", o.table));
    sel.table = tables.at(o.table);
    std::string f = o.format;
    if (f.empty()) f = o.output.size() >= 5 && o.output.substr(o.output.size() - 5) == ".json" ? "json" : "csv";
    if (f != "csv" && f != "json") throw InputError(fmt::format("--format = '{}' is not a format; valid: csv, json", f));
    format = f == "json" ? ExportFormat::Json : ExportFormat::Csv;
    const bool collapse = sel.table == ExportTable::Collapse || sel.table == ExportTable::Realizations;
    for (const char* name : {"T0", "T"})
      if (collapse && o.filters.given(name))
        throw InputError(fmt::format("--{}: collapse counts have no {}; valid filters for --table {}: N, e, k, engine, where",
                                     name, name, o.table));
    o.filters.apply(sel);
    sel.engines = parse_name_list(o.engine);
    sel.where = o.where;
    if (is_standard_output(o.output)) o.output.clear();
    if (!o.output.empty()) check_output_file(o.output, "--output", {{"--db", o.db}});
  } catch (const InputError& e) {
    fmt::print(stderr, "granchain: error: {}\n", e.what());
    return kExitBadInput;
  }
  announce_on_interrupt(o.output.empty() ? "the export was not finished; what was printed is incomplete; the store is unchanged"
                                          : fmt::format("the export was not finished; {} was not written; the store is unchanged", o.output),
                        o.output.empty() ? "" : o.output + ".tmp" + std::to_string(::getpid()));
  std::string text;
  try {
    text = export_results(o.db, sel, format);
  } catch (const StoreError& e) {
    fmt::print(stderr, "granchain: error: {}\n", e.what());
    return kExitBadInput;
  }
  if (o.output.empty()) {
    try {
      write_standard_output(text);
    } catch (const std::exception& e) {
      fmt::print(stderr, "granchain: error: {}\n", e.what());
      return kExitStoreFailed;
    }
    return kExitOk;
  }
  try {
    write_file_atomically(o.output, text, "--output");
  } catch (const std::exception& e) {
    fmt::print(stderr, "granchain: error: {}\n", e.what());
    return kExitStoreFailed;
  }
  return kExitOk;
}

}  // namespace

}  // namespace granchain
