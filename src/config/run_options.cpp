#include "config/run_options.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>

#include "config/input_error.hpp"
#include "engines/engine_registry.hpp"

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
  if (!t.empty() && ec == std::errc::result_out_of_range && p == t.data() + t.size())  // beyond a double, or below its least
    throw InputError(fmt::format("--{} = '{}'{} is out of range: {}; valid range: {}", name, v.text, where(v),
                                 std::abs(std::strtod(t.c_str(), nullptr)) > 1 ? "larger than the largest double"
                                                                                : "smaller than the least positive double",
                                 range));
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
  if (!t.empty() && ec == std::errc::result_out_of_range && p == t.data() + t.size())
    throw InputError(fmt::format("--{} = '{}'{} is out of range; valid range: {}", name, v.text, where(v), range));
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
      const std::string names = engine_name_list();
      d.push_back({{"engine", "time integrator; one of: " + names + "; default " + std::string(engines().front().name) +
                                  " (reference = the paper's 2nd-order Runge-Kutta with dt = tau_c/dt-factor)", "NAME"},
                   [names](RunOptions& o, const RawValue& v, std::map<std::string, double>&) {
                     if (const EngineInfo* e = find_engine(strip(v.text))) {
                       o.spec.engine.kind = e->kind;
                       return;
                     }
                     throw InputError(fmt::format("--engine = '{}'{} is not an engine; valid: {}", v.text, where(v), names));
                   }});
    }
    d.push_back(real_param("dt-factor", "reference engine step dt = tau_c / dt-factor (the paper: 100)", "10 <= dt-factor <= 1e6", "100",
                           [](double x) { return x >= 10 && x <= 1e6; }, [](RunOptions& o, double x) { o.spec.engine.dt_factor = x; }));
    // The hard engine declares an inelastic collapse when collapse_collisions (1000) collisions
    // fall within collapse_time (1e-9). A TC time shorter than that span leaves collisions inside
    // it inelastic, and the watch can fire although the TC model is on (N = 100, e = 0.05 collapses
    // at tc = 1e-10, runs at 1e-9); from tc = collapse_time on, every further collision of a
    // particle inside the span is elastic.
    d.push_back(real_param("tc", "hard engine: TC model time t_c, a collision within t_c of a particle's previous one is elastic (0: off)",
                           fmt::format("tc = 0 (off) or tc >= {:g} (the hard engine counts {} collisions within {:g} as a collapse; "
                                       "a shorter t_c leaves them inelastic)",
                                       HardSphereOptions{}.collapse_time, HardSphereOptions{}.collapse_collisions,
                                       HardSphereOptions{}.collapse_time),
                           "0", [](double x) { return x == 0 || x >= HardSphereOptions{}.collapse_time; },
                           [](RunOptions& o, double x) { o.spec.engine.hard.tc = x; }));
    d.push_back(real_param("m", "particle mass (unit of mass)", "m > 0", "1",
                           [](double x) { return x > 0; }, [](RunOptions& o, double x) { o.spec.params.m = x; }));
    d.push_back(real_param("d", "particle diameter (unit of length)", "d > 0", "1",
                           [](double x) { return x > 0; }, [](RunOptions& o, double x) { o.spec.params.d = x; }));
    d.push_back(real_param("g", "gravitational acceleration", "g > 0", "1",
                           [](double x) { return x > 0; }, [](RunOptions& o, double x) { o.spec.params.g = x; }));
    d.push_back(real_param("sample-interval", "time between profile samples (rounded to whole engine steps); 16 to 1e10 samples in T, at least 1e6 clock resolutions", "sample-interval > 0", "0.01",
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

// ---------------------------------------------------------------------------------------------
// What the engines resolve in double precision. Each parameter alone has a wide valid range, but
// together they set two scales that must stay resolvable; a run outside them prints numbers that
// mean nothing (k = 1e300: tau_c = 2e-150, every contact begins and ends at one clock value) or
// an exploded column (m = 1e-300: speeds of 1e150, heights of 1e149 after t = 1).

// Resolution steps a scale must span: the exact engine steps over what it cannot resolve in
// intervals of 1e-6 tau_c (ExactEngine::kResolutionSkip), the reference engine's finest step is
// tau_c / 1e6 (dt-factor <= 1e6), and heights are asked to resolve d to the same 1e-6.
constexpr double kResolutionSteps = 1e6;

double ulp(double t) { return std::nextafter(t, std::numeric_limits<double>::infinity()) - t; }

// x to 3 significant digits, rounded into the valid range (down for an upper bound).
std::string rounded(double x, bool upper) {
  if (!(x > 0) || !std::isfinite(x)) return fmt::format("{:.3g}", x);
  const double unit = std::pow(10.0, std::floor(std::log10(x)) - 2);
  return fmt::format("{:.3g}", (upper ? std::floor(x / unit) : std::ceil(x / unit)) * unit);
}

// The flag a message names: the first of `names` that was given and fails with every other
// parameter at its default (fails(name) says so), else the first that was given.
std::string culprit(const std::vector<std::string>& names, const std::map<std::string, RawValue>& raw,
                    const std::function<bool(const std::string&)>& fails) {
  for (const auto& n : names)
    if (raw.count(n) && fails(n)) return n;
  for (const auto& n : names)
    if (raw.count(n)) return n;
  return names.front();
}

// The raw value of a flag, or its value in effect when it was not given.
RawValue given_or(const std::map<std::string, RawValue>& raw, const std::string& name, double value) {
  const auto it = raw.find(name);
  return it != raw.end() ? it->second : RawValue{fmt::format("{}", value), ""};
}

// Time (soft engines). A contact lasts tau_c, with tau_c^2 = m (pi^2 + ln^2 e) / 2k (Eqs. Dd,
// tauc), and the clock's resolution at the run's last instant t = transient + T is ulp(t) (about
// 2^-52 t) for a double clock, 2^-53 ulp(t) for the exact engine's FineTime: tau_c >= 1e6 times
// that, i.e. k <= m (pi^2 + ln^2 e) / (2 tau_min^2). At the paper's T = 1e4 that is k <= 1.49e12
// for m = 1 on a double clock (the reference engines) and k <= 1.2e44 for the exact engine.
void check_contact_time(const RunOptions& o, const std::map<std::string, RawValue>& raw) {
  const EngineInfo& engine = engine_info(o.spec.engine.kind);
  if (engine.hard_spheres) return;
  const ChainParameters& p = o.spec.params;
  const double t_end = o.spec.transient + o.spec.T;
  const auto tau = [](double k, double m, double e) { return contact_time(k, damping_constant(k, e, m), m); };
  const bool fine = engine.fine_clock;
  const auto resolved = [&](double k, double m, double e, double t) { return tau(k, m, e) >= shortest_resolved_time(t, fine); };
  if (resolved(p.k, p.m, p.e, t_end)) return;
  const ChainParameters def;
  const double t_def = (p.N < 50 ? 1e4 : 1e3) * 1.1;
  const std::string name = culprit({"k", "m", "T", "transient"}, raw, [&](const std::string& n) {
    if (n == "k") return !resolved(p.k, def.m, def.e, t_def);
    if (n == "m") return !resolved(def.k, p.m, def.e, t_def);
    return !resolved(def.k, def.m, def.e, t_end);
  });
  const double tau_min = shortest_resolved_time(t_end, fine);
  const double l2 = std::log(p.e) * std::log(p.e);
  const double pi2 = std::numbers::pi * std::numbers::pi;
  std::string range;
  if (name == "k") {
    range = fmt::format("0 < k <= {} at m = {}, e = {} and transient + T = {}", rounded(p.m * (pi2 + l2) / (2 * tau_min * tau_min), true),
                        p.m, p.e, t_end);
  } else if (name == "m") {
    range = fmt::format("m >= {} at k = {}, e = {} and transient + T = {}", rounded(2 * p.k * tau_min * tau_min / (pi2 + l2), false),
                        p.k, p.e, t_end);
  } else {  // the largest t_end whose ulp, 2^(ilogb(t) - 52), is at most tau_c / 1e6 (times 2^53: fine)
    const double t_max = std::ldexp(1.0, 53 + std::ilogb(tau(p.k, p.m, p.e) / kResolutionSteps) + (fine ? 53 : 0));
    range = fmt::format("transient + T < {} at k = {}, m = {} and e = {}", rounded(t_max, true), p.k, p.m, p.e);
  }
  out_of_range(name, given_or(raw, name, name == "k" ? p.k : name == "m" ? p.m : o.spec.T),
               fmt::format("{}: a contact (tau_c = {:.3g} here) must last at least 1e6 times the {} engine's clock resolution "
                           "at t = transient + T ({:.3g})", range, tau(p.k, p.m, p.e), engine.name,
                           shortest_resolved_time(t_end, fine) / kResolutionSteps));
}

// Heights (all engines). The floor throws particles to heights of order k_B T0 / (m g) above a
// stack of N d. Profiles are sampled as absolute heights (and the reference engine integrates
// them), resolved to 2^-52 of the column's height scale; for that to resolve d to 1e-6,
// N d + T0/(m g) <= R d with R = 2^52 / 1e6 = 4.5e9.
void check_height_scale(const RunOptions& o, const std::map<std::string, RawValue>& raw) {
  const ChainParameters& p = o.spec.params;
  const double R = std::ldexp(1.0, 52) / kResolutionSteps;
  // Written as quotients, so that T0 / m overflowing to infinity fails the check.
  const auto resolved = [&](double kT0, double m, double g, double d) { return kT0 / m / g / d + p.N <= R; };
  if (resolved(p.kT0, p.m, p.g, p.d)) return;
  const ChainParameters def;
  const std::string name = culprit({"m", "T0", "g", "d"}, raw, [&](const std::string& n) {
    if (n == "m") return !resolved(def.kT0, p.m, def.g, def.d);
    if (n == "T0") return !resolved(p.kT0, def.m, def.g, def.d);
    if (n == "g") return !resolved(def.kT0, def.m, p.g, def.d);
    return !resolved(def.kT0, def.m, def.g, p.d);
  });
  const double room = R - p.N;  // T0 / (m g d) may be at most this
  std::string range;
  if (name == "m") range = fmt::format("m >= {} at T0 = {}, g = {}, d = {}", rounded(p.kT0 / p.g / p.d / room, false), p.kT0, p.g, p.d);
  else if (name == "T0") range = fmt::format("0 < T0 <= {} at m = {}, g = {}, d = {}", rounded(p.m * p.g * p.d * room, true), p.m, p.g, p.d);
  else if (name == "g") range = fmt::format("g >= {} at T0 = {}, m = {}, d = {}", rounded(p.kT0 / p.m / p.d / room, false), p.kT0, p.m, p.d);
  else range = fmt::format("d >= {} at T0 = {}, m = {}, g = {}", rounded(p.kT0 / p.m / p.g / room, false), p.kT0, p.m, p.g);
  out_of_range(name, given_or(raw, name, name == "m" ? p.m : name == "T0" ? p.kT0 : name == "g" ? p.g : p.d),
               fmt::format("{} and N = {}: the column's height scale N d + T0 / (m g) must stay below {:.2g} d, where heights "
                           "resolve d to 1e-6", range, p.N, R));
}

}  // namespace

double shortest_resolved_time(double t, bool fine) { return kResolutionSteps * (fine ? std::ldexp(ulp(t), -53) : ulp(t)); }

double largest_resolved_k(double m, double e, double t, bool fine) {
  const double tau_min = shortest_resolved_time(t, fine);
  const double l2 = std::log(e) * std::log(e);
  return m * (std::numbers::pi * std::numbers::pi + l2) / (2 * tau_min * tau_min);
}

namespace {

// The clock's scale over a collapse launch (run_options.hpp).
double launch_time_scale(int N, double a, double v0, double d) { return 2.0 * (N + 1) * (a + d) / v0; }

}  // namespace

void check_collapse_contact_time(double k, double e, double m, double d, int N, double a, double v0, bool fine) {
  const double t = launch_time_scale(N, a, v0, d);
  const double k_max = largest_resolved_k(m, e, t, fine);
  if (!(k <= k_max))
    throw InputError(fmt::format("--k: {:g} is out of range; valid range: 0 < k <= {} at e = {:g}, N = {}, a = {:g}, v0 = {:g} "
                                 "(a contact must last at least 1e6 times the engine's clock resolution, {:.3g}, over the "
                                 "launch's time scale 2 (N + 1)(a + d) / v0 = {:.3g})",
                                 k, rounded(k_max, true), e, N, a, v0, shortest_resolved_time(t, fine) / kResolutionSteps, t));
}

void check_collapse_launch(int N, double a, double v0, double d) {
  const double t = launch_time_scale(N, a, v0, d);
  if (!(t <= 1e6))
    throw InputError(fmt::format("--a = {:g}, --v0 = {:g}: the launch's time scale 2 (N + 1)(a + d) / v0 = {:.3g} is out of range; "
                                 "valid range: <= 1e6 (a launch is given up at t = 1e7)", a, v0, t));
}

void check_collapse_tc(double tc, double collapse_time) {
  if (!(tc == 0 || tc >= collapse_time))
    throw InputError(fmt::format("--tc = {:g} is out of range; valid range: tc = 0 (off) or tc >= collapse-time = {:g}", tc,
                                 collapse_time));
}

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
  if (engine_info(o.spec.engine.kind).hard_spheres) {
    if (raw.count("k")) throw InputError("--k: the hard-sphere engine has k = infinity; leave --k out");
    o.spec.params.k = std::numeric_limits<double>::infinity();
  } else if (raw.count("tc")) {
    throw InputError("--tc: the TC model belongs to --engine hard");
  }
  o.spec.T = late.count("T") ? late["T"] : (o.spec.params.N < 50 ? 1e4 : 1e3);
  o.spec.transient = late.count("transient") ? late["transient"] : o.spec.T / 10.0;
  check_contact_time(o, raw);
  check_height_scale(o, raw);
  // The clock runs from 0 to transient + T: beyond 1e15 a step of order 1 stops advancing it.
  if (!(o.spec.transient + o.spec.T <= 1e15))
    out_of_range(raw.count("transient") ? "transient" : "T", given_or(raw, raw.count("transient") ? "transient" : "T",
                                                                      raw.count("transient") ? o.spec.transient : o.spec.T),
                 "transient + T <= 1e15 (the clock must still advance by steps of order 1)");
  // The profile histograms hold (1 + 3N) bins doubles: at most 1 GiB.
  if (static_cast<double>(1 + 3 * o.spec.params.N) * o.spec.bins * 8.0 > 1073741824.0) {
    const bool bins_given = raw.count("bins") > 0;
    const long long n_max = (1073741824LL / (8LL * o.spec.bins) - 1) / 3;
    out_of_range(bins_given ? "bins" : "N", given_or(raw, bins_given ? "bins" : "N", bins_given ? o.spec.bins : o.spec.params.N),
                 bins_given ? fmt::format("bins <= {} at N = {} (the profile histograms, (1 + 3N) x bins doubles, take at most 1 GiB)",
                                          1073741824LL / (8LL * (1 + 3LL * o.spec.params.N)), o.spec.params.N)
                            : fmt::format("N <= {} at bins = {} (the profile histograms, (1 + 3N) x bins doubles, take at most 1 GiB)",
                                          n_max, o.spec.bins));
  }
  // Profiles are sampled every sample-interval over the window T: blocking needs at least 16
  // samples (the least --bins), more than 1e10 would take longer to sample than any run is meant to, and the sample
  // times must be told apart by the clock (1e6 resolutions at transient + T, as contacts are).
  {
    const double samples = o.spec.T / o.spec.sample_interval, t_end = o.spec.transient + o.spec.T;
    const bool interval_given = raw.count("sample-interval") > 0;
    const std::string name = interval_given || !raw.count("T") ? "sample-interval" : "T";
    const RawValue& given = given_or(raw, name, name == "T" ? o.spec.T : o.spec.sample_interval);
    if (!(samples >= 16 && samples <= 1e10))
      out_of_range(name, given,
                   name == "T" ? fmt::format("16 sample-intervals <= T <= 1e10 sample-intervals, i.e. {} <= T <= {} at "
                                             "sample-interval = {} (a window of 16 to 1e10 profile samples)",
                                             rounded(16 * o.spec.sample_interval, false), rounded(1e10 * o.spec.sample_interval, true),
                                             o.spec.sample_interval)
                               : fmt::format("T / 1e10 <= sample-interval <= T / 16, i.e. {} <= sample-interval <= {} at T = {} "
                                             "(a window of 16 to 1e10 profile samples)",
                                             rounded(o.spec.T / 1e10, false), rounded(o.spec.T / 16, true), o.spec.T));
    if (o.spec.sample_interval < shortest_resolved_time(t_end))
      out_of_range("sample-interval", given_or(raw, "sample-interval", o.spec.sample_interval),
                   fmt::format("sample-interval >= {} at transient + T = {} (1e6 times the clock's resolution there)",
                               rounded(shortest_resolved_time(t_end), false), t_end));
  }
  return o;
}

}  // namespace granchain
