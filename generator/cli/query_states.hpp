// SPDX-License-Identifier: Apache-2.0
// States for `railtab query --states FILE`, read one line at a time (FILE '-' is stdin), so any
// number of states fits in a fixed amount of memory.
//
//   # comment lines and blank lines are skipped
//   y,load,xi          <- header: y and any of roll, load, xi, eta, phi, yaw, comma-separated
//   0.003,78500,0.001  <- one state per line, every number by its documented range
#pragma once

#include <array>
#include <fstream>
#include <istream>
#include <string>

#include "railtab/lookup.hpp"

namespace railtab {

class StateReader {
 public:
  // Opens `path` ('-': stdin) and reads its header; throws railtab::Error naming the file.
  explicit StateReader(const std::string& path);

  // True when the header names column `name`.
  bool has(const char* name) const;

  // The next state: the columns of the file set in `state`, the rest left as given. False at the
  // end; a bad line throws railtab::Error "FILE:LINE: column NAME: problem".
  bool next(lookup::State& state);

 private:
  bool read_line(std::string& line);  // the next line that is not blank or a comment

  std::string path_;         // as given, for messages
  std::ifstream file_;       // when not stdin
  std::istream* in_;         // the file or std::cin
  long line_number_ = 0;     // of the last line read
  std::array<int, 7> column_{};  // for y, roll, load, xi, eta, phi, yaw: its column, or -1
  int columns_ = 0;          // fields per line
};

}  // namespace railtab
