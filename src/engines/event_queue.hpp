#pragma once
// The schedule of an event-driven engine: one predicted time per slot (a cluster, a gap, the
// floor). Slots are grouped in blocks of kBlock that keep their earliest time; setting a slot
// touches its block only (a re-scan of kBlock times when the block's earliest slot moved later),
// and the earliest slot overall is found by scanning the block minima once per event. An event
// re-predicts several slots, so this costs less than a heap or tournament-tree climb per slot
// (each climb is a chain of dependent loads and stores). Ties go to the lowest slot. Time is a
// double or a FineTime (fine_time.hpp).
#include <limits>
#include <vector>

namespace granchain {

template <class Time>
class BasicEventQueue {
 public:
  explicit BasicEventQueue(int slots = 1) { reset(slots); }

  // All slots at +infinity.
  void reset(int slots) {
    blocks_ = (slots + kBlock - 1) / kBlock;
    t_.assign(static_cast<std::size_t>(blocks_) * kBlock, kNever);
    block_t_.assign(blocks_, kNever);
    block_slot_.resize(blocks_);
    for (int b = 0; b < blocks_; ++b) block_slot_[b] = b * kBlock;
    stale_ = true;
  }

  void set(int slot, const Time& t) {
    const Time old = t_[slot];
    if (old == t) return;  // same time (often +inf again): nothing changes
    t_[slot] = t;
    const int b = slot / kBlock;
    if (t < block_t_[b] || (t == block_t_[b] && slot < block_slot_[b])) {
      block_t_[b] = t;
      block_slot_[b] = slot;
    } else if (slot == block_slot_[b]) {  // the block's earliest moved later: scan the block
      const int first = b * kBlock;
      int best = first;
      Time best_t = t_[first];
      for (int s = first + 1; s < first + kBlock; ++s) {  // selects, not branches
        const bool earlier = t_[s] < best_t;
        best_t = earlier ? t_[s] : best_t;
        best = earlier ? s : best;
      }
      block_t_[b] = best_t;
      block_slot_[b] = best;
    } else {
      return;  // the block's earliest is unchanged
    }
    stale_ = true;
  }

  const Time& time(int slot) const { return t_[slot]; }

  int next_slot() const {  // the earliest (the lowest slot on a tie)
    if (stale_) find_next();
    return next_slot_;
  }
  Time next_time() const {
    if (stale_) find_next();
    return next_t_;
  }

  static constexpr Time kNever = Time(std::numeric_limits<double>::infinity());

 private:
  static constexpr int kBlock = 8;
  void find_next() const {
    int best = 0;
    Time best_t = block_t_[0];
    for (int b = 1; b < blocks_; ++b) {
      const bool earlier = block_t_[b] < best_t;
      best_t = earlier ? block_t_[b] : best_t;
      best = earlier ? b : best;
    }
    next_t_ = best_t;
    next_slot_ = block_slot_[best];
    stale_ = false;
  }
  std::vector<Time> t_;             // each slot's time (padded to whole blocks with +inf)
  std::vector<Time> block_t_;       // earliest time in each block
  std::vector<int> block_slot_;     // and its slot
  int blocks_ = 1;
  mutable bool stale_ = true;
  mutable Time next_t_ = kNever;
  mutable int next_slot_ = 0;
};

using EventQueue = BasicEventQueue<double>;

}  // namespace granchain
