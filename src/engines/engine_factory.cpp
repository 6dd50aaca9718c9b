#include "engines/engine_factory.hpp"

#include <stdexcept>

#include "engines/runge_kutta_engine.hpp"

namespace granchain {

const std::vector<std::string>& engine_names() {
  static const std::vector<std::string> names{"reference"};
  return names;
}

std::unique_ptr<Engine> make_engine(const EngineChoice& choice, const ChainParameters& p,
                                    const ChainState& initial, FloorDrive* floor) {
  if (choice.name == "reference") {
    return std::make_unique<RungeKuttaEngine>(p, initial, floor, RungeKuttaOptions{choice.dt_factor});
  }
  throw std::invalid_argument("unknown engine '" + choice.name + "'");
}

}  // namespace granchain
