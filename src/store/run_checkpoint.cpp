#include "store/run_checkpoint.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "store/output_file.hpp"

namespace granchain {

namespace {
constexpr const char* kFormat = "granchain run checkpoint";
constexpr int kVersion = 1;
}  // namespace

void write_run_checkpoint(const std::string& path, const RunCheckpoint& c, const std::string& option) {
  const StateArchive doc = {{"format", kFormat}, {"version", kVersion}, {"key", c.key}, {"written_by", c.written_by}, {"state", c.state}};
  const std::vector<std::uint8_t> bytes = StateArchive::to_cbor(doc);
  write_file_atomically(path, std::string(bytes.begin(), bytes.end()), option);
}

std::optional<RunCheckpoint> read_run_checkpoint(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CheckpointError(fmt::format("'{}' cannot be read", path));
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  StateArchive doc;
  try {
    doc = StateArchive::from_cbor(bytes);
  } catch (const StateArchive::exception&) {
    throw CheckpointError(fmt::format("'{}' is not a granchain run checkpoint (it does not read as CBOR)", path));
  }
  if (!doc.is_object() || doc.value("format", "") != kFormat) {
    throw CheckpointError(fmt::format("'{}' is not a granchain run checkpoint", path));
  }
  if (doc.value("version", 0) != kVersion) {
    throw CheckpointError(fmt::format("'{}' is a run checkpoint of format version {}; this build reads version {}", path,
                                      doc.value("version", 0), kVersion));
  }
  if (!doc.contains("key") || !doc["key"].is_string() || !doc.contains("state") || !doc["state"].is_object()) {
    throw CheckpointError(fmt::format("'{}' is a run checkpoint without its key or state", path));
  }
  return RunCheckpoint{doc["key"].get<std::string>(), doc.value("written_by", ""), std::move(doc["state"])};
}

std::optional<RunCheckpoint> read_run_checkpoint_of(const std::string& path, const std::string& key) {
  std::optional<RunCheckpoint> checkpoint = read_run_checkpoint(path);
  if (checkpoint && checkpoint->key != key) {
    throw CheckpointError(fmt::format("'{}' holds the state of another run ({}); give another file, or delete it to start this run anew",
                                      path, checkpoint->key));
  }
  return checkpoint;
}

bool remove_spent_run_checkpoint(const std::string& path, const std::string& key) {
  try {
    const std::optional<RunCheckpoint> left = read_run_checkpoint(path);
    return left && left->key == key && std::filesystem::remove(path);
  } catch (const std::exception&) {  // not a checkpoint (of this run), or not removable: left as it is
    return false;
  }
}

}  // namespace granchain
