// SPDX-License-Identifier: Apache-2.0
// Safe output files (output_file.hpp): target checks by device and inode, a locked temporary
// beside the target, fsync around the rename, removal of temporaries left by killed runs.
#include "table/output_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <fstream>

#include "core/check.hpp"

namespace railtab {
namespace {

namespace fs = std::filesystem;

fs::path directory_of(const fs::path& target) {
  fs::path dir = target.parent_path();
  return dir.empty() ? fs::path(".") : dir;
}

const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
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
  struct stat st {};
  if (::stat(target.c_str(), &st) != 0) {
    RAILTAB_CHECK(errno == ENOENT, "{}: cannot check the output path: {}", target.string(), std::strerror(errno));
    return;  // a new file
  }
  RAILTAB_CHECK(S_ISREG(st.st_mode), "{}: refusing to write: it is {}, railtab writes only regular files",
                target.string(), kind_of(st.st_mode));
  for (const fs::path& input : inputs) {
    struct stat in {};
    if (::stat(input.c_str(), &in) != 0) continue;
    RAILTAB_CHECK(!(in.st_dev == st.st_dev && in.st_ino == st.st_ino),
                  "{}: refusing to write: it is the input {} (same file); choose another output path",
                  target.string(), input.string());
  }
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
    : target_(std::move(target)), temporary_(temporary_path(target_)) {
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
  check_output_path(target_);  // something non-regular may have appeared there meanwhile
  RAILTAB_CHECK(::rename(temporary_.c_str(), target_.c_str()) == 0, "{}: cannot rename {} into place: {}",
                target_.string(), temporary_.string(), std::strerror(errno));
  committed_ = true;
  sync_directory(directory_of(target_));
}

void write_text_file(const fs::path& target, std::string_view text) {
  OutputFile file(target);
  {
    std::ofstream out(file.temporary(), std::ios::binary | std::ios::trunc);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.close();
    RAILTAB_CHECK(out.good(), "{}: write failed", file.temporary().string());
  }
  file.commit();
}

}  // namespace railtab
