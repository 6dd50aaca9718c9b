#include "provenance.hpp"

#include <unistd.h>

#include <mutex>

#include "version.hpp"

namespace granchain {

namespace {

struct Invocation {
  std::mutex lock;
  std::string command_line;
  int threads = 1, ranks = 1;
};
Invocation& invocation() {
  static Invocation inv;
  return inv;
}

// An argument as a shell would need it: bare when it holds only safe characters, else in quotes.
std::string shell_word(const std::string& a) {
  if (!a.empty() && a.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_.,:/=+@%") == std::string::npos)
    return a;
  std::string q = "'";
  for (char c : a) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

}  // namespace

void set_invocation(int argc, const char* const* argv) {
  std::string line;
  for (int i = 0; i < argc; ++i) line += (i ? " " : "") + shell_word(argv[i]);
  set_invocation_text(line);
}

void set_invocation_text(const std::string& command_line) {
  std::lock_guard<std::mutex> g(invocation().lock);
  invocation().command_line = command_line;
}

void set_parallelism(int threads, int ranks) {
  std::lock_guard<std::mutex> g(invocation().lock);
  invocation().threads = threads;
  invocation().ranks = ranks;
}

nlohmann::json provenance_json() {
  char host[256] = {};
  if (::gethostname(host, sizeof host - 1) != 0) host[0] = '\0';
  Invocation& inv = invocation();
  std::lock_guard<std::mutex> g(inv.lock);
  const std::string build = build_settings();
  return {{"command_line", inv.command_line},
          {"host", host},
          {"threads", inv.threads},
          {"ranks", inv.ranks},
          {"build", build},
#ifdef GRANCHAIN_WITH_MPI
          {"mpi", true},
#else
          {"mpi", false},
#endif
          {"code_version", code_version()},
          {"units", "lengths in d, masses in m, times in sqrt(d/g), energies in m g d (m = d = g = 1 unless given); "
                    "k_B T0 as given, in those energy units"}};
}

}  // namespace granchain
