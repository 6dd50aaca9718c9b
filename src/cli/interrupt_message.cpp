#include "cli/interrupt_message.hpp"

#include <fmt/format.h>
#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <array>
#include <cstdlib>
#include <cstring>

namespace granchain {

namespace {

// The messages, formatted before any signal can arrive: the handler only writes and re-raises
// (both async-signal-safe).
std::array<char, 1024> sigint_message{}, sigterm_message{};
std::size_t sigint_length = 0, sigterm_length = 0;
std::array<std::array<char, 4096>, 4> unfinished{};

void on_signal(int sig) {
  const char* msg = sig == SIGINT ? sigint_message.data() : sigterm_message.data();
  const std::size_t len = sig == SIGINT ? sigint_length : sigterm_length;
  for (const auto& file : unfinished)
    if (file[0] != '\0') ::unlink(file.data());
  [[maybe_unused]] const ssize_t n = ::write(STDERR_FILENO, msg, len);
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

volatile sig_atomic_t recorded = 0;
std::atomic<CancelFlag*> also_cancel{nullptr};
static_assert(CancelFlag::is_always_lock_free && std::atomic<CancelFlag*>::is_always_lock_free);
void record_signal(int sig) {
  recorded = sig;
  if (CancelFlag* flag = also_cancel.load()) flag->store(true);  // lock-free: safe in a handler
}

// SIGINT and SIGTERM to `handler`, with sigaction flags (SA_RESETHAND: once).
void install(void (*handler)(int), int flags) {
  struct sigaction sa {};
  sa.sa_handler = handler;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = flags;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

template <std::size_t Size>
std::size_t store(std::array<char, Size>& buffer, const std::string& text) {
  const std::size_t len = std::min(text.size(), buffer.size() - 1);
  std::memcpy(buffer.data(), text.data(), len);
  buffer[len] = '\0';
  return len;
}

}  // namespace

void announce_on_interrupt(const std::string& what_was_kept, const std::string& unfinished_file) {
  announce_on_interrupt(what_was_kept, std::vector<std::string>{unfinished_file});
}

void announce_on_interrupt(const std::string& what_was_kept, const std::vector<std::string>& unfinished_files) {
  // A handler installed before may run while the texts change: the signals wait until they are whole.
  sigset_t block, previous;
  sigemptyset(&block);
  sigaddset(&block, SIGINT);
  sigaddset(&block, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &block, &previous);
  for (std::size_t i = 0; i < unfinished.size(); ++i) {
    const std::string f = i < unfinished_files.size() ? unfinished_files[i] : std::string();
    store(unfinished[i], f.size() < unfinished[i].size() ? f : std::string());
  }
  sigint_length = store(sigint_message, fmt::format("\ngranchain: interrupted by SIGINT; {}\n", what_was_kept));
  sigterm_length = store(sigterm_message, fmt::format("\ngranchain: interrupted by SIGTERM; {}\n", what_was_kept));
  install(on_signal, SA_RESETHAND);
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
}

void record_interrupts(CancelFlag* also_set) {
  also_cancel.store(also_set);
  install(record_signal, SA_RESETHAND);  // a second signal takes the default action: ends at once
}

int recorded_interrupt() { return recorded; }

void reraise_interrupt(int sig) {
  ::signal(sig, SIG_DFL);
  ::raise(sig);
  std::_Exit(128 + sig);  // not reached: the default action ends the process
}

const char* interrupt_name(int sig) { return sig == SIGINT ? "SIGINT" : "SIGTERM"; }

}  // namespace granchain
