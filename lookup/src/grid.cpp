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
  front_ = x_.front();
  back_ = x_.back();
  last_cell_ = static_cast<int>(n) - 2;
}

}  // namespace railtab::lookup::detail
