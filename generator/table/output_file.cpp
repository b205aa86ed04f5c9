// SPDX-License-Identifier: Apache-2.0
// Safe output files (output_file.hpp): target checks by device and inode, a locked temporary
// beside the target, fsync around the rename, removal of temporaries left by killed runs, the
// checked reopening of an output a run continues.
#include "table/output_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>

#include "core/check.hpp"
#include "core/input_files.hpp"

namespace railtab {
namespace {

namespace fs = std::filesystem;

fs::path directory_of(const fs::path& target) {
  fs::path dir = target.parent_path();
  return dir.empty() ? fs::path(".") : dir;
}

// Takes the write lock of the open file description `fd` without waiting. Open-file-description
// locks are used because HDF5 takes flock() locks of its own on the same file (the two kinds do
// not interact on Linux) and because closing another descriptor of the file does not drop them.
bool try_lock(int fd) {
  struct flock lock {};
  lock.l_type = F_WRLCK;
  lock.l_whence = SEEK_SET;
  return ::fcntl(fd, F_OFD_SETLK, &lock) == 0;
}

bool process_gone(long pid) { return pid > 0 && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH; }

void sync_directory(const fs::path& dir) {
  int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;  // nothing to sync on a directory we cannot open; the rename itself succeeded
  ::fsync(fd);
  ::close(fd);
}

// Throws when the file `st` (reached as `target`) is one of `inputs` or a file this run read.
void refuse_inputs(const fs::path& target, const struct stat& st, const std::vector<fs::path>& inputs) {
  for (const fs::path& input : inputs) {
    struct stat in {};
    if (::stat(input.c_str(), &in) != 0) continue;
    RAILTAB_CHECK(!(in.st_dev == st.st_dev && in.st_ino == st.st_ino),
                  "{}: refusing to write: it is the input {} (same file); choose another output path",
                  target.string(), input.string());
  }
  const std::string read = input_file_path({static_cast<std::uint64_t>(st.st_dev), static_cast<std::uint64_t>(st.st_ino)});
  RAILTAB_CHECK(read.empty(), "{}: refusing to write: it is the input {} of this run (same file); choose another "
                "output path", target.string(), read);
}

// Throws unless the existing `target` (`link`: its lstat) may be replaced or continued: a regular
// file with one name, not a symbolic link.
void refuse_links_and_special_files(const fs::path& target, const struct stat& link) {
  RAILTAB_CHECK(!S_ISLNK(link.st_mode), "{}: refusing to write: it is a symbolic link; railtab writes only regular "
                "files of their own (give the file it points to, or another path)", target.string());
  RAILTAB_CHECK(S_ISREG(link.st_mode), "{}: refusing to write: it is {}, railtab writes only regular files",
                target.string(), file_kind(link.st_mode));
  RAILTAB_CHECK(link.st_nlink == 1, "{}: refusing to write: the file has {} names (hard links), and another name "
                "may be someone's input; remove this name first or choose another path",
                target.string(), static_cast<unsigned long long>(link.st_nlink));
}

}  // namespace

fs::path temporary_path(const fs::path& target) { return target.string() + ".tmp." + std::to_string(::getpid()); }

void check_output_path(const fs::path& target, const std::vector<fs::path>& inputs) {
  RAILTAB_CHECK(!target.empty() && target.filename() != "." && target.filename() != "..",
                "output path \"{}\" names no file", target.string());
  struct stat dir {};
  const fs::path parent = directory_of(target);
  RAILTAB_CHECK(::stat(parent.c_str(), &dir) == 0 && S_ISDIR(dir.st_mode),
                "{}: directory {} does not exist; refused before starting", target.string(), parent.string());
  // The temporary is created in this directory: without write and search permission every
  // minute of work before the write would be lost.
  RAILTAB_CHECK(::access(parent.c_str(), W_OK | X_OK) == 0, "{}: cannot write in directory {} ({}); refused before starting",
                target.string(), parent.string(), std::strerror(errno));
  struct stat link {};
  if (::lstat(target.c_str(), &link) != 0) {
    RAILTAB_CHECK(errno == ENOENT, "{}: cannot check the output path: {}", target.string(), std::strerror(errno));
    return;  // a new file
  }
  // An input reached through a link is named as the input: the most useful message.
  struct stat st {};
  if (::stat(target.c_str(), &st) == 0) refuse_inputs(target, st, inputs);
  refuse_links_and_special_files(target, link);
}

void check_output_directory(const fs::path& dir) {
  static std::atomic<unsigned> serial{0};
  const fs::path probe = dir / fmt::format(".railtab-write-check.{}.{}", ::getpid(), serial++);
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
  RAILTAB_CHECK(fd >= 0, "{}: cannot write there ({}); refused before starting", dir.string(), std::strerror(errno));
  ::close(fd);
  ::unlink(probe.c_str());
}

std::size_t remove_stale_temporaries(const fs::path& target) {
  const std::string prefix = target.filename().string() + ".tmp.";
  std::size_t removed = 0;
  std::error_code ec;
  for (fs::directory_iterator it(directory_of(target), ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string digits = name.substr(prefix.size());
    if (digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) continue;
    const long pid = std::stol(digits);
    // Ours from an earlier process of the same pid, or one whose process is gone; and in both
    // cases nobody holds its lock (a live writer always does).
    if (pid != ::getpid() && !process_gone(pid)) continue;
    int fd = ::open(it->path().c_str(), O_RDWR | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0) continue;
    struct stat st {};
    const bool stale = ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && try_lock(fd);
    if (stale && ::unlink(it->path().c_str()) == 0) ++removed;
    ::close(fd);
  }
  return removed;
}

OutputFile::OutputFile(fs::path target, const std::vector<fs::path>& inputs)
    : target_(std::move(target)), temporary_(temporary_path(target_)), inputs_(inputs) {
  check_output_path(target_, inputs);
  remove_stale_temporaries(target_);
  lock_fd_ = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
  RAILTAB_CHECK(lock_fd_ >= 0, "{}: cannot create the temporary {}: {}", target_.string(), temporary_.string(),
                std::strerror(errno));
  if (!try_lock(lock_fd_)) {
    const int err = errno;
    ::unlink(temporary_.c_str());
    ::close(lock_fd_);
    lock_fd_ = -1;
    throw Error(fmt::format("{}: cannot lock the temporary {}: {}", target_.string(), temporary_.string(),
                            std::strerror(err)));
  }
}

OutputFile::~OutputFile() {
  if (!committed_) ::unlink(temporary_.c_str());
  if (lock_fd_ >= 0) ::close(lock_fd_);
}

void OutputFile::commit() {
  RAILTAB_CHECK(!committed_, "{}: committed twice", target_.string());
  // The content reaches the disk before the name does: after a power loss the target is the old
  // file or the complete new one.
  RAILTAB_CHECK(::fsync(lock_fd_) == 0, "{}: cannot sync {}: {}", target_.string(), temporary_.string(),
                std::strerror(errno));
  // The name still leads to the file created (not a link or a file planted in its place).
  struct stat held {};
  struct stat named {};
  RAILTAB_CHECK(::fstat(lock_fd_, &held) == 0 && ::lstat(temporary_.c_str(), &named) == 0 && S_ISREG(named.st_mode) &&
                    held.st_dev == named.st_dev && held.st_ino == named.st_ino,
                "{}: the temporary {} was replaced while it was written; not renamed", target_.string(),
                temporary_.string());
  check_output_path(target_, inputs_);  // something may have appeared there meanwhile
  RAILTAB_CHECK(::rename(temporary_.c_str(), target_.c_str()) == 0, "{}: cannot rename {} into place: {}",
                target_.string(), temporary_.string(), std::strerror(errno));
  committed_ = true;
  sync_directory(directory_of(target_));
}

int OutputFile::commit_and_keep_open() {
  commit();
  const int fd = lock_fd_;
  lock_fd_ = -1;
  return fd;
}

int open_output_to_continue(const fs::path& path, const std::vector<fs::path>& inputs) {
  struct stat link {};
  if (::lstat(path.c_str(), &link) != 0) {
    RAILTAB_CHECK(errno == ENOENT, "{}: cannot check the file: {}", path.string(), std::strerror(errno));
    return -1;
  }
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) refuse_inputs(path, st, inputs);
  refuse_links_and_special_files(path, link);  // before opening: a device is never opened
  const int fd = ::open(path.c_str(), O_RDWR | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  RAILTAB_CHECK(fd >= 0, "{}: cannot open the file to continue it: {}", path.string(), std::strerror(errno));
  try {
    // What was opened is what is checked (the name may have changed since the lstat).
    RAILTAB_CHECK(::fstat(fd, &link) == 0, "{}: cannot stat the file: {}", path.string(), std::strerror(errno));
    refuse_inputs(path, link, inputs);
    refuse_links_and_special_files(path, link);
    RAILTAB_CHECK(try_lock(fd), "{}: another railtab run is writing this file; refused", path.string());
  } catch (...) {
    ::close(fd);
    throw;
  }
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  return fd;
}

void write_all(int fd, std::string_view bytes, const fs::path& file) {
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    RAILTAB_CHECK(n > 0, "{}: write failed: {}", file.string(), n < 0 ? std::strerror(errno) : "nothing written");
    bytes.remove_prefix(static_cast<std::size_t>(n));
  }
}

void write_text_file(const fs::path& target, std::string_view text, const std::vector<fs::path>& inputs) {
  OutputFile file(target, inputs);
  write_all(file.descriptor(), text, target);
  file.commit();
}

}  // namespace railtab
