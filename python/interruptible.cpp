// run_interruptible (bindings.hpp): long work on a thread of its own, the calling thread watching
// for Ctrl-C. CPython runs signal handlers on the main thread only, between bytecodes, so the
// thread that holds the call must wake now and then (PyErr_CheckSignals) while the work runs.
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

#include "bindings.hpp"

namespace granchain::python {

std::optional<py::error_already_set> run_interruptible(std::atomic<bool>& cancel, const std::function<void()>& work,
                                                       const std::function<void()>& progress, double progress_every) {
  std::mutex mu;
  std::condition_variable cv;
  bool done = false;
  std::exception_ptr failure;
  std::thread worker([&] {
    try {
      work();
    } catch (...) {
      failure = std::current_exception();
    }
    std::lock_guard lock(mu);
    done = true;
    cv.notify_all();
  });
  std::optional<py::error_already_set> stop;
  auto last_progress = std::chrono::steady_clock::now();
  for (bool finished = false; !finished;) {
    {
      py::gil_scoped_release nogil;
      std::unique_lock lock(mu);
      finished = cv.wait_for(lock, std::chrono::milliseconds(100), [&] { return done; });
    }
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      const auto now = std::chrono::steady_clock::now();
      if (progress && !finished && std::chrono::duration<double>(now - last_progress).count() >= progress_every) {
        last_progress = now;
        progress();
      }
    } catch (py::error_already_set& e) {
      stop.emplace(std::move(e));
      cancel = true;
      break;
    }
  }
  {
    py::gil_scoped_release nogil;
    worker.join();
  }
  if (failure) std::rethrow_exception(failure);
  return stop;
}

}  // namespace granchain::python
