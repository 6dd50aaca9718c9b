#pragma once
#include <CLI/CLI.hpp>
#include <memory>

namespace granchain {

// `granchain theory`: the paper's closed forms for inelastic collapse (src/theory/collapse_theory)
// for given N and e, as a table or JSON.
class TheoryCommand {
 public:
  explicit TheoryCommand(CLI::App& app);
  bool selected() const { return sub_->parsed(); }
  int execute();

 private:
  CLI::App* sub_;
  struct Impl;
  std::shared_ptr<Impl> impl_;
};

}  // namespace granchain
