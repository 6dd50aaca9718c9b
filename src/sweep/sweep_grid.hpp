#pragma once
// A parameter sweep over the driven column: the grid of points, each point's identity (its key),
// its seed and its estimated cost. Everything here is a pure function of the sweep's definition,
// so every thread, MPI rank and job-array shard builds the same points in the same order.
#include <cstdint>
#include <map>
#include <string>
#include <unordered_set>
#include <vector>

#include "config/run_options.hpp"
#include "simulation/driven_run.hpp"
#include "sweep/cost_model.hpp"

namespace granchain {

// Parameters that take a list or range in a sweep (each point takes one value of each).
const std::vector<std::string>& sweep_grid_parameters();

struct SweepDefinition {
  // Text of every parameter as given (flag or sweep file). Grid parameters may hold lists
  // ("3,4,5", "0.80:0.90:0.002", "1e5:1e10:x10"); the rest are single values of `granchain run`.
  std::map<std::string, RawValue> raw;
  int replicas = 1;             // independent runs per grid point
  std::uint64_t base_seed = 1;  // each point's seed derives from it and the point's parameters
};

struct SweepPoint {
  RunSpec spec;                 // complete, seed included
  int replica = 0;              // 0 .. replicas-1
  std::string key;              // identity of the run in the store (config/run_key.hpp)
  double cost = 0.0;            // estimated seconds of one core (sweep/cost_model.hpp)
};

// The 64-bit FNV-1a hash of a text (a point's key): the same on every machine and build.
std::uint64_t fnv1a(const std::string& s);

// Seed of a sweep point: SplitMix64 of (base seed, FNV-1a hash of the point's key without its
// seed, replica), kept to 63 bits. Depends on nothing else (not on thread, rank, shard or order).
std::uint64_t point_seed(std::uint64_t base_seed, const RunSpec& spec_without_seed, int replica);


// Expands the grid (validating every point as `granchain run` would; InputError on bad input)
// and orders it longest first, ties by key. The hard engine ignores the k list (its k is
// infinite) and the TC time applies to it alone.
std::vector<SweepPoint> build_sweep_points(const SweepDefinition& def);

// Indices of the points whose keys are not among `stored`, in the order of `points`.
std::vector<std::size_t> points_to_run(const std::vector<SweepPoint>& points, const std::unordered_set<std::string>& stored);

// Indices of points in the order a table of results lists them: by engine name, N, k_B T0, drive,
// A, omega, k, T, e and replica.
std::vector<std::size_t> table_order(const std::vector<SweepPoint>& points);

// Job-array share i of n (1 <= i <= n): points j (in build order) with j mod n = i - 1, so each
// shard gets long and short points alike.
std::vector<SweepPoint> shard_points(const std::vector<SweepPoint>& points, int i, int n);

}  // namespace granchain
