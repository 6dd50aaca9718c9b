#pragma once
// Counting the collisions of one inelastic collapse, averaged over random launches (paper
// Sec. III.D, Fig. ntot): no drive and no gravity; the spheres are launched inward in free space
// (or thrown against a wall, Sec. II.C), and the collisions are counted until a stop rule holds.
//
// Stop rules, checked whenever no contact is open (they concern free flight only):
//   ends   (the paper's): v_N - v_1 > 0, the end particles separate. Inner pairs may still be
//          approaching, so collisions may follow that are not counted.
//   strict: v_{i+1} >= v_i for every neighbouring pair (and, with a wall, v_1 >= 0): no pair
//          approaches, so in free flight no collision can ever happen again; n_tot is then the
//          total number of collisions of the launch. A launch also ends when no event happens
//          until t_max (1e7) with no contact open: a pair approaching that slowly (by round-off,
//          after a wall or a collapse) is not waited for.
// Under either rule a soft-sphere launch also ends, with no contact open, when every relative
// velocity is below 1e-13 of the speeds (the exact engine's resolution): the chain moves as one
// body. (Hard spheres that become one body collapse, and the collapse watch reports it.)
// A hard-sphere realisation that collapses (infinitely many collisions) is counted as collapsed
// and left out of the n_tot average; the fraction is reported.
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "engines/engine_registry.hpp"
#include "model/chain_parameters.hpp"
#include "model/collapse_setups.hpp"
#include "simulation/cancellation.hpp"

