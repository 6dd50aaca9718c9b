#include "model/chain_parameters.hpp"

#include <cmath>
#include <numbers>

namespace granchain {

double damping_constant(double k, double e, double m) {
  const double l2 = std::log(e) * std::log(e);
  return std::sqrt((2.0 * k / m) * l2 / (std::numbers::pi * std::numbers::pi + l2));
}

double contact_time(double k, double D, double m) {
  return std::numbers::pi / std::sqrt(2.0 * k / m - D * D);
}

ContactLaw contact_law(const ChainParameters& p) {
  ContactLaw c;
  if (std::isinf(p.k)) {  // hard spheres: instantaneous contacts of infinite stiffness
    c.k_over_m = c.D = p.k;
    c.tau_c = 0.0;
    return c;
  }
  c.k_over_m = p.k / p.m;
  c.D = damping_constant(p.k, p.e, p.m);
  c.tau_c = contact_time(p.k, c.D, p.m);
  return c;
}

}  // namespace granchain
