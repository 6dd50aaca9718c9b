#pragma once
// Where a sweep keeps the saved states of its running points (`sweep --checkpoint-dir DIR`): one
// run checkpoint (store/run_checkpoint.hpp) per point, DIR/<16 hex digits of the FNV-1a hash of
// the point's key>.ckpt, holding the key itself. A point of an engine that can save its state
// (EngineInfo::resumable) saves it there every `every` wall seconds and when the sweep stops it
// (a signal, or the end of a --time-limit); the next invocation resumes it from there, to the
// result the point would have had uninterrupted, bit for bit, and removes the file once the point
// is stored. Every thread and MPI rank uses the same files (the folder on a shared file system).
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "store/run_checkpoint.hpp"
#include "sweep/sweep_grid.hpp"

namespace granchain {

class SweepCheckpoints {
 public:
  // dir: the folder; every: wall seconds between two saves of one point.
  SweepCheckpoints(std::string dir, double every) : dir_(std::move(dir)), every_(every) {}
  // Creates the folder where it is missing; OutputError when it cannot be.
  void create_folder() const;

  const std::string& dir() const { return dir_; }
  double every() const { return every_; }
  // Whether a point resumed says so on standard error (one line: its key, where it stands, the
  // build that saved it); on unless set off.
  bool announces_resumes() const { return announce_; }
  void announce_resumes(bool on) { announce_ = on; }

  // Whether the point's engine can save its state (the others run as without checkpoints).
  static bool covers(const SweepPoint& point);
  // The point's file, and whether it is there.
  std::string path(const SweepPoint& point) const;
  bool has_saved(const SweepPoint& point) const;

  // The point's saved state; nothing when none is there. CheckpointError for a file that is not
  // this point's checkpoint (unreadable, or another run's key).
  std::optional<RunCheckpoint> saved(const SweepPoint& point) const;
  // Writes the point's state whole (a temporary file renamed into place); OutputError if it cannot.
  void save(const SweepPoint& point, const StateArchive& state) const;
  // Removes the point's file (its run is stored: the state is spent); true if one was removed.
  bool remove(const SweepPoint& point) const;

 private:
  std::string dir_;
  double every_;
  bool announce_ = true;
};

// The checkpoints of a sweep of these points kept in *dir (`--checkpoint-dir`; null: none, then
// nullptr), each point's state saved every `every` wall seconds (`--checkpoint-every` as given;
// null: its default). InputError for an empty path, for a sweep none of whose points can save its
// state, for `every` out of its range, and for `every` without a folder. The folder is not created
// yet (create_folder).
std::unique_ptr<SweepCheckpoints> make_sweep_checkpoints(const std::string* dir, const RawValue* every,
                                                         const std::vector<SweepPoint>& points);
// The saved states of points not in todo (stored already: their sweep stopped between storing a
// point and removing its state) are spent: removed; returns how many.
std::size_t remove_spent_states(const SweepCheckpoints& checkpoints, const std::vector<SweepPoint>& points,
                                const std::vector<std::size_t>& todo);

}  // namespace granchain
