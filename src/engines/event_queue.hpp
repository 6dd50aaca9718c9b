#pragma once
// The schedule of an event-driven engine: one predicted time per slot (a cluster, a gap, the
// floor), kept in a tournament tree so that the earliest slot is read in O(1) and a slot is
// re-predicted in O(log n) — usually less, because the climb stops where nothing changes.
#include <limits>
#include <vector>

namespace granchain {

class EventQueue {
 public:
  explicit EventQueue(int slots = 1) { reset(slots); }

  // All slots at +infinity.
  void reset(int slots) {
    leaves_ = 1;
    while (leaves_ < slots) leaves_ *= 2;
    tree_.assign(2 * leaves_, Node{kNever, 0});
    for (int s = 0; s < leaves_; ++s) tree_[leaves_ + s].slot = s;
    for (int node = leaves_ - 1; node >= 1; --node) tree_[node] = tree_[2 * node];
  }

  void set(int slot, double t) {
    int node = leaves_ + slot;
    if (tree_[node].t == t) return;  // same time (often +inf again): the tree stays as it is
    tree_[node].t = t;
    // Each node holds the earliest of its two children (the left one on a tie). Above a node
    // whose winner and time did not change, nothing changes.
    for (node >>= 1; node >= 1; node >>= 1) {
      const Node& a = tree_[2 * node];
      const Node& b = tree_[2 * node + 1];
      const Node& w = b.t < a.t ? b : a;
      if (tree_[node].slot == w.slot && tree_[node].t == w.t) break;
      tree_[node] = w;
    }
  }

  int next_slot() const { return tree_[1].slot; }  // the earliest (the lowest slot on a tie)
  double next_time() const { return tree_[1].t; }

  static constexpr double kNever = std::numeric_limits<double>::infinity();

 private:
  struct Node {
    double t;  // the earliest slot time below this node (a leaf: its slot's time)
    int slot;  // and its slot
  };
  std::vector<Node> tree_;
  int leaves_ = 1;
};

}  // namespace granchain
