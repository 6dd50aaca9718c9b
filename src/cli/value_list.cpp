#include "cli/value_list.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

#include "cli/input_error.hpp"

namespace granchain {

namespace {

constexpr std::size_t kMaxValues = 100000;

double number(const std::string& t, const std::string& option, const std::string& whole) {
  double x = 0;
  const char* b = t.data();
  const char* e = t.data() + t.size();
  if (b != e && *b == '+') ++b;
  const auto [p, ec] = std::from_chars(b, e, x);
  if (t.empty() || ec != std::errc() || p != e || !std::isfinite(x)) {
    throw InputError(fmt::format("{} = '{}': '{}' is not a finite number; valid: a list such as 1,2,3, a range "
                                 "first:last:step or first:last:xFACTOR", option, whole, t));
  }
  return x;
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : s) {
    if (c == sep) {
      out.push_back(cur);
      cur.clear();
    } else if (c != ' ' && c != '\t') {
      cur += c;
    }
  }
  out.push_back(cur);
  return out;
}

// A grid value rounded to 12 significant digits: 0.8 + 11 * 0.002 becomes the double nearest to
// 0.822, the same number a user typing 0.822 gets, so stored points can be selected by value.
double tidy(double x) {
  const std::string t = fmt::format("{:.12g}", x);
  double y = x;
  std::from_chars(t.data(), t.data() + t.size(), y);
  return y;
}

}  // namespace

std::vector<std::string> parse_name_list(const std::string& text) {
  std::vector<std::string> names;
  for (std::string& item : split(text, ','))
    if (!item.empty()) names.push_back(std::move(item));
  return names;
}

std::vector<double> parse_value_list(const std::string& text, const std::string& option) {
  std::vector<double> values;
  for (const std::string& item : split(text, ',')) {
    const std::vector<std::string> parts = split(item, ':');
    if (parts.size() == 1) {
      values.push_back(number(parts[0], option, text));
      continue;
    }
    if (parts.size() != 3) {
      throw InputError(fmt::format("{} = '{}': '{}' is not a value or a range first:last:step / first:last:xFACTOR",
                                   option, text, item));
    }
    const double first = number(parts[0], option, text);
    const double last = number(parts[1], option, text);
    const bool geometric = !parts[2].empty() && (parts[2][0] == 'x' || parts[2][0] == 'X');
    const double step = number(geometric ? parts[2].substr(1) : parts[2], option, text);
    std::size_t count = 0;
    if (geometric) {
      if (!(first > 0 && last >= first && step > 1)) {
        throw InputError(fmt::format("{} = '{}': a geometric range needs 0 < first <= last and a factor > 1", option, text));
      }
      const double n = std::floor(std::log(last / first) / std::log(step) + 1e-9);
      count = static_cast<std::size_t>(n) + 1;
      if (count > kMaxValues) throw InputError(fmt::format("{} = '{}': more than {} values", option, text, kMaxValues));
      for (std::size_t i = 0; i < count; ++i) values.push_back(tidy(first * std::pow(step, static_cast<double>(i))));
    } else {
      if (!(step > 0 && last >= first)) {
        throw InputError(fmt::format("{} = '{}': a range needs first <= last and a step > 0", option, text));
      }
      const double n = std::floor((last - first) / step + 1e-9);
      count = static_cast<std::size_t>(n) + 1;
      if (count > kMaxValues) throw InputError(fmt::format("{} = '{}': more than {} values", option, text, kMaxValues));
      // first + i * step (not accumulated), then tidied: 0.80:0.90:0.002 gives 0.8, 0.802, ..., 0.9.
      for (std::size_t i = 0; i < count; ++i) values.push_back(tidy(first + static_cast<double>(i) * step));
    }
  }
  return values;
}

}  // namespace granchain
