#pragma once
// Stopping a simulation from outside while it runs (a Python KeyboardInterrupt, a notebook's stop
// button): the caller sets a CancelFlag from any thread; the simulation reads it at every event it
// observes (and every sample it takes) and ends early, keeping only what was complete. A relaxed
// load per event: nothing is synchronised through the flag but the request itself.
#include <atomic>
#include <exception>

namespace granchain {

using CancelFlag = std::atomic<bool>;

inline bool cancel_requested(const CancelFlag* flag) { return flag != nullptr && flag->load(std::memory_order_relaxed); }

// Thrown inside a simulation whose CancelFlag was set; the function that owns the work catches it
// and returns what finished (or lets it through where nothing can be kept).
struct RunCancelled : std::exception {
  const char* what() const noexcept override { return "cancelled"; }
};

}  // namespace granchain
