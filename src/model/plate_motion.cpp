#include "model/plate_motion.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace granchain {

namespace {

struct DriveName {
  DriveKind kind;
  const char* name;
};
constexpr DriveName kDrives[] = {{DriveKind::Thermal, "thermal"},
                                 {DriveKind::Sine, "sine"},
                                 {DriveKind::Sawtooth, "sawtooth"},
                                 {DriveKind::Quadratic, "quadratic"}};

constexpr double kPi = std::numbers::pi;

}  // namespace

const char* drive_name(DriveKind kind) {
  for (const auto& d : kDrives)
    if (d.kind == kind) return d.name;
  throw std::logic_error("drive_name: a kind without a name");
}

bool find_drive(std::string_view name, DriveKind& kind) {
  for (const auto& d : kDrives)
    if (name == d.name) {
      kind = d.kind;
      return true;
    }
  return false;
}

std::string drive_name_list() {
  std::string s;
  for (const auto& d : kDrives) s += (s.empty() ? "" : ", ") + std::string(d.name);
  return s;
}

std::string drive_label(const DriveSpec& drive) {
  if (!drive.plate()) return "";
  return fmt::format(", {} plate A = {:g}, omega = {:g}", drive_name(drive.kind), drive.A, drive.omega);
}

double gamma_factor(DriveKind kind) {
  switch (kind) {
    case DriveKind::Sine: return 1.0;
    case DriveKind::Quadratic: return 8.0 / (kPi * kPi);
    case DriveKind::Sawtooth: return std::numeric_limits<double>::infinity();
    case DriveKind::Thermal: break;
  }
  return 0.0;
}

PlateMotion::PlateMotion(DriveKind kind, double A, double omega, double phase)
    : kind_(kind), A_(A), omega_(omega), phase_(phase), cycles_per_time_(omega / (2 * kPi)), cycle0_(phase / (2 * kPi)) {
  if (kind == DriveKind::Thermal) throw std::invalid_argument("PlateMotion: the thermal floor is not a plate");
  if (!(A > 0) || !(omega > 0) || !std::isfinite(A) || !std::isfinite(omega))
    throw std::invalid_argument("PlateMotion: the amplitude and the angular frequency must be positive and finite");
}

double PlateMotion::cycle(double t) const {
  const double c = cycles_per_time_ * t + cycle0_;
  const double f = c - std::floor(c);
  return f < 1.0 ? f : 0.0;
}

double PlateMotion::z(double t) const {
  switch (kind_) {
    case DriveKind::Sine: return A_ * std::sin(omega_ * t + phase_);
    case DriveKind::Sawtooth: return A_ * (2.0 * cycle(t) - 1.0);
    case DriveKind::Quadratic: {
      const double c = cycle(t);
      if (c < 0.5) {
        const double u = 4.0 * c - 1.0;
        return A_ * (1.0 - u * u);
      }
      const double u = 4.0 * c - 3.0;
      return -A_ * (1.0 - u * u);
    }
    case DriveKind::Thermal: break;
  }
  return 0.0;
}

double PlateMotion::v(double t) const {
  switch (kind_) {
    case DriveKind::Sine: return A_ * omega_ * std::cos(omega_ * t + phase_);
    case DriveKind::Sawtooth: return A_ * omega_ / kPi;
    case DriveKind::Quadratic: {
      const double c = cycle(t);
      const double scale = 4.0 * A_ * omega_ / kPi;
      return c < 0.5 ? scale * (1.0 - 4.0 * c) : scale * (4.0 * c - 3.0);
    }
    case DriveKind::Thermal: break;
  }
  return 0.0;
}

double PlateMotion::a(double t) const {
  switch (kind_) {
    case DriveKind::Sine: return -A_ * omega_ * omega_ * std::sin(omega_ * t + phase_);
    case DriveKind::Sawtooth: return 0.0;
    case DriveKind::Quadratic: {
      const double peak = 8.0 * A_ * omega_ * omega_ / (kPi * kPi);
      return cycle(t) < 0.5 ? -peak : peak;
    }
    case DriveKind::Thermal: break;
  }
  return 0.0;
}

double PlateMotion::next_switch(double t) const {
  if (kind_ == DriveKind::Sine) return std::numeric_limits<double>::infinity();
  // Switching cycle fractions: 0 (sawtooth), 0 and 1/2 (quadratic). In half-cycles h = 2c:
  const double per = kind_ == DriveKind::Sawtooth ? 1.0 : 2.0;  // switches per cycle
  const double c = (cycles_per_time_ * t + cycle0_) * per;
  double n = std::floor(c) + 1.0;
  double ts = (n / per - cycle0_) / cycles_per_time_;
  // Round-off may put the candidate at or before t: take the next one.
  while (!(ts > t)) {
    n += 1.0;
    ts = (n / per - cycle0_) / cycles_per_time_;
  }
  return ts;
}

double PlateMotion::max_speed() const {
  switch (kind_) {
    case DriveKind::Sine: return A_ * omega_;
    case DriveKind::Sawtooth: return A_ * omega_ / kPi;
    case DriveKind::Quadratic: return 4.0 * A_ * omega_ / kPi;
    case DriveKind::Thermal: break;
  }
  return 0.0;
}

}  // namespace granchain
