// SPDX-License-Identifier: Apache-2.0
// Progress of a long sweep: a redrawn bar with rate and ETA on a terminal, plain periodic lines
// otherwise (logs, CI), called from one reporter thread only.
#pragma once

#include <ostream>

#include "sweep/sweep.hpp"

namespace railtab {

class ProgressPrinter {
 public:
  ProgressPrinter(std::ostream& out, bool terminal) : out_(out), terminal_(terminal) {}
  void operator()(const SweepProgress& p);
  void finish();  // ends the bar's line

 private:
  std::ostream& out_;
  bool terminal_;             // redraw one line with \r
  double last_line_ = -1e9;   // time of the last plain line [s]
  double last_fraction_ = -1.0;
  bool drawn_ = false;
};

// "1:05", "12:03:44"
std::string format_duration(double seconds);

}  // namespace railtab
