#pragma once
// What an engine is, written once: its name (on the command line, in stores and point keys),
// whether it treats the spheres as hard, whether it steps in time (dt = tau_c / dt_factor, then part
// of a run's identity), whether its clock is a FineTime, whether it has an audit, whether a run of it
// can be saved and resumed, and how to make one. Every engine runs every drive (model/plate_motion.hpp). The layers ask this registry (by EngineKind) instead of comparing names; names appear only
// where text is read or written.
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "engines/engine.hpp"
#include "engines/hard_sphere_options.hpp"
#include "model/chain_parameters.hpp"
#include "model/floor.hpp"

namespace granchain {

// Declared in the order of their names (exact, hard, reference, reference-located), so that
// whatever is ordered by kind (the analysis's families) lists them as their names sort.
enum class EngineKind { Exact, Hard, Reference, ReferenceLocated };

struct EngineChoice {
  EngineKind kind = EngineKind::Exact;  // the registry's first engine is the default
  double dt_factor = 100.0;             // time-stepped engines: dt = tau_c / dt_factor
  HardSphereOptions hard;               // the hard-sphere engine (k = infinity): TC model, collapse watch
  // The hard-sphere engine started from a soft column (driven runs): the exact engine at this k
  // runs the transient, and the hard spheres take over its state. 0: the hard engine runs from the
  // initial state.
  double start_k = 0.0;
  bool audit = false;                   // engines with an audit: check every overlap and gap between events (slow)
};

struct EngineInfo {
  EngineKind kind;
  const char* name;          // as typed on the command line and stored
  bool hard_spheres;         // k = infinity, instantaneous collisions (TC model and collapse watch)
  bool time_stepped;         // fixed steps dt = tau_c / dt_factor: dt_factor is part of a run's identity
  bool fine_clock;           // FineTime clock, resolving 2^-53 ulp(t) at time t; otherwise ulp(t)
  bool has_audit;            // --audit checks it
  bool resumable;            // Engine::save / restore: a run of it can be checkpointed and resumed
  std::unique_ptr<Engine> (*make)(const EngineChoice&, const ChainParameters&, const ChainState&, FloorDrive*);
};

// Every engine, the default first.
const std::vector<EngineInfo>& engines();
const EngineInfo& engine_info(EngineKind kind);
inline const char* engine_name(EngineKind kind) { return engine_info(kind).name; }
// The engine of that name, or nullptr.
const EngineInfo* find_engine(std::string_view name);
// The engine of a name read back from a store or a JSON file; throws std::invalid_argument.
EngineKind stored_engine_kind(std::string_view name);
// "exact, reference, reference-located, hard": for help texts and error messages.
std::string engine_name_list();
// The same for the resumable engines only.
std::string resumable_engine_list();

std::unique_ptr<Engine> make_engine(const EngineChoice& choice, const ChainParameters& p, const ChainState& initial,
                                    FloorDrive* floor);

}  // namespace granchain
