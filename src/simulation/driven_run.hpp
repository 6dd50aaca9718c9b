#pragma once
// One run of the driven column (paper Sec. III.A): set-up, a discarded transient, then the
// measuring window of length T in which observers count collisions and sample profiles.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "analysis/blocking.hpp"
#include "engines/engine_registry.hpp"
#include "model/chain_parameters.hpp"
#include "model/chain_state.hpp"
#include "model/floor.hpp"
#include "model/plate_motion.hpp"
#include "model/state_archive_fwd.hpp"
#include "observables/contact_durations.hpp"
#include "observables/profile_sampler.hpp"

namespace granchain {

struct RunSpec {
  ChainParameters params;
  DriveSpec drive;                // thermal floor (the paper's) or a vibrating plate
  EngineChoice engine;
  double T = 1e4;                 // measuring time
  double transient = 1e3;         // discarded time before the window
  std::uint64_t seed = 1;
  double sample_interval = 0.01;  // requested spacing of profile samples
  int bins = 1024;                // fine time bins for blocking (a power of two)
};

struct RunResult {
  RunSpec spec;
  ContactLaw law;                 // D and tau_c of this run
  double time_step = 0.0;         // engine's step (0 for event-driven engines)
  double sample_interval = 0.0;   // spacing actually used (a multiple of the step)
  std::int64_t samples = 0;

  Estimate n_coll;                // collisions per particle per unit time
  Estimate floor_rate;            // floor hits per unit time
  Estimate pp_rate;               // particle-particle collisions per unit time
  std::uint64_t particle_collisions = 0;  // in the window
  std::uint64_t floor_hits = 0;           // in the window
  std::vector<ParticleProfile> profiles;
  // How long neighbours stay in contact (observables/contact_durations.hpp): the plate's contact
  // (index 0) and pairs (i, i+1) (index i); empty for hard spheres and for runs stored before it.
  std::vector<PairContacts> contacts;
  // Is the window stationary? n_coll and the column's mean height compared between the window's
  // two halves (analysis/blocking.hpp, halves_check); a run that fails is still a result, but its
  // error bars are not to be trusted (the summary warns, the JSON and the store keep the verdict).
  StationarityCheck n_coll_halves, height_halves;
  bool stationary() const { return n_coll_halves.stationary && height_halves.stationary; }
  // The blocking curves behind n_coll's error and of the column's mean height: the standard error
  // with 2^l bins to a block at every level l (analysis/blocking.hpp). Where it still rises at the
  // last levels the column has states that outlast a block, and independent replicas are the test
  // of the error; empty for runs stored before the curves were kept.
  std::vector<BlockingLevel> n_coll_blocking, height_blocking;

  std::uint64_t steps = 0;        // engine steps, transient included
  std::uint64_t events = 0;       // contact ends + floor hits, transient included
  double wall_seconds = 0.0;
  // CPU time of the thread that ran it: unlike wall_seconds, not stretched when more runs share the
  // machine than it has cores (NaN for a result read from a run stored without it).
  double cpu_seconds = 0.0;
  // Exact engine with its audit on (EngineChoice::audit): instants and values checked between
  // events, transient included. A value of the wrong sign is an error (run_driven_column throws).
  std::uint64_t audit_instants = 0, audit_values = 0;
};

struct RunProgress {
  double t = 0.0;          // simulated time reached
  double t_total = 0.0;    // transient + T
  bool in_transient = true;
  std::uint64_t steps = 0;
  std::uint64_t events = 0;
  double wall_seconds = 0.0;
};
using ProgressCallback = std::function<void(const RunProgress&)>;

// Saving a run as it goes and resuming it (a checkpoint), for the engines whose registry entry is
// resumable (EngineInfo::resumable): the engine, the floor's random generator, the observers and
// the run's place are saved between two samples (in the transient, between two of its chunks of
// one time unit), and a run resumed from its saved state gives bit for bit the result the
// uninterrupted run gives. The wall and CPU seconds of a resumed run add those before the save.
struct RunResumption {
  // A state saved by `save` for this very spec (the caller checks that it is: config/run_key.hpp);
  // null: start from t = 0. A state that does not fit the spec throws StateArchiveError.
  const StateArchive* resume_from = nullptr;
  // Receives the run's state about every `every` wall seconds, and once more when the run is
  // cancelled (RunCancelled from the progress callback) before the cancel goes on; empty: never.
  std::function<void(const StateArchive&)> save;
  double every = 600.0;
};

// Where a saved state stands: the simulated time it reached and whether that is in the window.
struct SavedRunPlace {
  double t = 0.0;
  bool in_window = false;
};
SavedRunPlace saved_run_place(const StateArchive& state);
// Whether a run of this spec can be saved and resumed: its engine is resumable (EngineInfo), and
// with a soft start the soft engine too (a state saved in the transient is the soft engine's, one
// saved in the window the hard spheres', with the soft engine's counts).
bool can_resume(const RunSpec& spec);

// The hard spheres' start from a soft column's state: centres raised from the bottom up until no
// pair overlaps and particle 1 does not overlap the floor or the plate, velocities kept. The
// springs' energy is dropped with the overlaps: at large k, the column's weight compresses a
// contact by N m g / k, and a collision in progress is finished by the hard engine's rule (its
// approach speed times e).
ChainState hard_sphere_start(ChainState soft, const ChainParameters& p, const FloorDrive& floor);

// Runs the driven column; throws UnphysicalStateError if the dynamics becomes unphysical.
// progress (if set) is called about every progress_every wall-clock seconds.
RunResult run_driven_column(const RunSpec& spec, const ProgressCallback& progress = {},
                            double progress_every = 0.5, const RunResumption& resumption = {});

}  // namespace granchain
