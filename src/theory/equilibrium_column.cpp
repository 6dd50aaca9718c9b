#include "theory/equilibrium_column.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace granchain {

namespace {

struct GapMoments {
  double mean, var, density_at_zero;
};

// Moments of p(s) ~ exp(-(a s + (b/2) s^2 theta(-s))), a = W/kT0, b = k/kT0.
GapMoments soft_gap(double a, double b) {
  // s >= 0: integral of s^n exp(-a s) = n! / a^{n+1}.
  const double p0 = 1.0 / a, p1 = 1.0 / (a * a), p2 = 2.0 / (a * a * a);
  // s < 0: exp(a^2/2b) * sqrt(2 pi / b) * E[s^n; s < 0] for s ~ Normal(mu = -a/b, sigma^2 = 1/b).
  const double expo = a * a / (2.0 * b);
  if (expo > 600.0) throw std::domain_error("elastic_column_equilibrium: column too soft for closed form");
  const double mu = -a / b, sigma = 1.0 / std::sqrt(b);
  const double alpha = -mu / sigma;  // (0 - mu) / sigma
  const double Phi = 0.5 * std::erfc(-alpha / std::numbers::sqrt2);
  const double phi = std::exp(-0.5 * alpha * alpha) / std::sqrt(2.0 * std::numbers::pi);
  const double scale = std::exp(expo) * std::sqrt(2.0 * std::numbers::pi / b);
  const double n0 = scale * Phi;
  const double n1 = scale * (mu * Phi - sigma * phi);
  const double n2 = scale * ((mu * mu + sigma * sigma) * Phi - sigma * mu * phi);
  const double M0 = p0 + n0, M1 = p1 + n1, M2 = p2 + n2;
  const double mean = M1 / M0;
  return {mean, M2 / M0 - mean * mean, 1.0 / M0};
}

}  // namespace

ElasticColumnEquilibrium elastic_column_equilibrium(const ChainParameters& p) {
  if (!(p.g > 0)) throw std::domain_error("elastic_column_equilibrium: needs g > 0");
  const double beta = 1.0 / p.kT0;
  ElasticColumnEquilibrium eq;
  eq.kinetic = 0.5 * p.kT0;
  double mean = 0.5 * p.d, var = 0.0;
  const double pair_flux = std::sqrt(p.kT0 / (std::numbers::pi * p.m));
  double total_rate = 0.0;
  for (int j = 1; j <= p.N; ++j) {
    const double a = beta * p.m * p.g * (p.N - j + 1);
    if (j == 1) {
      // Hard floor: exponential gap of mean kT0 / W_1.
      mean += 1.0 / a;
      var += 1.0 / (a * a);
      eq.floor_rate = a * std::sqrt(p.kT0 / (2.0 * std::numbers::pi * p.m));
      total_rate += eq.floor_rate;
    } else {
      const GapMoments gm = soft_gap(a, beta * p.k);
      mean += p.d + gm.mean;
      var += gm.var;
      const double rate = gm.density_at_zero * pair_flux;
      eq.contact_end_rate.push_back(rate);
      total_rate += rate;
    }
    eq.z_mean.push_back(mean);
    eq.z_std.push_back(std::sqrt(var));
  }
  eq.n_coll = total_rate / p.N;
  return eq;
}

}  // namespace granchain
