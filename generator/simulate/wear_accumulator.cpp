// SPDX-License-Identifier: Apache-2.0
// Accumulates the wear of a simulation per wheel revolution into a radial depth distribution.
#include "simulate/wear_accumulator.hpp"

#include <algorithm>
#include <cmath>

#include "core/check.hpp"

namespace railtab {
namespace {

// Number of bins of `grid`; the range must be a whole number of steps, so that every bin has the
// same width and worn_area = step * sum(depth) holds exactly.
std::size_t bin_count(const WearGrid& grid) {
  RAILTAB_CHECK(std::isfinite(grid.u_min) && std::isfinite(grid.u_max) && grid.u_max > grid.u_min,
                "wear grid: u_min < u_max (both finite) required, got [{}, {}] m", grid.u_min, grid.u_max);
  RAILTAB_CHECK(std::isfinite(grid.step) && grid.step > 0.0, "wear grid: step must be > 0, got {} m", grid.step);
  const double bins = (grid.u_max - grid.u_min) / grid.step;
  const double whole = std::round(bins);
  RAILTAB_CHECK(whole >= 1.0 && std::abs(bins - whole) <= 1e-6 * whole,
                "wear grid: [{}, {}] m is not a whole number of steps of {} m", grid.u_min, grid.u_max,
                grid.step);
  RAILTAB_CHECK(whole <= 1e7, "wear grid: {} bins is too many", whole);
  return static_cast<std::size_t>(whole);
}

}  // namespace

WearAccumulator::WearAccumulator(const Scene& scene, const WearGrid& grid)
    : WearAccumulator(scene, to_string(scene.normal.model), grid) {}

WearAccumulator::WearAccumulator(const Scene& scene, const std::string& post_processor,
                                 const WearGrid& grid)
    : solver_(make_geometry_solver(scene)),
      yaw_axis_(scene.grids.yaw.size() > 1),
      fixed_yaw_(fixed_yaw(scene)),
      wheel_wear_(make_wheel_wear(scene, post_processor)),
      grid_(grid) {
  const std::size_t n = bin_count(grid);
  u_.resize(n);
  for (std::size_t i = 0; i < n; ++i) u_[i] = grid.u_min + (static_cast<double>(i) + 0.5) * grid.step;
  for (auto& d : depth_) d.assign(n, 0.0);
}

std::uint32_t WearAccumulator::sample(double y_relative, const double (&load)[vehicle::kWheels],
                                      const vehicle::WheelsetMotion& motion, double distance) {
  RAILTAB_CHECK(std::isfinite(distance) && distance >= 0.0,
                "wear sample: distance must be finite and >= 0 m, got {}", distance);
  RAILTAB_CHECK(std::isfinite(motion.speed) && motion.speed > 0.0,
                "wear sample: speed must be > 0 m/s (creepages divide by it), got {}", motion.speed);
  for (int w = 0; w < vehicle::kWheels; ++w) {
    RAILTAB_CHECK(std::isfinite(load[w]) && load[w] >= 0.0,
                  "wear sample: load of wheel {} must be finite and >= 0 N, got {}", w, load[w]);
  }
  ++samples_;
  distance_ += distance;

  StatusBits bits = 0;
  WheelsetContactGeometry geometry;
  try {
    geometry = solver_.solve({y_relative, solver_.equilibrium_roll(y_relative), yaw_axis_ ? motion.yaw : fixed_yaw_});
  } catch (const Error&) {
    failures_ += vehicle::kWheels;
    return status::kFailed;
  }
  for (int w = 0; w < vehicle::kWheels; ++w) {
    if (!(load[w] > 0.0)) {
      bits |= status::kLiftOff;
      continue;
    }
    try {
      const StatusBits wheel_bits = wheel_wear_->wheel_wear(geometry.wheels[static_cast<std::size_t>(w)], w,
                                                            load[w], motion, pending_);
      if (wheel_bits & status::kNotConverged) ++not_converged_;
      bits |= wheel_bits;
    } catch (const Error&) {
      ++failures_;
      bits |= status::kFailed;
      continue;  // this wheel adds no wear: none of its patches, not only the failing one
    }
    for (const StripWear& s : pending_) add_strip(w, s.wheel_u, s.width_u, s.depth_rate * distance);
  }
  status_seen_ |= bits;
  return bits;
}

// Adds a strip's radial depth over [u_centre -+ width_u/2] to the bins it overlaps, each by its
// overlap length, so the worn area depth * width_u is kept exactly (up to what leaves the grid).
void WearAccumulator::add_strip(int wheel, double u_centre, double width_u, double depth) {
  if (!(depth > 0.0) || !(width_u > 0.0)) return;
  std::vector<double>& d = depth_[static_cast<std::size_t>(wheel)];
  const double a = u_centre - 0.5 * width_u;
  const double b = u_centre + 0.5 * width_u;
  const double step = grid_.step;
  const auto n = static_cast<std::ptrdiff_t>(d.size());
  const auto first = std::max<std::ptrdiff_t>(0, static_cast<std::ptrdiff_t>(std::floor((a - grid_.u_min) / step)));
  const auto last = std::min<std::ptrdiff_t>(n - 1, static_cast<std::ptrdiff_t>(std::floor((b - grid_.u_min) / step)));
  for (std::ptrdiff_t i = first; i <= last; ++i) {
    const double lo = grid_.u_min + static_cast<double>(i) * step;
    const double overlap = std::min(b, lo + step) - std::max(a, lo);
    if (overlap > 0.0) d[static_cast<std::size_t>(i)] += depth * overlap / step;
  }
  const double end = grid_.u_min + static_cast<double>(n) * step;
  const double outside = std::clamp(grid_.u_min - a, 0.0, width_u) + std::clamp(b - end, 0.0, width_u);
  clipped_[static_cast<std::size_t>(wheel)] += depth * std::min(outside, width_u);
}

const std::vector<double>& WearAccumulator::u() const { return u_; }

const std::vector<double>& WearAccumulator::depth(int wheel) const {
  RAILTAB_CHECK(wheel >= 0 && wheel < vehicle::kWheels, "wheel index must be 0 or 1, got {}", wheel);
  return depth_[static_cast<std::size_t>(wheel)];
}

double WearAccumulator::worn_area(int wheel) const {
  double sum = 0.0;
  for (double d : depth(wheel)) sum += d;
  return sum * grid_.step;
}

double WearAccumulator::clipped_area(int wheel) const {
  RAILTAB_CHECK(wheel >= 0 && wheel < vehicle::kWheels, "wheel index must be 0 or 1, got {}", wheel);
  return clipped_[static_cast<std::size_t>(wheel)];
}

double WearAccumulator::distance() const { return distance_; }
int WearAccumulator::samples() const { return samples_; }
int WearAccumulator::failures() const { return failures_; }
std::uint32_t WearAccumulator::status_seen() const { return status_seen_; }
int WearAccumulator::not_converged() const { return not_converged_; }

void WearAccumulator::scale(double factor) {
  RAILTAB_CHECK(std::isfinite(factor) && factor >= 0.0, "wear scale factor must be finite and >= 0, got {}", factor);
  for (auto& d : depth_) {
    for (double& v : d) v *= factor;
  }
  for (double& c : clipped_) c *= factor;
}

}  // namespace railtab
