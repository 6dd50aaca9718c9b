#include "cli/subcommand.hpp"
#include "cli/exit_codes.hpp"

#include <fmt/format.h>

#include "cli/interrupt_message.hpp"
#include "store/store_merge.hpp"

namespace granchain {

namespace {

struct MergeFlags {
  std::string into;
  std::vector<std::string> sources;
  bool quiet = false;
};

int execute_merge(const std::shared_ptr<MergeFlags>& impl_);

}  // namespace

Subcommand add_merge_command(CLI::App& app) {
  auto impl_ = std::make_shared<MergeFlags>();
  CLI::App* sub_;
  sub_ = app.add_subcommand("merge", "Join results stores (job-array shards, other machines) into one.");
  sub_->footer(
      "Every run (with its profiles and point key) and every collapse count (with its realisations) of the\n"
      "sources is copied into --into, which is created if missing, and every launch kept of a count not yet\n"
      "finished (table collapse_launches), so that the count continues from the target. A point held by both with identical\n"
      "results is kept once, so merging again is harmless; with different results the merge stops, names\n"
      "both runs and the first differing number, and writes nothing (exit 2). Sources are only read.\n"
      "Example (job array): granchain merge --into all.db shard-*.db\n" +
      exit_codes_help("2 bad input or conflicting results (nothing merged), 4 the target could not be written"));
  sub_->add_option("--into", impl_->into, "the store to merge into (created if missing)")->required()->type_name("FILE");
  sub_->add_option("sources", impl_->sources, "stores to merge from")->required()->type_name("FILE...");
  sub_->add_flag("--quiet,-q", impl_->quiet, "print nothing on success");
  return {sub_, [impl_] { return execute_merge(impl_); }};
}

namespace {

int execute_merge(const std::shared_ptr<MergeFlags>& impl_) {
  announce_on_interrupt(fmt::format("nothing was merged: the merge is one transaction, which SQLite rolls back when {} is "
                                    "next opened; the sources are untouched; repeat the command",
                                    impl_->into.empty() ? "--into" : impl_->into));
  try {
    const MergeReport r = merge_stores(impl_->into, impl_->sources);
    if (!impl_->quiet)
      fmt::print("merged {} store{} into {}: {} runs added, {} already there; {} collapse counts added, {} already there{}{}\n",
                 impl_->sources.size(), impl_->sources.size() == 1 ? "" : "s", impl_->into, r.runs_added,
                 r.runs_already_there, r.collapse_added, r.collapse_already_there,
                 r.collapsed_added + r.collapsed_already_there > 0
                     ? fmt::format("; {} collapsed hard-sphere points added, {} already there", r.collapsed_added, r.collapsed_already_there)
                     : "",
                 r.launches_added + r.launches_already_there > 0
                     ? fmt::format("; {} launches of unfinished counts added, {} already there", r.launches_added, r.launches_already_there)
                     : "");
    return kExitOk;
  } catch (const MergeWriteError& e) {
    fmt::print(stderr, "granchain: error: {}\n", e.what());
    return kExitStoreFailed;
  } catch (const StoreError& e) {
    fmt::print(stderr, "granchain: error: {}\n", e.what());
    return kExitBadInput;
  }
}

}  // namespace

}  // namespace granchain
