#include "config/config_file.hpp"

#include <fmt/format.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <nlohmann/json.hpp>
#include <toml++/toml.h>
#include <set>
#include <sstream>
#include <vector>

#include "config/input_error.hpp"
#include "config/parameter.hpp"

namespace granchain {

std::string normalize_key(std::string key) {
  std::replace(key.begin(), key.end(), '_', '-');
  return key;
}

namespace {

// Parameter files are a few hundred bytes; anything beyond this is not one.
constexpr std::size_t kMaxConfigBytes = std::size_t{1} << 20;

std::map<std::string, RawValue> parse_json(const std::string& path, const std::string& text, const std::string& option) {
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
  } catch (const nlohmann::json::out_of_range&) {  // a number beyond a double ("e": 1e400)
    throw InputError(fmt::format("{}: '{}' holds a number out of range: beyond the range of a double (about 1e-308 to "
                                 "1e308 in magnitude)", option, path));
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: '{}' cannot be read as JSON (error {})", option, path, e.id));
  }
  if (!repeated.empty()) throw InputError(fmt::format("{}: '{}': '{}' is set twice", option, path, repeated));
  if (!j.is_object()) throw InputError(fmt::format("{}: '{}' must hold one JSON object of parameters", option, path));
  std::map<std::string, RawValue> out;
  for (const auto& [key, value] : j.items()) {
    RawValue v;
    if (value.is_array()) {
      std::string list;
      for (const auto& item : value) {
        if (!(item.is_string() || item.is_number()))
          throw InputError(fmt::format("{}: '{}': the list '{}' may hold only numbers and strings", option, path, key));
        list += (list.empty() ? "" : ",") + (item.is_string() ? item.get<std::string>()
                                             : item.is_number_float() ? real_text(item.get<double>()) : item.dump());
      }
      v = RawValue{list};
    } else if (value.is_string()) {
      v = RawValue{value.get<std::string>()};
    } else if (value.is_number_unsigned() && value.get<unsigned long long>() > 9223372036854775807ULL) {
      v = RawValue{value.dump()};  // beyond a long long: its digits, which the range check refuses
    } else if (value.is_number_integer()) {
      v = RawValue{value.get<long long>()};
    } else if (value.is_number_float()) {
      v = RawValue{value.get<double>()};
    } else if (value.is_boolean()) {
      v = RawValue{value.get<bool>() ? "true" : "false"};
    } else {
      throw InputError(fmt::format("{}: '{}': value of '{}' must be a number or a string", option, path, key));
    }
    // "dt_factor" and "dt-factor" name one parameter.
    if (!out.emplace(normalize_key(key), v).second)
      throw InputError(fmt::format("{}: '{}': '{}' is set twice", option, path, normalize_key(key)));
  }
  return out;
}

// TOML by toml++ (every valid TOML number: 1_000_000, 1e6, 0x10, inf), flat: parameters as
// `key = value`, lists as arrays of numbers or strings. toml++ refuses a key defined twice.
std::map<std::string, RawValue> parse_toml(const std::string& path, const std::string& text, const std::string& option) {
  toml::table table;
  try {
    table = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    throw InputError(fmt::format("{}: '{}' line {}: {}", option, path, e.source().begin.line, e.description()));
  }
  std::map<std::string, RawValue> out;
  auto scalar = [&](const toml::node& n, const std::string& key) -> std::string {
    if (const auto* i = n.as_integer()) return std::to_string(i->get());
    if (const auto* f = n.as_floating_point()) return real_text(f->get());
    if (const auto* s = n.as_string()) return s->get();
    if (const auto* b = n.as_boolean()) return b->get() ? "true" : "false";
    throw InputError(fmt::format("{}: '{}' line {}: the value of '{}' must be a number, a string or a list of them", option, path,
                                 n.source().begin.line, key));
  };
  for (const auto& [k, node] : table) {
    const std::string key(k.str());
    if (node.is_table())
      throw InputError(fmt::format("{}: '{}' line {}: tables/sections are not supported; use flat 'key = value'", option, path,
                                   node.source().begin.line));
    RawValue value;
    if (const auto* array = node.as_array()) {  // a sweep's list, as the command line writes one
      std::string list;
      for (const auto& item : *array) list += (list.empty() ? "" : ",") + scalar(item, key);
      value = RawValue{list};
    } else if (const auto* i = node.as_integer()) {
      value = RawValue{static_cast<long long>(i->get())};
    } else if (const auto* f = node.as_floating_point()) {
      value = RawValue{f->get()};
    } else {
      value = RawValue{scalar(node, key)};
    }
    // "dt_factor" and "dt-factor" name one parameter.
    if (!out.emplace(normalize_key(key), value).second)
      throw InputError(fmt::format("{}: '{}' line {}: '{}' is set twice", option, path, node.source().begin.line, normalize_key(key)));
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

std::map<std::string, RawValue> read_config_file(const std::string& path, const std::string& option) {
  const std::string text = read_parameter_file(path, option);
  if (ends_with(path, ".json")) return parse_json(path, text, option);
  if (ends_with(path, ".toml")) return parse_toml(path, text, option);
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first != std::string::npos && text[first] == '{') return parse_json(path, text, option);
  return parse_toml(path, text, option);
}

}  // namespace granchain
