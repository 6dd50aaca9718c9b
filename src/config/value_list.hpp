#pragma once
// Lists of parameter values on the command line: "3,4,5", a linear range "0.80:0.90:0.002"
// (first:last:step, last included when it lies on the grid, to round-off), a geometric range
// "1e4:1e12:x10" (first:last:xFACTOR), and any mix separated by commas.
#include <string>
#include <vector>

namespace granchain {

// Throws InputError naming `option` on malformed text or a list of more than 100000 values (a range
// whose count is too large to represent included).
std::vector<double> parse_value_list(const std::string& text, const std::string& option);

// One integer lo <= x <= hi, written in full ("12", not "1.2e1" or ""). Throws InputError
// "<option> = '<text>' is not valid; valid range: integer lo <= <name> <= hi".
long long parse_integer_in(const std::string& text, const std::string& option, long long lo, long long hi);

// A duration in seconds, 1 s to a year: "3600", "3600s", "90m", "2.5h" (a number with an optional
// unit s, m or h) or Slurm's "[D-]H:MM:SS" ("23:30:00", "1-00:00:00"). Throws InputError
// "<option> = '<text>' is not a duration; valid: ...".
double parse_duration(const std::string& text, const std::string& option);

// Names separated by commas ("exact, reference"), blanks dropped, empty items skipped.
std::vector<std::string> parse_name_list(const std::string& text);

}  // namespace granchain
