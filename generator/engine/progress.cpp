// SPDX-License-Identifier: Apache-2.0
// Progress bar (terminal) or periodic lines (logs) of a running sweep.
#include "engine/progress.hpp"

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

namespace {
// Points per second as before ("1234"); slow stages (contact jumps: columns per second) keep digits.
std::string format_rate(double rate) { return rate >= 100 ? fmt::format("{:.0f}", rate) : fmt::format("{:.2g}", rate); }
}  // namespace

void ProgressPrinter::operator()(const SweepProgress& p) {
  double fraction = p.points_todo == 0 ? 1.0 : static_cast<double>(p.points_done) / static_cast<double>(p.points_todo);
  double rate = p.seconds > 0 ? static_cast<double>(p.points_done) / p.seconds : 0.0;
  double eta = rate > 0 ? static_cast<double>(p.points_todo - p.points_done) / rate : NAN;
  if (terminal_) {
    constexpr int kWidth = 30;
    int filled = static_cast<int>(fraction * kWidth);
    out_ << fmt::format("\r{}[{}{}] {:5.1f}%  {}/{} {}  {} {}/s  ETA {}   ",
                        label_ == "progress" ? "" : label_ + " ", std::string(filled, '#'),
                        std::string(kWidth - filled, '.'), 100 * fraction, p.points_done, p.points_todo, unit_, format_rate(rate),
                        unit_, format_duration(eta))
         << std::flush;
    drawn_ = true;
    return;
  }
  // Plain lines: every 10 % or every 30 s, whichever comes first, and at the end.
  bool done = p.points_done == p.points_todo;
  if (done || fraction - last_fraction_ >= 0.1 || p.seconds - last_line_ >= 30.0) {
    if (done && last_fraction_ >= 1.0) return;
    out_ << fmt::format("{}: {:5.1f}%  {}/{} {}  {} {}/s  elapsed {}  ETA {}\n", label_, 100 * fraction,
                        p.points_done, p.points_todo, unit_, format_rate(rate), unit_, format_duration(p.seconds),
                        format_duration(eta))
         << std::flush;
    last_fraction_ = done ? 1.0 : std::floor(fraction * 10) / 10;
    last_line_ = p.seconds;
  }
}

void ProgressPrinter::finish() {
  if (terminal_ && drawn_) out_ << "\n" << std::flush;
  drawn_ = false;
}

TaskProgress::TaskProgress(std::function<void(const SweepProgress&)> report, std::size_t total, double interval)
    : report_(std::move(report)), total_(total), interval_(interval), start_(std::chrono::steady_clock::now()) {}

void TaskProgress::call(std::size_t done) {
  const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (done < total_ && t - last_ < interval_) return;
  last_ = t;
  report_(SweepProgress{done, total_, t});
}

void TaskProgress::tick() {
  const std::size_t done = ++done_;
  if (!report_) return;
  std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);  // a busy reporter: skip, not wait
  if (lock.owns_lock() && done < total_) call(done);
}

void TaskProgress::finish() {
  if (!report_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  call(total_);
}

}  // namespace railtab
