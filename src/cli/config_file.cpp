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

std::map<std::string, std::string> parse_json(const std::string& path, const std::string& text, const std::string& option) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(fmt::format("{}: '{}' is not valid JSON (byte {})", option, path, e.byte));
  }
  if (!j.is_object()) throw InputError(fmt::format("{}: '{}' must hold one JSON object of parameters", option, path));
  std::map<std::string, std::string> out;
  for (const auto& [key, value] : j.items()) {
    std::string v;
    if (value.is_array()) {
      for (const auto& item : value) {
        if (!(item.is_string() || item.is_number()))
          throw InputError(fmt::format("{}: '{}': the list '{}' may hold only numbers and strings", option, path, key));
        v += (v.empty() ? "" : ",") + (item.is_string() ? item.get<std::string>()
                                       : item.is_number_float() ? fmt::format("{:.17g}", item.get<double>()) : item.dump());
      }
    } else if (value.is_string()) {
      v = value.get<std::string>();
    } else if (value.is_number_integer() || value.is_number_unsigned()) {
      v = value.dump();
    } else if (value.is_number_float()) {
      v = fmt::format("{:.17g}", value.get<double>());
    } else if (value.is_boolean()) {
      v = value.get<bool>() ? "true" : "false";
    } else {
      throw InputError(fmt::format("{}: '{}': value of '{}' must be a number or a string", option, path, key));
    }
    out[normalize_key(key)] = v;
  }
  return out;
}

std::map<std::string, std::string> parse_toml(const std::string& path, const std::string& text, const std::string& option) {
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
      throw InputError(fmt::format("{}: '{}' line {}: tables/sections are not supported; use flat 'key = value'", option, path, number));
    const auto eq = line.find('=');
    if (eq == std::string::npos)
      throw InputError(fmt::format("{}: '{}' line {}: expected 'key = value'", option, path, number));
    std::string key = trim(line.substr(0, eq));
    std::string value = trim(line.substr(eq + 1));
    if (key.empty() || value.empty())
      throw InputError(fmt::format("{}: '{}' line {}: expected 'key = value'", option, path, number));
    if (value.front() == '"') {
      if (value.size() < 2 || value.back() != '"')
        throw InputError(fmt::format("{}: '{}' line {}: unterminated string", option, path, number));
      value = value.substr(1, value.size() - 2);
    } else if (value.front() == '[') {  // an array of numbers or strings: a sweep's list
      if (value.back() != ']')
        throw InputError(fmt::format("{}: '{}' line {}: unterminated array", option, path, number));
      std::string items;
      for (char c : value.substr(1, value.size() - 2))
        if (c != '"' && c != ' ' && c != '\t') items += c;
      value = items;
    }
    key = normalize_key(key);
    if (out.count(key)) throw InputError(fmt::format("{}: '{}' line {}: '{}' is set twice", option, path, number, key));
    out[key] = value;
  }
  return out;
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

std::map<std::string, std::string> read_config_file(const std::string& path, const std::string& option) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw InputError(fmt::format("{}: cannot read '{}'", option, path));
  std::stringstream ss;
  ss << f.rdbuf();
  if (f.bad()) throw InputError(fmt::format("{}: cannot read '{}'", option, path));
  const std::string text = ss.str();
  if (ends_with(path, ".json")) return parse_json(path, text, option);
  if (ends_with(path, ".toml")) return parse_toml(path, text, option);
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first != std::string::npos && text[first] == '{') return parse_json(path, text, option);
  return parse_toml(path, text, option);
}

}  // namespace granchain
