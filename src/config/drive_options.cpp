#include "config/drive_options.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "engines/engine_registry.hpp"
#include "model/plate_motion.hpp"

namespace granchain::run_table {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

bool plate_drive(const RunSpec& s) { return s.drive.plate(); }

// An input that only sets another parameter (Gamma sets A, f sets omega): read and range-checked
// here, used by resolve_drive.
Definition alias(Parameter p) {
  p.type = ParameterType::Real;
  return {std::move(p), false, {}, {}, [](RunOptions&, const Parameter& q, const RawValue& v) { (void)read_real(q, v); }};
}

}  // namespace

void add_drive_definitions(std::vector<Definition>& d) {
  using I = RunIdentity;
  const DriveSpec def;
  {
    Parameter p{"drive", ParameterType::Name, "",
                "what drives the column from below: the thermal floor at T0 (the paper's), or a plate vibrating as a sine, a "
                "sawtooth or arcs of constant acceleration (quadratic), touched with the contact law of a pair",
                "one of: " + drive_name_list(), drive_name(def.kind), kUseDriven | kUseTrace, EngineScope::Any, true, "drive", {}};
    p.identity = I::Physics;
    Definition drive{std::move(p), true,
                     [](const RunSpec& s) -> TypedValue { return std::string(drive_name(s.drive.kind)); },
                     [](RunSpec& s, const TypedValue& v) {
                       if (!find_drive(std::get<std::string>(v), s.drive.kind))
                         throw InputError(fmt::format("'{}' is not a drive; valid: {}", std::get<std::string>(v), drive_name_list()));
                     },
                     [](RunOptions& o, const Parameter& q, const RawValue& v) {
                       if (!find_drive(read_name(q, v), o.spec.drive.kind))
                         throw InputError(fmt::format("--drive = '{}'{} is not a drive; valid: {}", v.text(), from_where(v), drive_name_list()));
                     }};
    // NULL in the store and absent from the point key for the thermal floor: the runs of the
    // paper's column keep their identity.
    drive.acts_in = plate_drive;
    d.push_back(std::move(drive));
  }
  Definition A = real({"A", {}, "d", "plate: amplitude, half the stroke (the surface moves between -A and A)", "A > 0",
                       "none: give A or Gamma with a plate", kUseDriven | kUseTrace, EngineScope::Any, true, "plate_A",
                       [](double x) { return x > 0; }},
                      I::Physics, [](auto& s) -> auto& { return s.drive.A; });
  A.nullable = true;
  A.acts_in = plate_drive;
  d.push_back(std::move(A));
  Definition omega = real({"omega", {}, "sqrt(g / d)", "plate: angular frequency", "omega > 0", "none: give omega or f with a plate",
                           kUseDriven | kUseTrace, EngineScope::Any, true, "plate_omega", [](double x) { return x > 0; }},
                          I::Physics, [](auto& s) -> auto& { return s.drive.omega; });
  omega.nullable = true;
  omega.acts_in = plate_drive;
  d.push_back(std::move(omega));
  d.push_back(alias({"Gamma", {}, "",
                     "plate: peak acceleration over g, sets A: Gamma = A omega^2 / g (sine), 8 A omega^2 / (pi^2 g) (quadratic); "
                     "a sphere at rest on the plate stays there for Gamma <= 1",
                     "Gamma > 0 (sine, quadratic)", "none", kUseDriven | kUseTrace, EngineScope::Any, true, "",
                     [](double x) { return x > 0; }}));
  d.push_back(alias({"f", {}, "sqrt(g / d)^-1", "plate: frequency, sets omega = 2 pi f", "f > 0", "none", kUseDriven | kUseTrace,
                     EngineScope::Any, true, "", [](double x) { return x > 0; }}));
}

