// SPDX-License-Identifier: Apache-2.0
// Progress of a long sweep: a redrawn bar with rate and ETA on a terminal, plain periodic lines
// otherwise (logs, CI), called from one reporter thread only.
#pragma once

#include <atomic>
#include <chrono>
#include <functional>
#include <mutex>
#include <ostream>
#include <string>

#include "engine/sweep.hpp"

namespace railtab {

class ProgressPrinter {
 public:
  // label starts each plain line ("progress" for the sweep); unit names what is counted.
  ProgressPrinter(std::ostream& out, bool terminal, std::string label = "progress", std::string unit = "points")
      : out_(out), terminal_(terminal), label_(std::move(label)), unit_(std::move(unit)) {}
  void operator()(const SweepProgress& p);
  void finish();  // ends the bar's line

 private:
  std::ostream& out_;
  bool terminal_;             // redraw one line with \r
  std::string label_, unit_;
  double last_line_ = -1e9;   // time of the last plain line [s]
  double last_fraction_ = -1.0;
  bool drawn_ = false;
};

// Progress of a parallel loop without a reporter thread: workers call tick() after each task;
// one of them (whoever holds the lock) calls `report` at most every `interval` seconds, and
// finish() calls it once more with everything done. No-op when `report` is empty.
class TaskProgress {
 public:
  TaskProgress(std::function<void(const SweepProgress&)> report, std::size_t total, double interval = 0.25);
  void tick();
  void finish();

 private:
  void call(std::size_t done);
  std::function<void(const SweepProgress&)> report_;
  std::size_t total_;
  double interval_;
  std::chrono::steady_clock::time_point start_;
  std::atomic<std::size_t> done_{0};
  std::mutex mutex_;
  double last_ = 0.0;  // time of the last report [s], under mutex_
};

// "1:05", "12:03:44"
std::string format_duration(double seconds);

}  // namespace railtab
