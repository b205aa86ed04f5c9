// SPDX-License-Identifier: Apache-2.0
// One axis of nodes and the search placing a query value in its cell (grid.hpp).
#include "grid.hpp"

#include <algorithm>
#include <cmath>

namespace railtab::lookup::detail {

const char* var_name(int var) {
  static const char* const names[kNumVars] = {"y", "roll", "load", "xi", "eta", "phi", "yaw"};
  return (var >= 0 && var < kNumVars) ? names[var] : "?";
}

void parabola_slope(const double p[3], double e, double w[3]) noexcept {
  w[0] = ((e - p[1]) + (e - p[2])) / ((p[0] - p[1]) * (p[0] - p[2]));
  w[1] = ((e - p[0]) + (e - p[2])) / ((p[1] - p[0]) * (p[1] - p[2]));
  w[2] = ((e - p[0]) + (e - p[1])) / ((p[2] - p[0]) * (p[2] - p[1]));
}

Axis::Axis(std::vector<double> nodes) : x_(std::move(nodes)) {
  const std::size_t n = x_.size();
  inv_width_.resize(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) inv_width_[i] = 1.0 / (x_[i + 1] - x_[i]);
  slope_.assign(9 * n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    double* w = &slope_[9 * k];
    if (k >= 1 && k + 1 < n) parabola_slope(&x_[k - 1], x_[k], w);
    if (k + 2 < n) parabola_slope(&x_[k], x_[k], w + 3);
    if (k >= 2) parabola_slope(&x_[k - 2], x_[k], w + 6);
  }
  // Uniform when every spacing matches the mean to 1e-9 relative: then the cell index is one
  // multiply (generators write linspace grids), with a one-step correction for rounding below.
  const double h = (x_.back() - x_.front()) / static_cast<double>(n - 1);
  uniform_ = true;
  for (std::size_t i = 0; i + 1 < n; ++i)
    if (std::abs((x_[i + 1] - x_[i]) - h) > 1e-9 * h) uniform_ = false;
  inv_h_ = 1.0 / h;
  front_ = x_.front();
  back_ = x_.back();
  last_cell_ = static_cast<int>(n) - 2;
  if (uniform_) return;
  double min_width = h;
  for (std::size_t i = 0; i + 1 < n; ++i) min_width = std::min(min_width, x_[i + 1] - x_[i]);
  const double buckets = std::ceil(4.0 * (back_ - front_) / min_width);
  if (!(buckets <= kMaxBuckets)) return;
  const int nb = std::max(1, static_cast<int>(buckets));
  inv_bucket_ = static_cast<double>(nb) / (back_ - front_);
  last_bucket_ = nb - 1;
  bucket_cell_.resize(static_cast<std::size_t>(nb));
  for (int k = 0; k < nb; ++k) {
    AxisLoc loc;
    locate(front_ + static_cast<double>(k) / inv_bucket_, loc);
    bucket_cell_[static_cast<std::size_t>(k)] = loc.i;
  }
}

}  // namespace railtab::lookup::detail
