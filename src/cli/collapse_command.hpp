#pragma once
#include <CLI/CLI.hpp>
#include <memory>

namespace granchain {

// `granchain collapse`: the number of collisions n_tot of one inelastic collapse (paper Sec. III.D,
// Fig. ntot), averaged over random launches, for lists of e and k and any engine; free space or
// Bernu and Mazighi's wall (Sec. II.C).
class CollapseCommand {
 public:
  explicit CollapseCommand(CLI::App& app);
  bool selected() const { return sub_->parsed(); }
  int execute();

 private:
  CLI::App* sub_;
  struct Impl;
  std::shared_ptr<Impl> impl_;
};

}  // namespace granchain
