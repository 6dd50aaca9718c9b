#include "sweep/sweep_checkpoints.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "store/output_file.hpp"
#include "version.hpp"

namespace granchain {

void SweepCheckpoints::create_folder() const {
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec || !std::filesystem::is_directory(dir_))
    throw OutputError(fmt::format("--checkpoint-dir: cannot create the folder '{}': {}", dir_, ec ? ec.message() : "not a folder"));
}

bool SweepCheckpoints::covers(const SweepPoint& point) {
  return can_resume(point.spec);
}

std::string SweepCheckpoints::path(const SweepPoint& point) const {
  return (std::filesystem::path(dir_) / fmt::format("{:016x}.ckpt", fnv1a(point.key))).string();
}

bool SweepCheckpoints::has_saved(const SweepPoint& point) const {
  std::error_code ec;
  return covers(point) && std::filesystem::exists(path(point), ec);
}

std::optional<RunCheckpoint> SweepCheckpoints::saved(const SweepPoint& point) const {
  std::optional<RunCheckpoint> c = read_run_checkpoint(path(point));
  if (c && c->key != point.key)
    throw CheckpointError(fmt::format("'{}' holds the state of another run ({})", path(point), c->key));
  return c;
}

void SweepCheckpoints::save(const SweepPoint& point, const StateArchive& state) const {
  write_run_checkpoint(path(point), {point.key, code_version(), state}, "--checkpoint-dir");
}

bool SweepCheckpoints::remove(const SweepPoint& point) const {
  std::error_code ec;
  return std::filesystem::remove(path(point), ec);
}

}  // namespace granchain
