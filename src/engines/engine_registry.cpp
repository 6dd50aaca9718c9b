#include "engines/engine_registry.hpp"

#include <stdexcept>

#include "engines/exact/exact_engine.hpp"
#include "engines/hard_sphere_engine.hpp"
#include "engines/runge_kutta_engine.hpp"

namespace granchain {

namespace {

std::unique_ptr<Engine> make_exact(const EngineChoice& c, const ChainParameters& p, const ChainState& s, FloorDrive* f) {
  return std::make_unique<ExactEngine>(p, s, f, ExactOptions{.audit = c.audit});
}
std::unique_ptr<Engine> make_reference(const EngineChoice& c, const ChainParameters& p, const ChainState& s, FloorDrive* f) {
  return std::make_unique<RungeKuttaEngine>(p, s, f, RungeKuttaOptions{c.dt_factor, false});
}
std::unique_ptr<Engine> make_reference_located(const EngineChoice& c, const ChainParameters& p, const ChainState& s, FloorDrive* f) {
  return std::make_unique<RungeKuttaEngine>(p, s, f, RungeKuttaOptions{c.dt_factor, true});
}
std::unique_ptr<Engine> make_hard(const EngineChoice& c, const ChainParameters& p, const ChainState& s, FloorDrive* f) {
  return std::make_unique<HardSphereEngine>(p, s, f, c.hard);
}

}  // namespace

const std::vector<EngineInfo>& engines() {
  //                                        kind                     name          hard   stepped fine  audit  resumable
  static const std::vector<EngineInfo> all{{EngineKind::Exact, "exact", false, false, true, true, true, make_exact},
                                           {EngineKind::Reference, "reference", false, true, false, false, true, make_reference},
                                           {EngineKind::ReferenceLocated, "reference-located", false, true, false, false, true,
                                            make_reference_located},
                                           {EngineKind::Hard, "hard", true, false, false, false, true, make_hard}};
  return all;
}

const EngineInfo& engine_info(EngineKind kind) {
  for (const EngineInfo& e : engines())
    if (e.kind == kind) return e;
  throw std::logic_error("engine registry: a kind without an entry");
}

const EngineInfo* find_engine(std::string_view name) {
  for (const EngineInfo& e : engines())
    if (name == e.name) return &e;
  return nullptr;
}

EngineKind stored_engine_kind(std::string_view name) {
  if (const EngineInfo* e = find_engine(name)) return e->kind;
  throw std::invalid_argument("unknown engine '" + std::string(name) + "' (known: " + engine_name_list() + ")");
}

std::string resumable_engine_list() {
  std::string names;
  for (const EngineInfo& e : engines())
    if (e.resumable) names += (names.empty() ? "" : ", ") + std::string(e.name);
  return names;
}

std::string engine_name_list() {
  std::string names;
  for (const EngineInfo& e : engines()) names += (names.empty() ? "" : ", ") + std::string(e.name);
  return names;
}

std::unique_ptr<Engine> make_engine(const EngineChoice& choice, const ChainParameters& p, const ChainState& initial,
                                    FloorDrive* floor) {
  return engine_info(choice.kind).make(choice, p, initial, floor);
}

}  // namespace granchain
