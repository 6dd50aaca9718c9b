#include "reproduce/plot_script.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <cstring>

#ifndef GRANCHAIN_PLOTS_DIR
#define GRANCHAIN_PLOTS_DIR "plots"
#endif

namespace granchain {

namespace {

// The last non-empty line of a script's error output (Python's traceback ends with the error).
std::string last_line(const std::string& text) {
  std::size_t end = text.find_last_not_of(" \n\r\t");
  if (end == std::string::npos) return "";
  const std::size_t begin = text.rfind('\n', end);
  return text.substr(begin == std::string::npos ? 0 : begin + 1, end - (begin == std::string::npos ? 0 : begin + 1) + 1);
}

}  // namespace

// The folder of the plot scripts: <prefix>/share/granchain/plots beside an installed binary
// (<prefix>/bin/granchain), else the source tree's plots/ that the build binary was made from.
std::string plots_dir() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const std::filesystem::path installed = exe.parent_path().parent_path() / "share" / "granchain" / "plots";
    if (std::filesystem::is_directory(installed, ec)) return installed.string();
  }
  return GRANCHAIN_PLOTS_DIR;
}

std::string run_plot_script(const std::string& script, const std::vector<std::string>& args) {
  const std::string path = plots_dir() + "/" + script;
  std::vector<std::string> argv_s = {"/usr/bin/python3", path};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);

  int err_pipe[2];
  if (::pipe2(err_pipe, O_CLOEXEC) != 0) return fmt::format("drawing with plots/{}: cannot create a pipe: {}", script, std::strerror(errno));
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(err_pipe[0]);
    ::close(err_pipe[1]);
    return fmt::format("drawing with plots/{}: cannot start it: {}", script, std::strerror(errno));
  }
  if (pid == 0) {  // the child: dies with its parent; standard output discarded, errors to the pipe
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);  // the script removes its unfinished file and ends (plot_common.py)
    if (::getppid() != parent) ::_exit(127);  // the parent died before prctl took effect
    const int devnull = ::open("/dev/null", O_WRONLY);
    if (devnull >= 0) ::dup2(devnull, STDOUT_FILENO);
    ::dup2(err_pipe[1], STDERR_FILENO);
    ::execv(argv[0], argv.data());
    const char msg[] = "cannot execute /usr/bin/python3\n";
    [[maybe_unused]] const ssize_t n = ::write(STDERR_FILENO, msg, sizeof msg - 1);
    ::_exit(127);
  }
  ::close(err_pipe[1]);
  std::string errors;
  char buf[4096];
  for (;;) {
    const ssize_t n = ::read(err_pipe[0], buf, sizeof buf);
    if (n > 0) {
      errors.append(buf, static_cast<std::size_t>(n));
      if (errors.size() > (1 << 20)) errors.erase(0, errors.size() - (1 << 16));  // keep the end
    } else if (n == 0 || errno != EINTR) {
      break;
    }
  }
  ::close(err_pipe[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return "";
  if (WIFSIGNALED(status))
    return fmt::format("drawing with plots/{} was ended by signal {} ({}); no figure was written", script, WTERMSIG(status),
                       strsignal(WTERMSIG(status)));
  const std::string why = last_line(errors);
  if (why.find("No module named") != std::string::npos)
    return fmt::format("drawing with plots/{} failed: {} (it needs /usr/bin/python3 with numpy and matplotlib, which "
                       "scripts/install-deps.sh installs)", script, why);
  return fmt::format("drawing with plots/{} failed (exit code {}): {}", script, WEXITSTATUS(status),
                     why.empty() ? "no message" : why);
}

}  // namespace granchain
