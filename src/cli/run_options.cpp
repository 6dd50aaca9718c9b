#include "cli/run_options.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <functional>
#include <limits>

#include "cli/input_error.hpp"
#include "engines/engine_factory.hpp"

namespace granchain {

namespace {

std::string where(const RawValue& v) { return v.source.empty() ? "" : " (from " + v.source + ")"; }

std::string strip(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t");
  std::string out = s.substr(b, e - b + 1);
  if (!out.empty() && out.front() == '+') out.erase(0, 1);
  return out;
}

// Strict real number: the whole text must be a number, and it must be finite.
double parse_real(const std::string& name, const RawValue& v, const std::string& range) {
  const std::string t = strip(v.text);
  double x = 0;
  const auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), x);
  if (t.empty() || ec != std::errc() || p != t.data() + t.size())
    throw InputError(fmt::format("--{} = '{}'{} is not a number; valid range: {}", name, v.text, where(v), range));
  if (!std::isfinite(x))
    throw InputError(fmt::format("--{} = '{}'{} is not finite; valid range: {}", name, v.text, where(v), range));
  return x;
}

long long parse_integer(const std::string& name, const RawValue& v, const std::string& range) {
  const std::string t = strip(v.text);
  long long x = 0;
  const auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), x);
  if (t.empty() || ec != std::errc() || p != t.data() + t.size())
    throw InputError(fmt::format("--{} = '{}'{} is not an integer; valid range: {}", name, v.text, where(v), range));
  return x;
}

[[noreturn]] void out_of_range(const std::string& name, const RawValue& v, const std::string& range) {
  throw InputError(fmt::format("--{} = {}{} is out of range; valid range: {}", name, strip(v.text), where(v), range));
}

struct Definition {
  ParameterInfo info;
  std::function<void(RunOptions&, const RawValue&, std::map<std::string, double>&)> apply;
};

// Real parameter with an open/closed interval check.
Definition real_param(std::string name, std::string meaning, std::string range, std::string dflt,
                      std::function<bool(double)> ok, std::function<void(RunOptions&, double)> set) {
  std::string help = meaning + "; " + range + (dflt.empty() ? "" : "; default " + dflt);
  return {{name, help, "REAL"}, [name, range, ok, set](RunOptions& o, const RawValue& v, std::map<std::string, double>&) {
            const double x = parse_real(name, v, range);
            if (!ok(x)) out_of_range(name, v, range);
            set(o, x);
          }};
}

