#pragma once
// The value filters `export` and `analyze` share: --N, --e, --k, --T0, --T, each a list or range
// (config/value_list.hpp) that a stored row's column must match (store/store_export.hpp).
#include <CLI/CLI.hpp>

#include <map>
#include <string>

#include "store/store_export.hpp"

namespace granchain {

class RowFilters {
 public:
  // Registers --N, --e, --k, --T0 and --T on sub; `rows` names what they select ("rows", "runs").
  void add_to(CLI::App* sub, const std::string& rows);
  bool given(const std::string& name) const { return options_.at(name)->count() > 0; }
  // Puts every given filter into sel.values; throws InputError naming the flag of a bad list.
  void apply(ExportSelection& sel) const;

 private:
  std::map<std::string, std::string> text_;
  std::map<std::string, CLI::Option*> options_;
};

}  // namespace granchain
