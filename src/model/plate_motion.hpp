#pragma once
// Vibrating bottom plates: the drives of the classical one-dimensional columns (Luding, Clement,
// Blumen, Rajchenbach, Duran, PRE 49, 1634: a sinusoid; Bernu, Delyon, Mazighi, PRE 50, 4551: a
// sawtooth and a piecewise-quadratic motion) beside the paper's thermal floor (Sec. II.A).
//
// The plate's surface is at height z_p(t); particle 1 touches it while its lower edge is below the
// surface, z_1 - d/2 < z_p. The plate is an infinitely heavy sphere with the contact law of twice
// the spring and twice the dashpot of a pair (force on particle 1: 2k x_w + 2 m D x_w', x_w =
// z_p + d/2 - z_1 > 0): particle 1 meets the plate as it would meet its mirror image in a plate
// at rest (Eq. symmetry of the paper), so a collision with the plate has the restitution e and
// the duration tau_c of a binary collision (Eqs. Dd, tauc) and the hard-sphere limit k -> infinity
// at fixed e is a hard plate with restitution e.
//
// Phase theta(t) = omega t + phi, cycle fraction c = frac(theta / 2 pi); each run draws phi
// uniformly in [0, 2 pi) from its seed.
//   sine       z_p = A sin theta                                     peak acceleration A omega^2
//   sawtooth   z_p = A (2c - 1): rises at the constant speed A omega / pi from -A to A, then drops
//              back to -A at once (c = 0)                            (the drop: infinite)
//   quadratic  z_p = A (1 - (4c - 1)^2) for c < 1/2, -A (1 - (4c - 3)^2) for c >= 1/2: arcs of
//              constant acceleration -+8 A omega^2 / pi^2, z_p and v_p continuous, a_p switching
//              sign at c = 0 and 1/2                                  peak acceleration 8 A omega^2 / pi^2
// Gamma = peak acceleration / g, the control parameter of both papers (a sphere resting on the
// plate stays on it for Gamma <= 1).
#include <compare>
#include <string>
#include <string_view>

namespace granchain {

enum class DriveKind { Thermal, Sine, Sawtooth, Quadratic };

// "thermal", "sine", "sawtooth", "quadratic": as typed and stored.
const char* drive_name(DriveKind kind);
// The drive of that name; false when there is none.
bool find_drive(std::string_view name, DriveKind& kind);
// "thermal, sine, sawtooth, quadratic".
std::string drive_name_list();

// How the column is driven from below: the thermal floor (Sec. II.A) or a plate of amplitude A
// (half its stroke, units of d) and angular frequency omega.
struct DriveSpec {
  DriveKind kind = DriveKind::Thermal;
  double A = 0.0;
  double omega = 0.0;
  bool plate() const { return kind != DriveKind::Thermal; }
  auto operator<=>(const DriveSpec&) const = default;  // families of an analysis are per drive
  bool operator==(const DriveSpec&) const = default;
};

// "" for the thermal floor, else ", sine plate A = 0.08, omega = 5": what names a drive beside a
// family's engine, N and T0 in reports.
std::string drive_label(const DriveSpec& drive);

// Peak plate acceleration over A omega^2 (1 for the sine, 8 / pi^2 for the quadratic arcs,
// infinite for the sawtooth's drop): Gamma = gamma_factor * A omega^2 / g.
double gamma_factor(DriveKind kind);

class PlateMotion {
 public:
  // kind must be a plate; A > 0, omega > 0, phase in [0, 2 pi).
  PlateMotion(DriveKind kind, double A, double omega, double phase);

  DriveKind kind() const { return kind_; }
  double amplitude() const { return A_; }
  double omega() const { return omega_; }
  double phase() const { return phase_; }

  // Height, velocity and acceleration of the surface at time t. At a switching instant (see
  // next_switch) they are those of the piece that begins there.
  double z(double t) const;
  double v(double t) const;
  double a(double t) const;
  // The first switching instant after t (strictly): where the sawtooth drops or the quadratic's
  // acceleration changes sign; infinity for the sine. Between two switching instants the
  // piecewise drives are polynomials of degree <= 2.
  double next_switch(double t) const;
  // The highest the surface ever is (A) and its largest speed: A omega (sine), A omega / pi
  // (sawtooth, drops aside), 4 A omega / pi (quadratic).
  double top() const { return A_; }
  double max_speed() const;

 private:
  // The cycle fraction c in [0, 1) at time t.
  double cycle(double t) const;

  DriveKind kind_;
  double A_, omega_, phase_;
  double cycles_per_time_;  // omega / 2 pi
  double cycle0_;           // phase / 2 pi
};

}  // namespace granchain
