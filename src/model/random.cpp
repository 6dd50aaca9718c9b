#include "model/random.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "model/state_archive.hpp"

namespace granchain {

std::uint64_t derive_seed(std::uint64_t base, std::uint64_t stream) {
  std::uint64_t z = base + 0x9E3779B97F4A7C15ULL * (stream + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

double Rng::normal() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  const double u1 = 1.0 - uniform01();  // (0, 1]: log is finite
  const double u2 = uniform01();
  const double r = std::sqrt(-2.0 * std::log(u1));
  const double phi = 2.0 * std::numbers::pi * u2;
  spare_ = r * std::sin(phi);
  has_spare_ = true;
  return r * std::cos(phi);
}

// The Mersenne twister's state as the standard's text form (its 312 words), which reads back exactly.
void Rng::save(StateArchive& out) const {
  std::ostringstream words;
  words << engine_;
  out["mt19937_64"] = words.str();
  out["spare"] = spare_;
  out["has_spare"] = has_spare_;
}

void Rng::restore(const StateArchive& in) {
  std::istringstream words(saved_value<std::string>(in, "mt19937_64"));
  words >> engine_;
  if (words.fail()) throw StateArchiveError("saved state: the random generator's state does not read back");
  spare_ = saved_value<double>(in, "spare");
  has_spare_ = saved_value<bool>(in, "has_spare");
}

}  // namespace granchain
