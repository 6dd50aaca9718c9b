#include "engines/plate_flight.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engines/free_flight.hpp"

namespace granchain::plate_flight {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
// Root-free steps of one sine search before it gives up on converging further and takes the
// value reached as the root (never seen: a simple root converges in a handful of steps).
constexpr int kMaxSteps = 100000;
}  // namespace

double first_root_any(double c0, double c1, double p2) {
  if (p2 <= 0) return free_flight::first_root(c0, c1, p2);
  if (c0 <= 0 && c1 < 0) return 0.0;
  if (c1 >= 0) return kInf;  // convex and rising from >= 0
  const double disc = c1 * c1 - 2.0 * p2 * std::max(c0, 0.0);
  if (disc < 0) return kInf;                    // its minimum stays above zero
  return 2.0 * std::max(c0, 0.0) / (std::sqrt(disc) - c1);  // the smaller root, without cancellation
}

PieceState piece_state(const PlateMotion& plate, double t) {
  if (plate.kind() == DriveKind::Sine) return {plate.z(t), plate.v(t), plate.a(t)};
  // Read the piece at its middle, where no round-off of the cycle fraction can put it on a
  // neighbour, and carry it back to t exactly (a polynomial of degree <= 2).
  const double s = 0.5 * (plate.next_switch(t) - t);
  const double tm = t + s;
  const double a = plate.a(tm);
  const double v = plate.v(tm) - a * s;
  return {plate.z(tm) - plate.v(tm) * s + 0.5 * a * s * s, v, a};
}

Contact first_contact(const PlateMotion& plate, double t0, double h0, double w0, double g) {
  if (plate.kind() != DriveKind::Sine) {
    const double t_end = plate.next_switch(t0);
    const PieceState p = piece_state(plate, t0);
    const double s = first_root_any(h0 - p.z, w0 - p.v, -(g + p.a));
    if (t0 + s < t_end) return {Contact::Touch, t0 + s};
    return {Contact::Switch, t_end};
  }
  const double A = plate.amplitude(), omega = plate.omega();
  const double B = g + A * omega * omega;  // -f'' <= B
  // Down to the top of the stroke first: no contact above it.
  double s = h0 > A ? free_flight::first_root(h0 - A, w0, -g) : 0.0;
  if (s == kInf) return {Contact::None, kInf};
  const double scale = std::abs(h0) + A + std::abs(w0) + 1.0;
  for (int step = 0; step < kMaxSteps; ++step) {
    const double t = t0 + s;
    const double f = h0 + s * (w0 - 0.5 * g * s) - plate.z(t);
    const double f1 = w0 - g * s - plate.v(t);
    // At the root (within round-off of the heights) and approaching: the contact.
    if (f <= 4e-16 * scale && f1 < 0) return {Contact::Touch, t};
    double h = free_flight::quadratic_step(f, f1, -0.5 * B);
    // At zero but not approaching (grazing within round-off): move on by a step that resolves time.
    if (!(h > 0)) h = 1e-12 * std::max(1.0, std::abs(t)) / std::max(omega, 1.0);
    const double next = s + h;
    if (!(next > s)) return {Contact::Touch, t};  // time no longer resolves the step: the root is here
    s = next;
  }
  return {Contact::Touch, t0 + s};
}

}  // namespace granchain::plate_flight
