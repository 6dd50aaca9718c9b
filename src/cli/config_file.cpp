#include "cli/config_file.hpp"

#include <fmt/format.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <vector>

#include "cli/input_error.hpp"

namespace granchain {

std::string normalize_key(std::string key) {
  std::replace(key.begin(), key.end(), '_', '-');
  return key;
}

namespace {

// Parameter files are a few hundred bytes; anything beyond this is not one.
constexpr std::size_t kMaxConfigBytes = std::size_t{1} << 20;

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

std::map<std::string, std::string> parse_json(const std::string& path, const std::string& text, const std::string& option) {
  // nlohmann::json keeps the last of repeated keys; its parse callback sees every key as it is
  // read, so a key that the object being read already holds is caught (in any object).
  std::vector<std::set<std::string>> open_objects;
  std::string repeated;
  const auto watch = [&](int, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using Event = nlohmann::json::parse_event_t;
    if (event == Event::object_start) {
      open_objects.emplace_back();
    } else if (event == Event::object_end) {
      if (!open_objects.empty()) open_objects.pop_back();
    } else if (event == Event::key && !open_objects.empty() && parsed.is_string()) {
      const std::string& key = parsed.get_ref<const std::string&>();
      if (!open_objects.back().insert(key).second && repeated.empty()) repeated = key;
    }
    return true;
  };
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text, watch);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(fmt::format("{}: '{}' is not valid JSON (byte {})", option, path, e.byte));
  }
  if (!repeated.empty()) throw InputError(fmt::format("{}: '{}': '{}' is set twice", option, path, repeated));
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
    // "dt_factor" and "dt-factor" name one parameter.
    if (!out.emplace(normalize_key(key), v).second)
      throw InputError(fmt::format("{}: '{}': '{}' is set twice", option, path, normalize_key(key)));
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

const char* file_kind(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// The whole text of a parameter file. Only a regular file is read (a directory, device, FIFO or
// socket is refused before it is opened: /dev/zero would never end, a FIFO would block), and at
// most kMaxConfigBytes of it: files under /proc report size 0, so the cap is enforced on what
// read() returns, and a read error (EIO from /proc/self/mem) is an error, not an empty file.
std::string read_parameter_file(const std::string& path, const std::string& option) {
  const std::string valid = fmt::format("valid: a JSON or TOML file of at most {} MiB", kMaxConfigBytes >> 20);
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    throw InputError(fmt::format("{}: cannot read '{}' ({}); {}", option, path, std::strerror(errno), valid));
  if (!S_ISREG(st.st_mode)) throw InputError(fmt::format("{}: '{}' is {}; {}", option, path, file_kind(st.st_mode), valid));
  if (st.st_size > static_cast<off_t>(kMaxConfigBytes))
    throw InputError(fmt::format("{}: '{}' is larger than {} MiB ({} bytes); {}", option, path, kMaxConfigBytes >> 20, st.st_size, valid));
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) throw InputError(fmt::format("{}: cannot read '{}' ({}); {}", option, path, std::strerror(errno), valid));
  std::string text;
  std::string error;
  // The file may have been replaced between stat() and open(): check what was opened.
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    error = fmt::format("{}: '{}' is {}; {}", option, path, file_kind(st.st_mode), valid);
  } else {
    char buffer[65536];
    while (error.empty()) {
      const ssize_t n = ::read(fd, buffer, sizeof buffer);
      if (n == 0) break;
      if (n < 0) {
        if (errno == EINTR) continue;
        error = fmt::format("{}: cannot read '{}' ({}); {}", option, path, std::strerror(errno), valid);
      } else if (text.size() + static_cast<std::size_t>(n) > kMaxConfigBytes) {
        error = fmt::format("{}: '{}' is larger than {} MiB; {}", option, path, kMaxConfigBytes >> 20, valid);
      } else {
        text.append(buffer, static_cast<std::size_t>(n));
      }
    }
  }
  ::close(fd);
  if (!error.empty()) throw InputError(error);
  return text;
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

std::map<std::string, std::string> read_config_file(const std::string& path, const std::string& option) {
  const std::string text = read_parameter_file(path, option);
  if (ends_with(path, ".json")) return parse_json(path, text, option);
  if (ends_with(path, ".toml")) return parse_toml(path, text, option);
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first != std::string::npos && text[first] == '{') return parse_json(path, text, option);
  return parse_toml(path, text, option);
}

}  // namespace granchain