void resolve_drive(RunOptions& o, const std::map<std::string, RawValue>& raw) {
  DriveSpec& drive = o.spec.drive;
  const ChainParameters& p = o.spec.params;
  const auto given = [&](const char* name) { return raw.count(name) > 0; };
  const auto real_of = [&](const char* name) { return read_real(*find_parameter(run_parameters(), name), raw.at(name)); };
  if (!drive.plate()) {
    for (const char* name : {"A", "omega", "Gamma", "f"})
      if (given(name))
        throw InputError(fmt::format("--{} = {}{} sets a vibrating plate, and --drive is thermal; valid: leave --{} out, or "
                                     "--drive one of sine, sawtooth, quadratic",
                                     name, raw.at(name).text(), from_where(raw.at(name)), name));
    return;
  }
  const EngineInfo& engine = engine_info(o.spec.engine.kind);

  if (given("omega") && given("f"))
    throw InputError(fmt::format("--f = {}{}: the frequency is given twice, with --omega = {}; valid: one of --omega, --f",
                                 raw.at("f").text(), from_where(raw.at("f")), raw.at("omega").text()));
  if (given("A") && given("Gamma"))
    throw InputError(fmt::format("--Gamma = {}{}: the amplitude is given twice, with --A = {}; valid: one of --A, --Gamma",
                                 raw.at("Gamma").text(), from_where(raw.at("Gamma")), raw.at("A").text()));
  const char* kind = drive_name(drive.kind);
  if (given("f")) drive.omega = kTwoPi * real_of("f");
  else if (!given("omega"))
    throw InputError(fmt::format("--drive {} needs the plate's frequency; valid: --omega > 0 or --f > 0", kind));
  if (given("Gamma")) {
    if (drive.kind == DriveKind::Sawtooth)
      throw InputError(fmt::format("--Gamma = {}{}: the sawtooth's drop has no finite peak acceleration; valid: give its amplitude, --A > 0",
                                   raw.at("Gamma").text(), from_where(raw.at("Gamma"))));
    drive.A = real_of("Gamma") * p.g / (gamma_factor(drive.kind) * drive.omega * drive.omega);
  } else if (!given("A")) {
    throw InputError(fmt::format("--drive {} needs the plate's amplitude; valid: --A > 0{}", kind,
                                 drive.kind == DriveKind::Sawtooth ? "" : " or --Gamma > 0"));
  }
  const char* amplitude = given("Gamma") ? "Gamma" : "A";
  const char* frequency = given("f") ? "f" : "omega";
  if (!std::isfinite(drive.A) || !(drive.A > 0))
    value_out_of_range(amplitude, raw.at(amplitude), fmt::format("a finite amplitude A > 0 at omega = {}", drive.omega));

  // The plate's motion must be slow beside a contact for a soft sphere to follow it: its period at
  // least 10 tau_c (the hard-sphere limit is tau_c -> 0 at fixed omega).
  if (!engine.hard_spheres) {
    const double tau_c = contact_law(p).tau_c;
    const double omega_max = kTwoPi / (10.0 * tau_c);
    if (!(drive.omega <= omega_max)) {
      const double factor = given("f") ? 1.0 / kTwoPi : 1.0;
      value_out_of_range(frequency, raw.at(frequency),
                         fmt::format("0 < {} <= {} at k = {}, e = {}, m = {}: the plate's period must last at least 10 contact "
                                     "times (tau_c = {:.3g})",
                                     frequency, rounded_bound(omega_max * factor, true), p.k, p.e, p.m, tau_c));
    }
  }
  // Heights: the plate throws particle 1 to about (peak plate speed)^2 / g above its stroke; with
  // the stack and the floor temperature's height (run_options.cpp, check_height_scale) this must
  // stay where heights resolve d to 1e-6.
  const PlateMotion motion(drive.kind, drive.A, drive.omega, 0.0);
  const double R = std::ldexp(1.0, 52) / kResolutionSteps;
  const double height = (drive.A + motion.max_speed() * motion.max_speed() / p.g) / p.d;
  if (!(height + p.N + p.kT0 / p.m / p.g / p.d <= R))
    value_out_of_range(amplitude, raw.at(amplitude),
                       fmt::format("A + (peak plate speed)^2 / g <= {:.2g} d at N = {}, omega = {} (the column's height scale must "
                                   "stay below {:.2g} d, where heights resolve d to 1e-6)",
                                   R - p.N - p.kT0 / p.m / p.g / p.d, p.N, drive.omega, R));
}

}  // namespace granchain::run_table
