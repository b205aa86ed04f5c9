// SPDX-License-Identifier: Apache-2.0
// Reading an input file safely (text_file.hpp): regular files only, size capped.
#include "profile/formats/text_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/check.hpp"
#include "core/input_files.hpp"
#include "profile/formats/profile_limits.hpp"

namespace railtab {
namespace {

// Closes the descriptor on every path out.
struct Descriptor {
  int fd;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

[[noreturn]] void fail_file(const std::filesystem::path& file, const std::string& problem) {
  throw Error(fmt::format("{}: {}", file.string(), problem));
}

}  // namespace

std::string read_regular_file(const std::filesystem::path& file, std::size_t max_bytes) {
  // O_NONBLOCK: opening a FIFO without a writer must not wait; fstat then refuses it.
  const Descriptor d{::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
  if (d.fd < 0) fail_file(file, fmt::format("cannot open the file for reading ({})", std::strerror(errno)));
  struct stat st {};
  if (::fstat(d.fd, &st) != 0) fail_file(file, fmt::format("cannot stat the file ({})", std::strerror(errno)));
  if (!S_ISREG(st.st_mode)) fail_file(file, "not a regular file (a device, FIFO, socket or directory): refused");
  note_input_file(file.string(), {static_cast<std::uint64_t>(st.st_dev), static_cast<std::uint64_t>(st.st_ino)});
  if (st.st_size < 0 || static_cast<std::size_t>(st.st_size) > max_bytes) {
    fail_file(file, fmt::format("{} bytes, more than the limit of {} bytes", static_cast<long long>(st.st_size),
                           max_bytes));
  }
  // Read at most the size plus one byte, whatever the size said (the file may grow meanwhile).
  std::string text;
  text.resize(static_cast<std::size_t>(st.st_size) + 1);
  std::size_t have = 0;
  while (have < text.size()) {
    const ssize_t n = ::read(d.fd, text.data() + have, text.size() - have);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail_file(file, fmt::format("read error ({})", std::strerror(errno)));
    if (n == 0) break;
    have += static_cast<std::size_t>(n);
  }
  if (have > static_cast<std::size_t>(st.st_size)) fail_file(file, "the file grew while it was read");
  text.resize(have);
  return text;
}

namespace detail {

TextFile read_text_file(const std::filesystem::path& file) {
  const std::string text = read_regular_file(file, limits::kMaxProfileFileBytes);
  TextFile out;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = text.find('\n', start);
    if (out.lines.size() >= limits::kMaxProfileLines) {
      fail_file(file, fmt::format("more than {} lines: not a profile", limits::kMaxProfileLines));
    }
    if (end == std::string::npos) {
      out.lines.push_back(text.substr(start));
      out.ends_with_newline = false;
      break;
    }
    out.lines.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

}  // namespace detail
}  // namespace railtab