const std::vector<Definition>& definitions() {
  static const std::vector<Definition> defs = [] {
    std::vector<Definition> d;
    d.push_back({{"N", "number of particles; integer N >= 1 (up to 100000); default 25", "INT"},
                 [](RunOptions& o, const RawValue& v, std::map<std::string, double>&) {
                   const std::string range = "integer 1 <= N <= 100000";
                   const long long n = parse_integer("N", v, range);
                   if (n < 1 || n > 100000) out_of_range("N", v, range);
                   o.spec.params.N = static_cast<int>(n);
                 }});
    d.push_back(real_param("e", "restitution coefficient of a binary collision", "0 < e <= 1", "0.9",
                           [](double x) { return x > 0 && x <= 1; }, [](RunOptions& o, double x) { o.spec.params.e = x; }));
    d.push_back(real_param("k", "elastic constant of the spring (hard-sphere limit: k -> infinity at fixed e)", "k > 0", "1e5",
                           [](double x) { return x > 0; }, [](RunOptions& o, double x) { o.spec.params.k = x; }));
    d.push_back(real_param("T0", "temperature of the thermal floor, k_B T0", "T0 > 0", "1",
                           [](double x) { return x > 0; }, [](RunOptions& o, double x) { o.spec.params.kT0 = x; }));
    d.push_back({{"T", "measuring time (window after the transient); T > 0; default 1e4 for N < 50, 1e3 for N >= 50 (the paper's)", "REAL"},
                 [](RunOptions&, const RawValue& v, std::map<std::string, double>& late) {
                   const double x = parse_real("T", v, "T > 0");
                   if (!(x > 0)) out_of_range("T", v, "T > 0");
                   late["T"] = x;
                 }});
    d.push_back({{"transient", "discarded time before the measuring window; transient >= 0; default T/10", "REAL"},
                 [](RunOptions&, const RawValue& v, std::map<std::string, double>& late) {
                   const double x = parse_real("transient", v, "transient >= 0");
                   if (!(x >= 0)) out_of_range("transient", v, "transient >= 0");
                   late["transient"] = x;
                 }});
    d.push_back({{"seed", "random seed (initial state and floor); integer 0 <= seed <= 9223372036854775807; default 1", "INT"},
                 [](RunOptions& o, const RawValue& v, std::map<std::string, double>&) {
                   const std::string range = "integer 0 <= seed <= 9223372036854775807";
                   const long long s = parse_integer("seed", v, range);
                   if (s < 0) out_of_range("seed", v, range);
                   o.spec.seed = static_cast<std::uint64_t>(s);
                 }});
    {
      std::string names;
      for (const auto& n : engine_names()) names += (names.empty() ? "" : ", ") + n;
      d.push_back({{"engine", "time integrator; one of: " + names + "; default " + engine_names().front() +
                                  " (reference = the paper's 2nd-order Runge-Kutta with dt = tau_c/dt-factor)", "NAME"},
                   [names](RunOptions& o, const RawValue& v, std::map<std::string, double>&) {
                     const std::string t = strip(v.text);
                     for (const auto& n : engine_names())
                       if (t == n) {
                         o.spec.engine.name = n;
                         return;
                       }
                     throw InputError(fmt::format("--engine = '{}'{} is not an engine; valid: {}", v.text, where(v), names));
                   }});
    }
    d.push_back(real_param("dt-factor", "reference engine step dt = tau_c / dt-factor (the paper: 100)", "10 <= dt-factor <= 1e6", "100",
                           [](double x) { return x >= 10 && x <= 1e6; }, [](RunOptions& o, double x) { o.spec.engine.dt_factor = x; }));
    d.push_back(real_param("tc", "hard engine: TC model time t_c, a collision within t_c of a particle's previous one is elastic (0: off)",
                           "tc >= 0", "0", [](double x) { return x >= 0; },
                           [](RunOptions& o, double x) { o.spec.engine.hard.tc = x; }));
    d.push_back(real_param("m", "particle mass (unit of mass)", "m > 0", "1",
                           [](double x) { return x > 0; }, [](RunOptions& o, double x) { o.spec.params.m = x; }));
    d.push_back(real_param("d", "particle diameter (unit of length)", "d > 0", "1",
                           [](double x) { return x > 0; }, [](RunOptions& o, double x) { o.spec.params.d = x; }));
    d.push_back(real_param("g", "gravitational acceleration", "g > 0", "1",
                           [](double x) { return x > 0; }, [](RunOptions& o, double x) { o.spec.params.g = x; }));
    d.push_back(real_param("sample-interval", "time between profile samples (rounded to whole engine steps)", "sample-interval > 0", "0.01",
                           [](double x) { return x > 0; }, [](RunOptions& o, double x) { o.spec.sample_interval = x; }));
    d.push_back({{"bins", "time bins for the blocking error analysis; power of two, 16 <= bins <= 65536; default 1024", "INT"},
                 [](RunOptions& o, const RawValue& v, std::map<std::string, double>&) {
                   const std::string range = "power of two, 16 <= bins <= 65536";
                   const long long b = parse_integer("bins", v, range);
                   if (b < 16 || b > 65536 || (b & (b - 1)) != 0) out_of_range("bins", v, range);
                   o.spec.bins = static_cast<int>(b);
                 }});
    d.push_back({{"db", "results store (SQLite file), created if missing; default granchain.db in the working folder", "PATH"},
                 [](RunOptions& o, const RawValue& v, std::map<std::string, double>&) {
                   if (strip(v.text).empty()) throw InputError("--db: the path is empty; give a file name");
                   o.db_path = v.text;
                 }});
    return d;
  }();
  return defs;
}

}  // namespace

const std::vector<ParameterInfo>& run_parameters() {
  static const std::vector<ParameterInfo> infos = [] {
    std::vector<ParameterInfo> v;
    for (const auto& d : definitions()) v.push_back(d.info);
    return v;
  }();
  return infos;
}

RunOptions resolve_run_options(const std::map<std::string, RawValue>& raw) {
  RunOptions o;
  std::map<std::string, double> late;
  for (const auto& [key, value] : raw) {
    bool known = false;
    for (const auto& d : definitions()) {
      if (d.info.name == key) {
        d.apply(o, value, late);
        known = true;
        break;
      }
    }
    if (!known) {
      std::string names;
      for (const auto& d : definitions()) names += (names.empty() ? "" : ", ") + d.info.name;
      throw InputError(fmt::format("unknown parameter '{}'{}; known: {}", key, where(value), names));
    }
  }
  if (is_hard_sphere_engine(o.spec.engine.name)) {
    if (raw.count("k")) throw InputError("--k: the hard-sphere engine has k = infinity; leave --k out");
    o.spec.params.k = std::numeric_limits<double>::infinity();
  } else if (raw.count("tc")) {
    throw InputError("--tc: the TC model belongs to --engine hard");
  }
  o.spec.T = late.count("T") ? late["T"] : (o.spec.params.N < 50 ? 1e4 : 1e3);
  o.spec.transient = late.count("transient") ? late["transient"] : o.spec.T / 10.0;
  // A window shorter than one profile sample cannot be analysed.
  if (o.spec.T < o.spec.sample_interval)
    throw InputError(fmt::format("--T = {} is shorter than --sample-interval = {}; valid range: T >= sample-interval",
                                 o.spec.T, o.spec.sample_interval));
  return o;
}

}  // namespace granchain
