// SPDX-License-Identifier: Apache-2.0
// Reading input files safely: only regular files (a device or FIFO is refused at
// once, without blocking), at most limits::kMaxProfileFileBytes and kMaxProfileLines.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace railtab {

// The whole content of a small input file (a profile, a scene), read safely: only a regular file
// (opened with O_NONBLOCK, so a FIFO cannot block, then checked with fstat: devices, FIFOs,
// sockets and directories are refused before any read) of at most max_bytes. Throws
// railtab::Error "file: problem" naming the file.
std::string read_regular_file(const std::filesystem::path& file, std::size_t max_bytes);

}  // namespace railtab

namespace railtab::detail {

struct TextFile {
  std::vector<std::string> lines;  // without their line ends
  bool ends_with_newline = true;   // false when the last line has no line end (a cut file)
};

// Throws railtab::Error "file: problem" for a missing, unreadable, non-regular or oversized file.
TextFile read_text_file(const std::filesystem::path& file);

}  // namespace railtab::detail
