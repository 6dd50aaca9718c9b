#pragma once
// What a parameter is, written once: its name (the flag without "--", the config-file key, the
// Python keyword with '_' for '-'), its type, unit, default, valid range and meaning, the
// commands and engines that take it, whether a sweep may take a list of it and which store column
// keeps it. The tables of the driven column (run_options.cpp) and of the collapse count
// (collapse_options.cpp) are lists of these; the command line's flags and help, the config files,
// the Python keywords, the sweep axes and the messages of bad input all read them.
#include <functional>
#include <map>
#include <string>
#include <variant>
#include <vector>

namespace granchain {

enum class ParameterType { Integer, Real, Name, Path, RealList };

// The commands that take a parameter (a bit set).
enum ParameterUse : unsigned {
  kUseRun = 1u << 0,       // granchain run (and its config file)
  kUseSweep = 1u << 1,     // granchain sweep (and its sweep file)
  kUseTrace = 1u << 2,     // granchain trace
  kUseCollapse = 1u << 3,  // granchain collapse
  kUsePython = 1u << 4,    // the Python module's run / collapse
};
constexpr unsigned kUseDriven = kUseRun | kUseSweep | kUsePython;  // `trace` takes those marked kUseTrace too

// The engines that take a parameter. A Soft or Hard parameter given for another engine is refused
// (check_engine_scope); a TimeStepped one is ignored by the event-driven engines.
enum class EngineScope { Any, Soft, Hard, TimeStepped };

struct EngineInfo;

// A value as it is kept: text (a name), an integer or a real.
using TypedValue = std::variant<std::string, long long, double>;

// The part of a driven-column run's identity (its point key, config/run_key.hpp) that a parameter
// is, in the key's order: the engine, the physics (model and set-up), the measuring window, the
// engine's own options, the seed. The store keeps every part in the run's columns.
enum class RunIdentity { None, Engine, Physics, Window, EngineOption, Seed };

// A value as it arrives: text (a flag, a list such as "1e4:1e10:x10"), or already typed (a
// Python int or float). `source` says where it came from for messages: "" for the command line,
// else "config file 'x'".
struct RawValue {
  TypedValue value;
  std::string source;
  RawValue() = default;
  RawValue(std::string text, std::string from = "") : value(std::move(text)), source(std::move(from)) {}
  RawValue(const char* text, std::string from = "") : value(std::string(text)), source(std::move(from)) {}
  RawValue(long long x, std::string from = "") : value(x), source(std::move(from)) {}
  RawValue(double x, std::string from = "") : value(x), source(std::move(from)) {}
  // The value as a message shows it: text as given (blanks and a leading '+' dropped), numbers
  // in their shortest round-trip form (real_text for a real).
  std::string text() const;
};

// A real number as text that reads back exactly and stays a real: 3.0 is "3.0", so an integer
// parameter given as a real (N = 3.0, or 2.9999999999999999, which is the same double) is refused
// as the command line refuses --N 3.0, instead of being taken as 3.
std::string real_text(double x);

struct Parameter {
  std::string name;
  ParameterType type = ParameterType::Real;
  std::string unit;     // "" for pure numbers; else in units made of m, d and g (d and v0 for a collapse)
  std::string meaning;  // what it is
  std::string range;    // the valid range as messages print it ("0 < e <= 1")
  std::string fallback; // the default as help prints it ("0.9", "T/10")
  unsigned uses = 0;    // ParameterUse bits
  EngineScope engines = EngineScope::Any;
  bool sweep_axis = false;   // a sweep may take a list of it (each point one value)
  std::string store_column;  // the column of the store's runs / collapse_runs table that keeps it ("" none)
  // Numbers: the value must satisfy this (range says which).
  std::function<bool(double)> valid;
  // Soft or Hard scope: why another engine refuses it ("the hard-sphere engine has k = infinity",
  // "the TC model"), for check_engine_scope's message.
  std::string scope_note = "";
  // Driven column: the part of a run's identity it is (None: not part of it, like --db).
  RunIdentity identity = RunIdentity::None;

  // "meaning; range; default D" for --help.
  std::string help() const;
  // INT, REAL, NAME, PATH or LIST for --help.
  std::string type_name() const;
};

// Reading a raw value as the parameter's type, with one InputError line naming the parameter,
// the value, where it came from and the valid range:
//   "--e = 2 is out of range; valid range: 0 < e <= 1"
double read_real(const Parameter& p, const RawValue& v);       // a finite number in p.valid
long long read_integer(const Parameter& p, const RawValue& v);  // a whole decimal number in p.valid
std::string read_name(const Parameter& p, const RawValue& v);   // text, blanks trimmed
std::vector<double> read_real_list(const Parameter& p, const RawValue& v);  // config/value_list.hpp; each in p.valid

// " (from config file 'x')" or "".
std::string from_where(const RawValue& v);
// Throws InputError "--name = VALUE<from> is out of range; valid range: RANGE".
[[noreturn]] void value_out_of_range(const std::string& name, const RawValue& v, const std::string& range);

// x to 3 significant digits, rounded into the valid range (down for an upper bound), for the
// bound a message prints.
std::string rounded_bound(double x, bool upper);

// The first parameter of `table` in `raw` that `engine` does not take (EngineScope Soft with the
// hard-sphere engine, Hard with a soft one) is refused: "--k: the hard-sphere engine has k =
// infinity; leave --k out", "--tc: the TC model belongs to --engine hard".
void check_engine_scope(const std::vector<Parameter>& table, const std::map<std::string, RawValue>& raw, const EngineInfo& engine);

// The entry called `name` in `table`, or nullptr.
const Parameter* find_parameter(const std::vector<Parameter>& table, const std::string& name);
// "N, e, k, ..." in table order, for the message about an unknown key.
std::string parameter_names(const std::vector<Parameter>& table, unsigned uses = ~0u);

}  // namespace granchain
