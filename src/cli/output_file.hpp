#pragma once
#include <string>

namespace granchain {

// Before anything runs: throws InputError "<option>: <why>" if path cannot be created.
void check_output_file(const std::string& path, const std::string& option = "--json");

// Writes the whole file or nothing: a temporary file renamed into place. Throws
// std::runtime_error "<option>: cannot write '<path>'" on failure.
void write_file_atomically(const std::string& path, const std::string& text, const std::string& option = "--json");

}  // namespace granchain
