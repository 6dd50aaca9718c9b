#pragma once
// Free flight, shared by the event-driven engines (hard spheres, exact soft spheres): the gap
// between two free particles is a line in time (gravity cancels in the difference), the height of
// a free particle above the floor a parabola. Each event time is the first root of
// c0 + c1 s + p2 s^2 / 2, written without cancellation for either sign of c1.
#include <cmath>
#include <limits>

namespace granchain::free_flight {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

// First positive root of f + f1 h + a h^2 with a <= 0 (a negative f counts as zero), +inf if
// there is none. The exact engine also uses it as the longest step over which a quadratic lower
// bound of a watched function stays positive.
inline double quadratic_step(double f, double f1, double a) {
  if (f < 0) f = 0;
  if (a >= 0) return f1 < 0 ? f / -f1 : kInf;
  const double disc = std::sqrt(f1 * f1 - 4.0 * a * f);  // >= |f1|
  return f1 >= 0 ? (f1 + disc) / (-2.0 * a) : 2.0 * f / (disc - f1);
}

// First time s >= 0 at which c0 + c1 s + p2 s^2 / 2 (p2 <= 0) reaches zero: 0 when it is at or
// below zero and moving down. A value at zero with no rate and no acceleration (two free spheres
// touching at equal velocities, in free space) stays there: no root.
inline double first_root(double c0, double c1, double p2) {
  return c0 <= 0 && (c1 < 0 || (c1 == 0 && p2 < 0)) ? 0.0 : quadratic_step(c0, c1, 0.5 * p2);
}

}  // namespace granchain::free_flight
