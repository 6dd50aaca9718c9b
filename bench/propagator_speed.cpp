// One step of a cluster's overlaps, two ways, per cluster size, in one invocation:
//  - fixed step: ChainPropagator::advance, one step h = tau_c / 2 of (x, x') in overlap
//    coordinates (banded kernel, no transcendental function);
//  - closed form: what each root-free step of today's contact search evaluates before its bounds,
//    every mode at a new time from its formation (ModeConstants::evolve: exp and sincos) and the
//    overlaps and rates from the modes (two projections x = S y, dense or FFTW).
//
//   build/bench/propagator_speed [--repeat R]
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <vector>

#include "bench_cli.hpp"
#include "engines/exact/chain_propagator.hpp"
#include "engines/exact/cluster_modes.hpp"
#include "model/chain_parameters.hpp"

using namespace granchain;

int main(int argc, char** argv) {
  CLI::App app{"granchain: a cluster's overlaps one step on, fixed-step propagator against closed-form modes, ns per step"};
  int repeat = 5;
  bench::add_repeat_option(app, repeat);
  if (const auto code = bench::parse_or_exit(app, argc, argv, "propagator_speed")) return *code;
  fmt::print("{:>5} {:>5} {:>5} {:>12} {:>14} {:>7}\n", "e", "n", "band", "fixed ns", "closed-form ns", "ratio");
  for (double e : {0.1, 0.5, 0.9}) {
    const ChainParameters p{.N = 2, .k = 1e8, .e = e};
    const ContactLaw law = contact_law(p);
    const ChainPropagator prop(law.k_over_m, law.D, 0.5 * law.tau_c);
    for (int n : {3, 5, 10, 25, 50, 100, 150, 300, 1000}) {
      const ClusterModeTable table(n, law.k_over_m, law.D);
      const int M = n - 1;
      std::vector<double> x(M), xd(M), x2(M), xd2(M), y0(M), yd0(M), y(M), yd(M);
      for (int i = 0; i < M; ++i) {
        x[i] = 1e-3 * std::sin(1.3 * i + 0.2);
        xd[i] = 1e-3 * std::cos(0.7 * i);
      }
      table.to_modes(x.data(), y0.data());
      table.to_modes(xd.data(), yd0.data());
      const int calls = std::max(100, 2000000 / (M * 40));
      volatile double sink = 0;
      auto time = [&](auto step) {
        return bench::fastest_ns_per_call(repeat, calls, [&](int c) {
          step(c);
          sink = sink + x2[M / 2];
        });
      };
      const double fixed = time([&](int) {
        prop.advance(n, x.data(), xd.data(), x2.data(), xd2.data());
        x[0] += 1e-30;  // a new input every call
      });
      const double closed = time([&](int c) {
        const double tau = (0.25 + 1e-3 * (c % 512)) * law.tau_c;
        for (int j = 0; j < M; ++j) table.modes[j].evolve(y0[j], yd0[j], tau, y[j], yd[j]);
        table.to_overlaps(y.data(), x2.data());
        table.to_overlaps(yd.data(), xd2.data());
      });
      fmt::print("{:>5} {:>5} {:>5} {:>12.0f} {:>14.0f} {:>7.1f}\n", e, n, prop.band(), fixed, closed, closed / fixed);
    }
  }
  fmt::print("h = tau_c / 2; ratio: closed form / fixed step. Fastest of {} timings per size.\n", repeat);
  return 0;
}
