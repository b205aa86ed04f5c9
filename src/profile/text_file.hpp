// Reading a profile file as lines, safely: only regular files (a device or FIFO is refused at
// once, without blocking), at most limits::kMaxProfileFileBytes and kMaxProfileLines.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace railtab::detail {

struct TextFile {
  std::vector<std::string> lines;  // without their line ends
  bool ends_with_newline = true;   // false when the last line has no line end (a cut file)
};

// Throws railtab::Error "file: problem" for a missing, unreadable, non-regular or oversized file.
TextFile read_text_file(const std::filesystem::path& file);

}  // namespace railtab::detail
