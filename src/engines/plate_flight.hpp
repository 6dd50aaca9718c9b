#pragma once
// A free-flying particle above a vibrating plate (model/plate_motion.hpp): when does its lower
// edge first reach the plate's surface? The height above the surface is
//   f(s) = h0 + w0 s - g s^2 / 2 - z_p(t0 + s),
// with h0 = z_1(t0) - d/2 and w0 = v_1(t0). Between the switching instants of the piecewise drives
// z_p is a polynomial of degree <= 2 and f's first root is found in closed form; the piece's end is
// then an event of its own (the surface's formula changes there). For the sine, f is searched by
// steps proven root-free: f'' >= -(g + A omega^2), so f stays above f(s) + f'(s) h - (g + A omega^2)
// h^2 / 2, whose first root is the next step; the steps converge onto the root (quadratically at a
// simple root), so no contact can be skipped. The search starts where the particle has come down
// to the top of the stroke, z_1 - d/2 = A.
#include "model/plate_motion.hpp"

namespace granchain::plate_flight {

struct Contact {
  enum Kind { Touch, Switch, None } kind = None;
  double t = 0;  // the instant: the surface is reached (Touch), or the piece ends first (Switch)
};

// The first instant after t0 at which the particle touches the surface while approaching it (or,
// for a piecewise drive, the end of the current piece if that comes first). h0 >= z_p(t0) up to
// round-off.
Contact first_contact(const PlateMotion& plate, double t0, double h0, double w0, double g);

// The surface's height, velocity and acceleration at t on the piece that begins at or before t and
// ends at next_switch(t) (at a switching instant: the new piece's, whatever the round-off of t).
struct PieceState {
  double z, v, a;
};
PieceState piece_state(const PlateMotion& plate, double t);

// First s >= 0 at which c0 + c1 s + p2 s^2 / 2 reaches zero for either sign of p2 (free_flight's
// first_root takes p2 <= 0 only): a convex parabola going down may miss zero.
double first_root_any(double c0, double c1, double p2);

}  // namespace granchain::plate_flight
