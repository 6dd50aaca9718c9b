// Projection of a cluster's modes onto its overlaps, x = S y: the dense product against FFTW's
// type-I sine transform, per cluster size, in one invocation. This is the measurement behind
// SineTransform::pays_off (src/engines/exact/sine_transform.hpp).
//
//   build/bench/transform_speed [--repeat R]
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <vector>

#include "bench_cli.hpp"
#include "engines/exact/cluster_modes.hpp"
#include "engines/exact/sine_transform.hpp"

using namespace granchain;

int main(int argc, char** argv) {
  CLI::App app{"granchain: dense sine product against FFTW's sine transform, ns per projection"};
  int repeat = 5;
  bench::add_repeat_option(app, repeat);
  if (const auto code = bench::parse_or_exit(app, argc, argv, "transform_speed")) return *code;
  fmt::print("{:>5} {:>5} {:>10} {:>10} {:>7}  {}\n", "n", "M", "dense ns", "FFTW ns", "ratio", "engine uses");
  for (int n : {8, 16, 24, 25, 31, 32, 37, 48, 64, 73, 100, 101, 128, 149, 150}) {
    ClusterModeTable table(n, 1e8, 3000.0);
    const int M = table.M;
    table.transform.reset();  // the dense product
    const SineTransform fast(M);
    std::vector<double> y(M), x(M);
    for (int j = 0; j < M; ++j) y[j] = std::sin(1.3 * j + 0.2);
    const int calls = std::max(200, 4000000 / (M * M));
    volatile double sink = 0;  // keeps the products from being optimised away
    auto time = [&](auto project) {
      return bench::fastest_ns_per_call(repeat, calls, [&](int c) {
        y[c % M] += 1e-12;
        project();
        sink = sink + x[M / 2];
      });
    };
    const double dense = time([&] { table.to_overlaps(y.data(), x.data()); });
    const double fftw = time([&] { fast.apply(y.data(), x.data()); });
    fmt::print("{:>5} {:>5} {:>10.0f} {:>10.0f} {:>7.2f}  {}{}\n", n, M, dense, fftw, dense / fftw,
               SineTransform::pays_off(M) ? "FFTW" : "dense", "");
  }
  fmt::print("ratio: dense / FFTW (above 1: the transform is faster). Fastest of {} timings per size.\n", repeat);
  return 0;
}
