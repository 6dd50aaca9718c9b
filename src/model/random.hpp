#pragma once
// Reproducible random numbers. The raw generator is std::mt19937_64, whose output the C++
// standard fixes bit for bit; the conversions to doubles are our own, so a seed gives the same
// numbers on every conforming library (std:: distributions are implementation-defined).
#include <cstdint>
#include <random>

#include "model/state_archive_fwd.hpp"

namespace granchain {

// Independent streams drawn from one user seed.
enum class RandomStream : std::uint64_t { InitialState = 1, Floor = 2, PlatePhase = 3 };

// SplitMix64 finaliser of (base, stream): decorrelated 64-bit seeds for separate streams.
std::uint64_t derive_seed(std::uint64_t base, std::uint64_t stream);

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : engine_(seed) {}
  std::uint64_t bits() { return engine_(); }
  // Uniform on [0, 1) with 53 random bits.
  double uniform01() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  // Standard normal deviate (Box-Muller, both deviates used).
  double normal();
  // The generator's whole state (model/state_archive.hpp): restored, it goes on with the same numbers.
  void save(StateArchive& out) const;
  void restore(const StateArchive& in);

 private:
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace granchain
