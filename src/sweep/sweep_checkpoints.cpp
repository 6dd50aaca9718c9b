#include "sweep/sweep_checkpoints.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

#include "config/input_error.hpp"
#include "engines/engine_registry.hpp"
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

std::unique_ptr<SweepCheckpoints> make_sweep_checkpoints(const std::string* given_dir, const RawValue* every,
                                                         const std::vector<SweepPoint>& points) {
  if (given_dir == nullptr) {
    if (every)
      throw InputError(fmt::format("--checkpoint-every = {}{}: it acts only with --checkpoint-dir DIR", every->text(), from_where(*every)));
    return nullptr;
  }
  const std::string& dir = *given_dir;
  if (dir.empty()) throw InputError("--checkpoint-dir: the path is empty; give a folder name");
  if (std::none_of(points.begin(), points.end(), [](const SweepPoint& p) { return SweepCheckpoints::covers(p); }))
    throw InputError(fmt::format("--checkpoint-dir = {}: no point of this sweep can save its state; valid: points of --engine {}", dir,
                                 resumable_engine_list()));
  const double seconds = every ? read_real(*find_parameter(run_parameters(), "checkpoint-every"), *every) : RunOptions{}.checkpoint_every;
  return std::make_unique<SweepCheckpoints>(dir, seconds);
}

std::size_t remove_spent_states(const SweepCheckpoints& checkpoints, const std::vector<SweepPoint>& points,
                                const std::vector<std::size_t>& todo) {
  std::vector<bool> to_run(points.size(), false);
  for (std::size_t i : todo) to_run[i] = true;
  std::size_t spent = 0;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!to_run[i] && checkpoints.has_saved(points[i])) spent += checkpoints.remove(points[i]) ? 1 : 0;
  return spent;
}

}  // namespace granchain
