// SPDX-License-Identifier: Apache-2.0
// The input files of a run (input_files.hpp): a set of (device, inode) behind a mutex.
#include "core/input_files.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <map>
#include <mutex>
#include <utility>

#include "core/check.hpp"

namespace railtab {
namespace {

struct Registry {
  std::atomic<bool> on{false};
  std::mutex mutex;
  std::map<std::pair<std::uint64_t, std::uint64_t>, std::string> files;  // (device, inode) -> path
};

Registry& registry() {
  static Registry r;
  return r;
}

}  // namespace

const char* file_kind(unsigned mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

void track_input_files(bool on) {
  Registry& r = registry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  r.on = on;
  if (!on) r.files.clear();
}

void note_input_file(const std::string& path, FileIdentity id) {
  Registry& r = registry();
  if (!r.on) return;
  const std::lock_guard<std::mutex> lock(r.mutex);
  r.files.emplace(std::make_pair(id.device, id.inode), path);
}

std::string input_file_path(FileIdentity id) {
  Registry& r = registry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  const auto it = r.files.find({id.device, id.inode});
  return it == r.files.end() ? std::string() : it->second;
}

// Throws unless `st` is a regular file's.
void require_regular(const struct stat& st, const std::string& path, std::string_view what) {
  RAILTAB_CHECK(S_ISREG(st.st_mode), "{} {}: it is {}, not a regular file: refused", what, path,
                file_kind(st.st_mode));
}

int open_input_file(const std::string& path, std::string_view what) {
  // stat first: a device is refused without being opened (opening some has effects, a tape
  // rewinds); fstat after the open: what was opened is what is checked.
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    RAILTAB_CHECK(errno != ENOENT, "{} {}: no such file", what, path);
    throw Error(fmt::format("{} {}: cannot open it for reading ({})", what, path, std::strerror(errno)));
  }
  require_regular(st, path, what);
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  RAILTAB_CHECK(fd >= 0, "{} {}: cannot open it for reading ({})", what, path, std::strerror(errno));
  try {
    RAILTAB_CHECK(::fstat(fd, &st) == 0, "{} {}: cannot stat it ({})", what, path, std::strerror(errno));
    require_regular(st, path, what);
  } catch (...) {
    ::close(fd);
    throw;
  }
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  note_input_file(path, {static_cast<std::uint64_t>(st.st_dev), static_cast<std::uint64_t>(st.st_ino)});
  return fd;
}

}  // namespace railtab
