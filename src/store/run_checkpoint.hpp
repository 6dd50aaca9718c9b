#pragma once
// A run's checkpoint file: what `granchain run --checkpoint FILE` keeps so that a run longer than
// a batch job or a sitting goes on where it stopped (simulation/driven_run.hpp, RunResumption).
// It holds the run's key (config/run_key.hpp: every parameter and the seed), the code version that
// wrote it and the run's saved state, as one CBOR document, written whole (a temporary file renamed
// into place): a kill while it is written leaves the checkpoint before it intact.
#include <optional>
#include <stdexcept>
#include <string>

#include "model/state_archive.hpp"

namespace granchain {

struct RunCheckpoint {
  std::string key;         // the run's point key
  std::string written_by;  // code_version() of the build that wrote it
  StateArchive state;      // RunResumption's saved state
};

// A file that is not a checkpoint of this format (another file, a truncated one, another version).
class CheckpointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Writes the checkpoint whole or not at all; OutputError "<option>: cannot write ..." on failure.
void write_run_checkpoint(const std::string& path, const RunCheckpoint& checkpoint, const std::string& option = "--checkpoint");
// The checkpoint at path; nothing when no file is there. CheckpointError when one is there but
// does not read as a checkpoint.
std::optional<RunCheckpoint> read_run_checkpoint(const std::string& path);
// The checkpoint of the run with this key at path; nothing when no file is there. CheckpointError
// also when the file holds another run's state (no state goes on under another run's name).
std::optional<RunCheckpoint> read_run_checkpoint_of(const std::string& path, const std::string& key);
// Removes path if it holds the checkpoint of the run with this key (spent: the run is stored or
// its result returned); true if it did. Anything else at path is left as it is.
bool remove_spent_run_checkpoint(const std::string& path, const std::string& key);

}  // namespace granchain