namespace granchain {

enum class CollapseSetup { FreeSpace, Wall };
enum class StopRule { Ends, Strict };

const char* setup_name(CollapseSetup s);  // "free_space", "wall"
const char* rule_name(StopRule r);        // "ends", "strict"

struct CollapseSpec {
  ChainParameters params;  // g is ignored (0); k = +inf with the hard-sphere engine
  EngineChoice engine;
  CollapseSetup setup = CollapseSetup::FreeSpace;
  LaunchParameters launch;
  StopRule rule = StopRule::Ends;
  int realizations = 1000;
  std::uint64_t seed = 1;  // realisation r launches from derive_seed(seed, r): the same launches at every k
  double t_max = 1e7;      // a realisation not stopped by then is an error (it cannot happen in free space)
  int threads = 1;         // realisations run in parallel; the results do not depend on it
};

// One collision as recorded for the event-sequence file: pair (i, i+1), 1-based, i = 0 for the wall.
struct CollisionRecord {
  int realization;  // 0-based
  std::uint64_t index;  // 1-based within the realisation
  double t_begin, t_end;  // contact begins and ends (equal for hard spheres and the wall)
  int i;
  double speed_in, speed_out;  // |relative velocity| at the start and the end of the contact
};

struct RealizationOutcome {
  std::uint64_t particle_collisions = 0;  // counted contact ends until the stop
  std::uint64_t wall_hits = 0;
  bool collapsed = false;  // hard spheres: inelastic collapse detected
  double t_stop = 0;       // time at which the stop rule held (or the collapse was detected)
  // Exact engine, contacts below its resolution (EngineCounters): grazing contacts, and those of
  // them held longer because their pair kept grazing.
  std::uint64_t grazing_contacts = 0, held_contacts = 0;
  // Ended because every relative velocity fell below the engine's resolution (1e-13 of the speeds)
  // before the stop rule held: the chain moves as one body (seen at k >= 1e14, docs/collapse.md).
  bool one_body = false;
  double seconds = 0;  // wall time the launch took on its thread
  std::uint64_t n_tot() const { return particle_collisions + wall_hits; }
};

struct CollapseResult {
  CollapseSpec spec;
  ContactLaw law;
  std::vector<RealizationOutcome> outcomes;  // in realisation order
  int collapsed = 0;
  // Over the realisations that did not collapse: mean of n_tot and its standard error
  // (sample standard deviation / sqrt(count)); NaN when none finished.
  double n_tot_mean = 0, n_tot_error = 0;
  std::uint64_t n_tot_min = 0, n_tot_max = 0;
  double wall_seconds = 0;
  // Over all realisations: collisions counted, and the contacts among them below the exact
  // engine's resolution (see RealizationOutcome).
  std::uint64_t collisions = 0, grazing_contacts = 0, held_contacts = 0;
  int one_body = 0;  // launches that ended as one body (RealizationOutcome::one_body)
  // Cancelled (run_collapse's cancel flag): only launches 0 .. n-1 finished; spec.realizations is n
  // and everything above is over them, the same numbers as a count of n launches.
  bool interrupted = false;
};

// Called with each realisation's collisions in order, realisations in order, from the calling
// thread (so a file written from it is the same for any thread count).
using CollisionLog = std::function<void(const std::vector<CollisionRecord>&)>;

// Throws UnphysicalStateError (other than a hard-sphere collapse) if a realisation turns unphysical.
// Progress: called on the calling thread after each launch is handed over (in launch order), with
// the launches done so far and the particle collisions of the one just done.
using LaunchProgress = std::function<void(int done, std::uint64_t collisions)>;
// The chain at an instant when no contact is open, right after the contact end (or wall hit) of
// record `after` (0-based, in the realisation's records): what a collision sequence leaves.
struct ClosedState {
  std::size_t after = 0;
  ChainState state;
};
// With a ClosedStateLog (and a CollisionLog), each realisation's closed states are handed over
// after its records, in the same order; keeping them costs one state per collision.
using ClosedStateLog = std::function<void(const std::vector<ClosedState>&)>;
// A count carried over sittings, launch by launch (store/launch_checkpoint.hpp keeps it in a
// results store). Launch r depends on (spec, r) alone, so a count assembled from launches of
// several sittings is the count of one sitting, bit for bit.
struct LaunchCheckpoint {
  std::map<int, RealizationOutcome> done;  // launches counted in earlier sittings: not run again
  double earlier_seconds = 0;              // the wall time those sittings spent on them
  // Each launch counted now, on the calling thread, in the order they finish (not launch order).
  std::function<void(int r, const RealizationOutcome&)> finished;
  // Called once before run_collapse returns (or throws): whatever `finished` has not yet made
  // durable must be, so that a caller may batch its writes.
  std::function<void()> flush;
};
// cancel (simulation/cancellation.hpp): when set, the launches under way are abandoned and the
// result holds those finished before the first unfinished one (CollapseResult::interrupted).
// checkpoint: its done launches are taken as counted (no records or progress for them: a
// CollisionLog with done launches is refused, std::invalid_argument) and every new one is handed to
// its `finished`; wall_seconds then includes earlier_seconds.
CollapseResult run_collapse(const CollapseSpec& spec, const CollisionLog& log = {}, const LaunchProgress& progress = {},
                            const ClosedStateLog& states = {}, const CancelFlag* cancel = nullptr,
                            const LaunchCheckpoint* checkpoint = nullptr);

// How n_tot changes between two counts of the same launches at k1 < k2 (same spec otherwise).
struct KSlope {
  double e = 0, k1 = 0, k2 = 0;
  // Mean and standard error of the per-launch increase of n_tot per decade of k; launches that
  // collapsed at either k are left out (NaN when none is left).
  double per_log10_k = 0, error = 0;
  int launches = 0;
  // alpha = d ln n_tot / d ln k from the two means (for n_tot ~ k^alpha); its error combines the
  // two standard errors as if independent, an upper bound since the launches are shared.
  double alpha = 0, alpha_error = 0;
};
KSlope k_slope(const CollapseResult& a, const CollapseResult& b);

// Every relative velocity below the exact engine's resolution (1e-13 of the speeds, the test that
// makes a contact grazing): the chain moves as one body, no pair approaches at a speed the doubles
// resolve, and waiting for the stop rule would wait on round-off. On a wall only when moving away
// from it (v_1 >= 0).
bool moves_as_one_body(const CollapseSpec& spec, const ChainState& s);

// The initial state of realisation r.
ChainState collapse_initial_state(const CollapseSpec& spec, int r);

}  // namespace granchain
