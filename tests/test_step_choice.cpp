// The exact engine's step rule (engines/exact/step_choice.hpp), shared by the free and the grounded
// cluster's contact-end searches: on families of functions c + a sin(w s + phi) — an overlap's
// shape, a constant plus a mode — the step never passes a root of any function, held functions take
// no part, and steps repeated from where the last one ended close in on the earliest root.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "engines/exact/step_choice.hpp"

namespace granchain {
namespace {

using taylor::Jet;
using taylor::P;
using taylor::shortest_safe_step;

struct Wave {
  double c, a, w, phi;
  double at(double s) const { return c + a * std::sin(w * s + phi); }
  // Derivatives 0 .. P-1 at s, and bounds on |f''| and |f^(P)| for all later s.
  Jet jet(double s) const {
    Jet j;
    double wn = 1.0;
    for (int n = 0; n < P; ++n, wn *= w) j.d[n] = a * wn * std::sin(w * s + phi + n * std::numbers::pi / 2);
    j.d[0] += c;
    j.m2 = std::abs(a) * w * w;
    j.mP = std::abs(a) * std::pow(w, P);
    return j;
  }
  // First root at or after s0 (none: infinity), by a fine scan and bisection.
  double first_root(double s0, double s_max) const {
    const double ds = 1e-3 / w;
    double lo = s0;
    if (at(lo) <= 0) return s0;
    for (double hi = s0 + ds; hi <= s_max; lo = hi, hi += ds) {
      if (at(hi) <= 0) {
        for (int it = 0; it < 200; ++it) {
          const double mid = 0.5 * (lo + hi);
          (at(mid) > 0 ? lo : hi) = mid;
        }
        return hi;
      }
    }
    return std::numeric_limits<double>::infinity();
  }
};

struct Family {
  std::vector<Wave> f;
  std::vector<double> hq;
  std::vector<bool> held;
  taylor::StepChoice step(double s) {
    double m2 = 0.0;
    for (const Wave& g : f) m2 = std::max(m2, std::abs(g.a) * g.w * g.w);
    auto value = [&](int k) { return f[k].at(s); };
    auto rate = [&](int k) { return f[k].jet(s).d[1]; };
    auto jet_of = [&](int k) { return f[k].jet(s); };
    auto is_held = [&](int k) { return static_cast<bool>(held[k]); };
    return shortest_safe_step(static_cast<int>(f.size()), m2, 0.0, 0.0, hq.data(), value, rate, jet_of, is_held);
  }
};

Family random_family(std::mt19937_64& rng, int n) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Family fam;
  for (int k = 0; k < n; ++k) {
    const double a = 0.2 + u(rng), c = a * (0.3 + 1.2 * u(rng));  // reaches zero when c < a
    Wave g{c, a, 0.5 + 4.0 * u(rng), 0.0};
    do g.phi = 2 * std::numbers::pi * u(rng);
    while (!(g.at(0.0) > 0.05 * a));  // every function starts above zero
    fam.f.push_back(g);
  }
  fam.hq.assign(n, 0.0);
  fam.held.assign(n, false);
  return fam;
}

TEST(StepChoice, NeverStepsOverARootAndClosesInOnTheEarliest) {
  std::mt19937_64 rng(20261127);
  int families_with_root = 0;
  for (int trial = 0; trial < 200; ++trial) {
    Family fam = random_family(rng, 1 + trial % 12);
    const double horizon = 20.0;
    double earliest = std::numeric_limits<double>::infinity();
    int first = -1;
    for (int k = 0; k < static_cast<int>(fam.f.size()); ++k) {
      const double r = fam.f[k].first_root(0.0, horizon);
      if (r < earliest) earliest = r, first = k;
    }
    double s = 0.0, found = -1.0;
    int which = -1;
    for (int it = 0; it < 4000 && s < horizon; ++it) {
      const taylor::StepChoice c = fam.step(s);
      if (c.root_now) {  // a step ended on a root within round-off: found here
        ASSERT_GT(it, 0) << "trial " << trial;  // (no function starts at zero)
        found = s;
        which = c.which;
        break;
      }
      ASSERT_GE(c.h, 0.0);
      ASSERT_LE(s + c.h, earliest * (1 + 1e-12)) << "trial " << trial << ": a step passed a root";
      if (c.jet.root_upper() - c.h <= 1e-15 * (s + 1.0)) {
        found = s + c.h;
        which = c.which;
        break;
      }
      s += c.h;
    }
    if (std::isinf(earliest)) {
      EXPECT_LT(found, 0.0) << "trial " << trial << ": a root reported where there is none";
      continue;
    }
    ++families_with_root;
    ASSERT_GE(found, 0.0) << "trial " << trial << ": the search did not close in on the root at " << earliest;
    EXPECT_NEAR(found, earliest, 1e-9 * (1 + earliest)) << "trial " << trial;
    EXPECT_EQ(which, first) << "trial " << trial;
  }
  EXPECT_GT(families_with_root, 100);  // the test covers roots (c < a in most families)
}

TEST(StepChoice, AFunctionAtZeroMovingDownIsARootNowAndAHeldOneTakesNoPart) {
  Family fam;
  fam.f = {{1.0, 0.5, 1.0, 0.0}, {0.0, -0.5, 2.0, 0.0}, {2.0, 0.3, 3.0, 1.0}};  // f1(0) = 0, f1'(0) = -1
  fam.hq.assign(3, 0.0);
  fam.held.assign(3, false);
  taylor::StepChoice c = fam.step(0.0);
  EXPECT_TRUE(c.root_now);
  EXPECT_EQ(c.which, 1);
  fam.held[1] = true;  // held: its root does not count, the others limit the step
  c = fam.step(0.0);
  EXPECT_FALSE(c.root_now);
  EXPECT_GT(c.h, 0.0);
  EXPECT_NE(c.which, 1);
  for (const int k : {0, 2}) EXPECT_GE(fam.f[k].first_root(0.0, 50.0), c.h);
}

}  // namespace
}  // namespace granchain
