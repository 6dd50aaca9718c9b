#pragma once
// Parameter files for `granchain run --config FILE`: a flat JSON object or a flat TOML table,
// keys named like the command-line flags (without "--"; "-" and "_" are interchangeable).
//   JSON:  {"N": 25, "e": 0.88, "k": 1e8, "engine": "reference"}
//   TOML:  N = 25      # comments allowed
//          e = 0.88
//          engine = "reference"
// The format is taken from the extension (.json / .toml), otherwise from the first character.
#include <map>
#include <string>

#include "config/parameter.hpp"

namespace granchain {

// key (flag spelling) -> value: integers and reals typed as the file types them (N = 3 an
// integer, N = 3.0 a real, which an integer parameter refuses), strings and booleans as text;
// arrays ([3, 4, 5] or ["exact", "hard"]) become comma lists, as a sweep's flags write them.
// Throws InputError naming the file and line on any problem; option names the flag in messages.
std::map<std::string, RawValue> read_config_file(const std::string& path, const std::string& option = "--config");

// Flag spelling of a key: underscores become dashes.
std::string normalize_key(std::string key);

}  // namespace granchain
