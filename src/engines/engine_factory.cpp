#include "engines/engine_factory.hpp"

#include <stdexcept>

#include "engines/exact/exact_engine.hpp"
#include "engines/runge_kutta_engine.hpp"

namespace granchain {

const std::vector<std::string>& engine_names() {
  static const std::vector<std::string> names{"exact", "reference", "reference-located", "hard"};
  return names;
}

std::unique_ptr<Engine> make_engine(const EngineChoice& choice, const ChainParameters& p,
                                    const ChainState& initial, FloorDrive* floor) {
  if (choice.name == "reference" || choice.name == "reference-located") {
    return std::make_unique<RungeKuttaEngine>(p, initial, floor,
                                              RungeKuttaOptions{choice.dt_factor, choice.name != "reference"});
  }
  if (choice.name == "exact") return std::make_unique<ExactEngine>(p, initial, floor, ExactOptions{.audit = choice.audit});
  if (choice.name == "hard") return std::make_unique<HardSphereEngine>(p, initial, floor, choice.hard);
  throw std::invalid_argument("unknown engine '" + choice.name + "'");
}

}  // namespace granchain
