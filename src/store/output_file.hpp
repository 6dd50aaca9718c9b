#pragma once
#include <stdexcept>
// The files a command writes: checked before anything runs (creatable, not one of the command's
// inputs), then written whole or not at all, every write and the final close checked.
#include <string>
#include <vector>

namespace granchain {

// A file the command reads or writes, with the flag that named it (for messages).
struct NamedPath {
  std::string option, path;
};

// "-": the file argument means standard output.
bool is_standard_output(const std::string& path);

// Whether a and b name the same file: the same inode when both exist, else the same normalised
// path (a file about to be created by one of them).
bool same_file(const std::string& a, const std::string& b);

// Before anything runs: throws InputError "<option>: <why>" if path cannot be created, or if it is
// the same file as one of `inputs` (a results store, a config file, another output).
// "-" (standard output) is refused here: a caller that can write to standard output handles it first.
void check_output_file(const std::string& path, const std::string& option = "--json", const std::vector<NamedPath>& inputs = {});

// An output (a file, standard output, a figure) that could not be written.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Every output of a command against every input and every other output (check_output_file for
// each, in order), before anything is written. Empty paths are skipped.
void check_outputs(const std::vector<NamedPath>& outputs, const std::vector<NamedPath>& inputs);

// A file written whole or not at all. The constructor writes the text to a temporary file beside
// the target (every write, the flush to disk and the close checked) and throws on failure;
// commit() renames it into place. A target that exists and is not a regular file (a device, a
// FIFO, /dev/stdout) cannot be replaced: it is written directly by commit(). The destructor
// removes a temporary file that was not committed. Errors: OutputError
// "<option>: cannot write '<path>': <reason>".
class PendingFile {
 public:
  PendingFile(std::string path, std::string text, std::string option);
  PendingFile(const PendingFile&) = delete;
  PendingFile& operator=(const PendingFile&) = delete;
  ~PendingFile();
  void commit();

 private:
  std::string path_, text_, option_, tmp_;  // tmp_ empty: written directly at commit
  bool committed_ = false;
};

// PendingFile(path, text, option).commit().
void write_file_atomically(const std::string& path, const std::string& text, const std::string& option = "--json");

// Writes text to standard output and flushes it; throws OutputError
// "cannot write standard output: <reason>".
void write_standard_output(const std::string& text);

}  // namespace granchain
