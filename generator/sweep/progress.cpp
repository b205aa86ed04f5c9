// SPDX-License-Identifier: Apache-2.0
// Progress bar (terminal) or periodic lines (logs) of a running sweep.
#include "sweep/progress.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace railtab {

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  auto s = static_cast<long long>(std::llround(seconds));
  if (s >= 3600) return fmt::format("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60);
  return fmt::format("{}:{:02}", s / 60, s % 60);
}

void ProgressPrinter::operator()(const SweepProgress& p) {
  double fraction = p.points_todo == 0 ? 1.0 : static_cast<double>(p.points_done) / static_cast<double>(p.points_todo);
  double rate = p.seconds > 0 ? static_cast<double>(p.points_done) / p.seconds : 0.0;
  double eta = rate > 0 ? static_cast<double>(p.points_todo - p.points_done) / rate : NAN;
  if (terminal_) {
    constexpr int kWidth = 30;
    int filled = static_cast<int>(fraction * kWidth);
    out_ << fmt::format("\r[{}{}] {:5.1f}%  {}/{} points  {:.0f} points/s  ETA {}   ", std::string(filled, '#'),
                        std::string(kWidth - filled, '.'), 100 * fraction, p.points_done, p.points_todo, rate,
                        format_duration(eta))
         << std::flush;
    drawn_ = true;
    return;
  }
  // Plain lines: every 10 % or every 30 s, whichever comes first, and at the end.
  bool done = p.points_done == p.points_todo;
  if (done || fraction - last_fraction_ >= 0.1 || p.seconds - last_line_ >= 30.0) {
    if (done && last_fraction_ >= 1.0) return;
    out_ << fmt::format("progress: {:5.1f}%  {}/{} points  {:.0f} points/s  elapsed {}  ETA {}\n", 100 * fraction,
                        p.points_done, p.points_todo, rate, format_duration(p.seconds), format_duration(eta))
         << std::flush;
    last_fraction_ = done ? 1.0 : std::floor(fraction * 10) / 10;
    last_line_ = p.seconds;
  }
}

void ProgressPrinter::finish() {
  if (terminal_ && drawn_) out_ << "\n" << std::flush;
  drawn_ = false;
}

}  // namespace railtab
