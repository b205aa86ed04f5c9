#include "grid.hpp"

#include <algorithm>
#include <cmath>

namespace railtab::lookup::detail {

const char* var_name(int var) {
  static const char* const names[kNumVars] = {"y", "roll", "load", "xi", "eta", "phi"};
  return (var >= 0 && var < kNumVars) ? names[var] : "?";
}

Axis::Axis(std::vector<double> nodes) : x_(std::move(nodes)) {
  const std::size_t n = x_.size();
  inv_width_.resize(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) inv_width_[i] = 1.0 / (x_[i + 1] - x_[i]);
  // Uniform when every spacing matches the mean to 1e-9 relative: then the cell index is one
  // multiply (generators write linspace grids), with a one-step correction for rounding below.
  const double h = (x_.back() - x_.front()) / static_cast<double>(n - 1);
  uniform_ = true;
  for (std::size_t i = 0; i + 1 < n; ++i)
    if (std::abs((x_[i + 1] - x_[i]) - h) > 1e-9 * h) uniform_ = false;
  inv_h_ = 1.0 / h;
}

bool Axis::locate(double x, AxisLoc& loc) const noexcept {
  const int n = size();
  const double* xs = x_.data();
  bool clamped = false;
  if (x < xs[0]) {
    x = xs[0];
    clamped = true;
  } else if (x > xs[n - 1]) {
    x = xs[n - 1];
    clamped = true;
  }
  int i;
  if (uniform_) {
    i = static_cast<int>((x - xs[0]) * inv_h_);
    i = std::clamp(i, 0, n - 2);
    if (x < xs[i] && i > 0) --i;  // rounding put us one cell too far
    else if (x > xs[i + 1] && i < n - 2) ++i;
  } else {
    // First interior node above x; the cell starts one before it.
    i = static_cast<int>(std::upper_bound(xs + 1, xs + n - 1, x) - xs) - 1;
  }
  loc.i = i;
  loc.t = (x - xs[i]) * inv_width_[i];
  return clamped;
}

}  // namespace railtab::lookup::detail
