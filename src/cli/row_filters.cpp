#include "cli/row_filters.hpp"

#include <fmt/format.h>

#include "config/value_list.hpp"

namespace granchain {

void RowFilters::add_to(CLI::App* sub, const std::string& rows) {
  for (const char* name : {"N", "e", "k", "T0", "T"})
    options_[name] = sub->add_option(std::string("--") + name, text_[name], fmt::format("only {} with {} in this list or range", rows, name))
                         ->type_name("LIST");
}

void RowFilters::apply(ExportSelection& sel) const {
  for (const auto& [name, opt] : options_)
    if (opt->count() > 0) sel.values[name] = parse_value_list(text_.at(name), "--" + name);
}

}  // namespace granchain
