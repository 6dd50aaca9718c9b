#pragma once
// One step of a cluster's contact-end search (a free cluster's, exact_search.cpp, and the grounded
// cluster's above a plate, exact_plate_search.cpp): over its watched functions (overlaps, and their
// distances to passing through), the longest step proven root-free for all of them, or the one
// function already at its root.
//
// Cheap quadratic steps first, from each function's value and rate with one common bound m2 on
// every second derivative; the full order-P bound (taylor_bounds.hpp) can only lengthen a step, so
// a function's jet is worked out only when its quadratic step is shorter than the best step found so
// far, and its safe step only when the Bernstein test cannot prove it positive over that step.
#include "engines/exact/taylor_bounds.hpp"

namespace granchain::taylor {

struct StepChoice {
  bool root_now = false;  // function `which` is at its root now (a found event)
  double h = kInf;        // the step (kInf: no function can ever reach zero)
  int which = -1;         // the function that limits the step
  Jet jet{};              // its jet (valid when which >= 0)
};

// value(k), rate(k): function k and its rate now; jet_of(k): its full jet; held(k): function k takes
// no part for now (a held pair). zero: values at or below it count as zero (round-off, after a
// stalled search); skip: the resolution interval a function at zero and not moving down steps over.
// hq: scratch of `functions` entries.
template <class Value, class Rate, class JetOf, class Held>
StepChoice shortest_safe_step(int functions, double m2, double zero, double skip, double* hq, const Value& value,
                              const Rate& rate, const JetOf& jet_of, const Held& held) {
  const auto step_of = [&](double f, double step) { return f <= zero ? std::max(step, skip) : step; };
  // The quadratic bound of function k: concave, so positive over [0, H] when positive at H.
  const auto quadratic_clear = [&](int k, double H) {
    const double f = value(k);
    return f > 0 && f + H * (rate(k) - 0.5 * m2 * H) > 0;
  };
  constexpr double kUnknown = -1.0;  // quadratic step not worked out: longer than some step
  StepChoice c;
  for (int k = 0; k < functions; ++k) {
    if (held(k)) {
      hq[k] = kInf;
      continue;
    }
    const double f = value(k), f1 = rate(k);
    if (f <= zero) {
      const Jet jk = jet_of(k);
      if (at_root(jk.d[0] - zero, jk.d[1], jk.d[2], jk.d[3])) {
        c.root_now = true;
        c.which = k;
        return c;
      }
    }
    if (c.h < kInf && quadratic_clear(k, c.h)) {
      hq[k] = kUnknown;
      continue;
    }
    hq[k] = step_of(f, quadratic_step(f, f1, -0.5 * m2));
    if (hq[k] < c.h) {
      c.h = hq[k];
      c.which = k;
    }
  }
  if (c.which < 0) return c;
  c.jet = jet_of(c.which);
  c.h = step_of(c.jet.d[0], safe_step(c.jet, kInf));
  for (int k = 0; k < functions; ++k) {
    if (k == c.which) continue;
    if (hq[k] == kUnknown) {
      if (quadratic_clear(k, c.h)) continue;
      hq[k] = step_of(value(k), quadratic_step(value(k), rate(k), -0.5 * m2));
    }
    if (!(hq[k] < c.h) || hq[k] == kInf) continue;
    const Jet jk = jet_of(k);
    if (jk.d[0] > 0 && jk.lower_positive(c.h)) continue;  // proven positive over the whole step
    const double hk = step_of(jk.d[0], safe_step(jk, c.h));
    if (hk < c.h) {
      c.h = hk;
      c.which = k;
      c.jet = jk;
    }
  }
  return c;
}

}  // namespace granchain::taylor
