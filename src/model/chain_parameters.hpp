#pragma once
// Physical parameters of the chain (paper Sec. II.A-B) and the contact law derived from them.

namespace granchain {

// N identical spheres of mass m and diameter d on a vertical line, numbered from the bottom,
// neighbours interacting by the linear spring-dashpot force of Eq. (force-0) while they overlap.
struct ChainParameters {
  int N = 25;         // number of particles
  double m = 1.0;     // particle mass
  double d = 1.0;     // particle diameter
  double g = 1.0;     // gravitational acceleration (0 for free space)
  double k = 1e5;     // elastic constant of the spring
  double e = 0.9;     // restitution coefficient of a binary collision, in (0, 1]
  double kT0 = 1.0;   // temperature of the thermal floor, k_B T0
};

// Damping constant D of Eq. (Dd): D = sqrt((2k/m) (ln e)^2 / (pi^2 + (ln e)^2)).
double damping_constant(double k, double e, double m);

// Duration of a binary contact, Eq. (tauc): tau_c = pi / sqrt(2k/m - D^2).
double contact_time(double k, double D, double m);

// Everything an engine needs to know about one contact, derived once from the parameters.
struct ContactLaw {
  double k_over_m = 0;  // k/m
  double D = 0;         // Eq. (Dd); the dashpot force is -D m v_{i,i+1}
  double tau_c = 0;     // Eq. (tauc)
};
ContactLaw contact_law(const ChainParameters& p);

}  // namespace granchain
