#include "cli/config_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/input_error.hpp"

namespace granchain {

std::string normalize_key(std::string key) {
  std::replace(key.begin(), key.end(), '_', '-');
  return key;
}

namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

std::map<std::string, std::string> parse_json(const std::string& path, const std::string& text) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(fmt::format("--config: '{}' is not valid JSON (byte {})", path, e.byte));
  }
  if (!j.is_object()) throw InputError(fmt::format("--config: '{}' must hold one JSON object of parameters", path));
  std::map<std::string, std::string> out;
  for (const auto& [key, value] : j.items()) {
    std::string v;
    if (value.is_string()) {
      v = value.get<std::string>();
    } else if (value.is_number_integer() || value.is_number_unsigned()) {
      v = value.dump();
    } else if (value.is_number_float()) {
      v = fmt::format("{:.17g}", value.get<double>());
    } else if (value.is_boolean()) {
      v = value.get<bool>() ? "true" : "false";
    } else {
      throw InputError(fmt::format("--config: '{}': value of '{}' must be a number or a string", path, key));
    }
    out[normalize_key(key)] = v;
  }
  return out;
}

std::map<std::string, std::string> parse_toml(const std::string& path, const std::string& text) {
  std::map<std::string, std::string> out;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    // Strip a comment that is not inside a quoted string.
    bool quoted = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
      if (line[i] == '"') quoted = !quoted;
      if (line[i] == '#' && !quoted) {
        line.resize(i);
        break;
      }
    }
    line = trim(line);
    if (line.empty()) continue;
    if (line.front() == '[')
      throw InputError(fmt::format("--config: '{}' line {}: tables/sections are not supported; use flat 'key = value'", path, number));
    const auto eq = line.find('=');
    if (eq == std::string::npos)
      throw InputError(fmt::format("--config: '{}' line {}: expected 'key = value'", path, number));
    std::string key = trim(line.substr(0, eq));
    std::string value = trim(line.substr(eq + 1));
    if (key.empty() || value.empty())
      throw InputError(fmt::format("--config: '{}' line {}: expected 'key = value'", path, number));
    if (value.front() == '"') {
      if (value.size() < 2 || value.back() != '"')
        throw InputError(fmt::format("--config: '{}' line {}: unterminated string", path, number));
      value = value.substr(1, value.size() - 2);
    }
    key = normalize_key(key);
    if (out.count(key)) throw InputError(fmt::format("--config: '{}' line {}: '{}' is set twice", path, number, key));
    out[key] = value;
  }
  return out;
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

std::map<std::string, std::string> read_config_file(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw InputError(fmt::format("--config: cannot read '{}'", path));
  std::stringstream ss;
  ss << f.rdbuf();
  if (f.bad()) throw InputError(fmt::format("--config: cannot read '{}'", path));
  const std::string text = ss.str();
  if (ends_with(path, ".json")) return parse_json(path, text);
  if (ends_with(path, ".toml")) return parse_toml(path, text);
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first != std::string::npos && text[first] == '{') return parse_json(path, text);
  return parse_toml(path, text);
}

}  // namespace granchain
