#pragma once
// Sweeps over MPI ranks (`mpirun -np P granchain sweep ...`). Rank 0 owns the results store and
// the queue: its main thread hands out points one at a time to whichever rank asks (dynamic load
// balancing) and writes every result, its own threads run points too; every other rank runs one
// point at a time and sends the result back as JSON (exact: doubles round-trip). Every rank
// builds the same point list from the same arguments, so only indices travel.
// Built only when CMake finds MPI (GRANCHAIN_WITH_MPI); without it, mpi_world_size() is 1.
#include <string>

#include "sweep/sweep_runner.hpp"

namespace granchain {

// True when this process was started by an MPI launcher with more than one rank, whether or
// not this build has MPI (then the sweep refuses to run rather than run every point P times).
bool launched_by_mpi_launcher();
bool built_with_mpi();

// Initialises MPI on construction when launched by an MPI launcher and built with MPI,
// finalises on destruction; otherwise a one-rank world.
class MpiWorld {
 public:
  MpiWorld();
  ~MpiWorld();
  MpiWorld(const MpiWorld&) = delete;
  MpiWorld& operator=(const MpiWorld&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }
  // Rank 0's value of x, on every rank.
  int broadcast(int x) const;

 private:
  int rank_ = 0;
  int size_ = 1;
  bool initialised_ = false;
};

// Rank 0: runs `runner` with `threads` local threads while its main thread serves the other
// ranks. Other ranks: run the points rank 0 sends until it says stop, keeping their states in
// `checkpoints` (if any; the same folder as rank 0's) and stopping them by `rank_stops` (the
// rank's own cancel flag and checkpoint deadline); a point stopped with its state saved is
// reported to rank 0 as such. points must be the same list on every rank.
void run_sweep_over_ranks(const MpiWorld& world, const std::vector<SweepPoint>& points, SweepRunner* runner,
                          int threads, const SweepProgressCallback& progress, double progress_every,
                          const SweepCheckpoints* checkpoints = nullptr, const PointStops& rank_stops = {});

}  // namespace granchain
