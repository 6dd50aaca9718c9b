#include "config/value_list.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

#include "config/input_error.hpp"

namespace granchain {

namespace {

constexpr std::size_t kMaxValues = 100000;

double number(const std::string& t, const std::string& option, const std::string& whole) {
  double x = 0;
  const char* b = t.data();
  const char* e = t.data() + t.size();
  if (b != e && *b == '+') ++b;
  const auto [p, ec] = std::from_chars(b, e, x);
  if (!t.empty() && ec == std::errc::result_out_of_range && p == e)
    throw InputError(fmt::format("{} = '{}': '{}' is out of range: beyond the range of a double (about 1e-308 to 1e308 in "
                                 "magnitude)", option, whole, t));
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

long long parse_integer_in(const std::string& text, const std::string& option, long long lo, long long hi) {
  long long x = 0;
  const auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), x);
  if (text.empty() || ec != std::errc() || p != text.data() + text.size() || x < lo || x > hi) {
    const std::string name = option.rfind("--", 0) == 0 ? option.substr(2) : option;
    throw InputError(fmt::format("{} = '{}' is not valid; valid range: integer {} <= {} <= {}", option, text, lo, name, hi));
  }
  return x;
}

namespace {
// Slurm's [D-]H:MM:SS, or -1 when the text is not of that form.
double clock_duration(const std::string& text) {
  std::string rest = text;
  long long days = 0;
  if (const auto dash = rest.find('-'); dash != std::string::npos) {
    const std::string d = rest.substr(0, dash);
    const auto [p, ec] = std::from_chars(d.data(), d.data() + d.size(), days);
    if (d.empty() || ec != std::errc() || p != d.data() + d.size() || days < 0) return -1;
    rest = rest.substr(dash + 1);
  }
  const std::vector<std::string> parts = split(rest, ':');
  if (parts.size() != 3) return -1;
  long long v[3] = {0, 0, 0};
  for (int i = 0; i < 3; ++i) {
    const std::string& s = parts[static_cast<std::size_t>(i)];
    const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v[i]);
    if (s.empty() || ec != std::errc() || p != s.data() + s.size() || v[i] < 0 || (i > 0 && v[i] > 59)) return -1;
  }
  return static_cast<double>(((days * 24 + v[0]) * 60 + v[1]) * 60 + v[2]);
}
}  // namespace

double parse_duration(const std::string& text, const std::string& option) {
  const auto refuse = [&] {
    throw InputError(fmt::format("{} = '{}' is not a duration; valid: 1 s to a year, as seconds (3600), with a unit s, m or h "
                                 "(90m, 2.5h) or as [D-]H:MM:SS (23:30:00)",
                                 option, text));
  };
  if (text.find(':') != std::string::npos) {
    const double seconds = clock_duration(text);
    if (!(seconds >= 1.0) || seconds > 366.0 * 86400.0) refuse();
    return seconds;
  }
  std::string number = text;
  double unit = 1.0;
  if (!number.empty()) {
    const char last = number.back();
    if (last == 's' || last == 'm' || last == 'h') {
      unit = last == 'h' ? 3600.0 : last == 'm' ? 60.0 : 1.0;
      number.pop_back();
    }
  }
  double x = 0;
  const auto [p, ec] = std::from_chars(number.data(), number.data() + number.size(), x);
  const double seconds = x * unit;
  if (number.empty() || ec != std::errc() || p != number.data() + number.size() || !(seconds >= 1.0) || seconds > 366.0 * 86400.0)
    refuse();
  return seconds;
}

std::vector<std::string> parse_name_list(const std::string& text) {
  std::vector<std::string> names;
  for (std::string& item : split(text, ','))
    if (!item.empty()) names.push_back(std::move(item));
  return names;
}

std::vector<double> parse_value_list(const std::string& text, const std::string& option) {
  std::vector<double> values;
  const auto too_many = [&] {
    throw InputError(fmt::format("{} = '{}': the list has more than {} values; valid: at most {} values in all", option, text,
                                 kMaxValues, kMaxValues));
  };
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
    // The number of intervals as a double, checked before it becomes an integer: a tiny step or a
    // factor next to 1 gives a count beyond any integer type (or infinity), whose conversion would
    // be undefined. The logarithms are subtracted, not the quotient taken, so that last / first
    // cannot overflow (1e-300:1e300:x10 is 601 values).
    double intervals = 0;
    if (geometric) {
      if (!(first > 0 && last >= first && step > 1)) {
        throw InputError(fmt::format("{} = '{}': a geometric range needs 0 < first <= last and a factor > 1", option, text));
      }
      intervals = std::floor((std::log(last) - std::log(first)) / std::log(step) + 1e-9);
    } else {
      if (!(step > 0 && last >= first)) {
        throw InputError(fmt::format("{} = '{}': a range needs first <= last and a step > 0", option, text));
      }
      const double span = last - first;  // infinite only for first and last near -+1.8e308
      intervals = std::floor((std::isfinite(span) ? span / step : last / step - first / step) + 1e-9);
    }
    const double limit = static_cast<double>(kMaxValues);
    if (!(intervals + 1 <= limit)) {
      const std::string count = std::isfinite(intervals) ? fmt::format("{:.3g} values", intervals + 1) : "too many values to count";
      const std::string which = item == text ? "the range" : fmt::format("the range '{}'", item);
      throw InputError(fmt::format("{} = '{}': {} has {}; valid: at most {} values (a larger {})", option, text, which, count,
                                   kMaxValues, geometric ? "factor" : "step"));
    }
    if (static_cast<double>(values.size()) + intervals + 1 > limit) too_many();
    const auto count = static_cast<std::size_t>(intervals) + 1;
    for (std::size_t i = 0; i < count; ++i) {
      // first + i * step (not accumulated), then tidied: 0.80:0.90:0.002 gives 0.8, 0.802, ..., 0.9.
      double x = geometric ? first * std::pow(step, static_cast<double>(i)) : first + static_cast<double>(i) * step;
      // step^i alone may overflow where first * step^i does not (1e-300:1e300:x10).
      if (geometric && !std::isfinite(x)) x = std::exp(std::log(first) + static_cast<double>(i) * std::log(step));
      values.push_back(tidy(x));
    }
  }
  if (values.size() > kMaxValues) too_many();
  return values;
}

}  // namespace granchain
