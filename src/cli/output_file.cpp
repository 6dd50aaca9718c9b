#include "cli/output_file.hpp"

#include "cli/input_error.hpp"
#include "store/results_store.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace granchain {

void check_output_file(const std::string& path, const std::string& option) {
  const std::string reason = cannot_create_file_reason(path);
  if (!reason.empty()) throw InputError(option + ": " + reason);
}

void write_file_atomically(const std::string& path, const std::string& text, const std::string& option) {
  const std::string tmp = path + ".tmp" + std::to_string(::getpid());
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    f << text;
    f.flush();
    if (!f) {
      std::remove(tmp.c_str());
      throw std::runtime_error(fmt::format("{}: cannot write '{}'", option, path));
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw std::runtime_error(fmt::format("{}: cannot write '{}'", option, path));
  }
}

}  // namespace granchain
