#include "store/output_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "config/input_error.hpp"
#include "store/results_store.hpp"

namespace granchain {

namespace {

// Writes all of text to fd, retrying short writes; errno on failure, 0 on success.
int write_all(int fd, const std::string& text) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    done += static_cast<std::size_t>(n);
  }
  return 0;
}

OutputError write_error(const std::string& option, const std::string& path, int err) {
  return OutputError(fmt::format("{}: cannot write '{}': {}", option, path, std::strerror(err)));
}

}  // namespace

bool is_standard_output(const std::string& path) { return path == "-"; }

bool same_file(const std::string& a, const std::string& b) {
  struct stat sa {}, sb {};
  if (::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  std::error_code ea, eb;
  const auto ca = std::filesystem::weakly_canonical(a, ea), cb = std::filesystem::weakly_canonical(b, eb);
  return !ea && !eb && ca == cb;
}

void check_output_file(const std::string& path, const std::string& option, const std::vector<NamedPath>& inputs) {
  if (path.empty()) throw InputError(fmt::format("{}: the file name is empty; name a file", option));
  if (is_standard_output(path))
    throw InputError(fmt::format("{}: '-' (standard output) is not possible for this output; name a file", option));
  for (const NamedPath& in : inputs)
    if (!in.path.empty() && !is_standard_output(in.path) && same_file(path, in.path))
      throw InputError(fmt::format("{}: '{}' is the same file as {} '{}'; writing it would destroy that; choose another file",
                                   option, path, in.option, in.path));
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode)) {
    if (::access(path.c_str(), W_OK) != 0) throw InputError(fmt::format("{}: '{}' is not writable", option, path));
    return;  // a device or FIFO, written directly
  }
  const std::string reason = cannot_create_file_reason(path);
  if (!reason.empty()) throw InputError(option + ": " + reason);
}

void check_outputs(const std::vector<NamedPath>& outputs, const std::vector<NamedPath>& inputs) {
  std::vector<NamedPath> others = inputs;
  for (const NamedPath& out : outputs) {
    if (out.path.empty()) continue;
    check_output_file(out.path, out.option, others);
    others.push_back(out);
  }
}

PendingFile::PendingFile(std::string path, std::string text, std::string option)
    : path_(std::move(path)), text_(std::move(text)), option_(std::move(option)) {
  struct stat st {};
  if (::stat(path_.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) return;  // written directly at commit
  tmp_ = path_ + ".tmp" + std::to_string(::getpid());
  const int fd = ::open(tmp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) {
    const int err = errno;
    tmp_.clear();
    throw write_error(option_, path_, err);
  }
  int err = write_all(fd, text_);
  if (err == 0 && ::fsync(fd) != 0) err = errno;
  if (::close(fd) != 0 && err == 0) err = errno;
  if (err != 0) {
    std::remove(tmp_.c_str());
    tmp_.clear();
    throw write_error(option_, path_, err);
  }
  text_.clear();
}

PendingFile::~PendingFile() {
  if (!committed_ && !tmp_.empty()) std::remove(tmp_.c_str());
}

void PendingFile::commit() {
  if (committed_) return;
  if (tmp_.empty()) {  // not a regular file: write into it
    const int fd = ::open(path_.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd < 0) throw write_error(option_, path_, errno);
    int err = write_all(fd, text_);
    if (::close(fd) != 0 && err == 0) err = errno;
    if (err != 0) throw write_error(option_, path_, err);
  } else if (std::rename(tmp_.c_str(), path_.c_str()) != 0) {
    throw write_error(option_, path_, errno);
  }
  committed_ = true;
}

void write_file_atomically(const std::string& path, const std::string& text, const std::string& option) {
  PendingFile(path, text, option).commit();
}

void write_standard_output(const std::string& text) {
  errno = 0;
  const bool ok = std::fwrite(text.data(), 1, text.size(), stdout) == text.size() && std::fflush(stdout) == 0;
  if (!ok) throw OutputError(fmt::format("cannot write standard output: {}", std::strerror(errno ? errno : EIO)));
}

}  // namespace granchain
