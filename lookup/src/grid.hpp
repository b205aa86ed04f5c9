// SPDX-License-Identifier: Apache-2.0
// Grid side of the lookup: one axis of nodes and the search that places a query value in a cell.
// Kept apart from the interpolators (interpolate.hpp), which only see (cell, fraction) pairs.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace railtab::lookup::detail {

// State variables, numbered as State's members and the public Variable (yaw last).
enum Var : int { kVarY = 0, kVarRoll, kVarLoad, kVarXi, kVarEta, kVarPhi, kVarYaw, kNumVars };
const char* var_name(int var);  // "y", "roll", ...
// The order of the table's dimensions (docs/table-format.md: y, roll, yaw, load, xi, eta, phi):
// every loop that reads or lays out the file's axes walks this, not the Var numbers.
inline constexpr int kFileOrder[kNumVars] = {kVarY, kVarRoll, kVarYaw, kVarLoad, kVarXi, kVarEta, kVarPhi};
// The normal part's axes at most: y, roll, yaw, load (the creep scales and coefficients' grid).
inline constexpr int kMaxNormalDims = 4;
// The creepages (not the wheelset's position, orientation or load).
constexpr bool is_creepage(int var) noexcept { return var == kVarXi || var == kVarEta || var == kVarPhi; }

// Where a query value falls: between nodes i and i+1, at fraction t of the cell.
struct AxisLoc {
  int i = 0;       // cell index, 0 .. n-2
  // Cubic stencils only: bit 1 keeps node i-1 out, bit 2 node i+2 (a located contact jump lies
  // between it and the cell: jump_side.hpp, cubic_stencil_limits). 0 everywhere else.
  unsigned char cut_stencil = 0;
  double t = 0.0;  // position in the cell, 0 .. 1 (after clamping)
};

// Derivative at e of the parabola through (p[0], p[1], p[2]), as weights on the three values.
void parabola_slope(const double p[3], double e, double w[3]) noexcept;

// One tabulated axis: strictly increasing nodes, length >= 2.
class Axis {
 public:
  Axis() = default;
  explicit Axis(std::vector<double> nodes);  // nodes already validated by the loader

  // Places x in its cell; x outside [front, back] is clamped to the edge and the call returns
  // true (the caller flags kOutOfRange). x must be finite. No allocation, no throw.
  // Inline: it runs once per tabulated axis per query.
  bool locate(double x, AxisLoc& loc) const noexcept {
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
      // x - xs[0] >= 0 here, so the conversion truncates towards the cell start.
      i = std::min(static_cast<int>((x - xs[0]) * inv_h_), n - 2);
      if (x < xs[i]) --i;  // rounding put us one cell too far (i > 0 since x >= xs[0])
      else if (x > xs[i + 1] && i < n - 2) ++i;
    } else {
      // First interior node above x; the cell starts one before it.
      i = static_cast<int>(std::upper_bound(xs + 1, xs + n - 1, x) - xs) - 1;
    }
    loc.i = i;
    loc.t = (x - xs[i]) * inv_width_[i];
    return clamped;
  }

  // The query path's variant: the same cell (or, for x within rounding of a node, the
  // neighbouring cell with t at 0 or 1: the same interpolated value) and t clamped to [0, 1],
  // but on a uniform axis without any load that depends on the cell index: u = (x - x0) / h,
  // i = min(floor(u), n - 2), t = u - i (|error| ~ n ulp). Non-uniform axes: exactly the cell and
  // t of locate(), found without a search: a uniform bucket map (buckets a quarter of the
  // smallest spacing wide) gives the cell at the bucket's start, one compare either way fixes it.
  // Always inlined: GCC keeps it out of line, and a yaw table's fused query calls it six times
  // (y, yaw, load and the three creep coordinates): inline, that query is about 5 % faster.
  __attribute__((always_inline)) bool locate_fast(double x, AxisLoc& loc) const noexcept {
    const bool clamped = x < front_ || x > back_;
    if (uniform_) {
      double u = (x - front_) * inv_h_;
      u = std::min(std::max(u, 0.0), last_cell_ + 1.0);  // clamp: maxsd/minsd, no branch
      const int i = std::min(static_cast<int>(u), last_cell_);
      loc.i = i;
      loc.t = u - static_cast<double>(i);
      return clamped;
    }
    x = std::min(std::max(x, front_), back_);
    if (bucket_cell_.empty()) return locate(x, loc) || clamped;
    const double* xs = x_.data();
    const int k = std::min(static_cast<int>((x - front_) * inv_bucket_), last_bucket_);
    int i = bucket_cell_[static_cast<std::size_t>(k)];
    // The bucket is narrower than any cell, so rounding of k is the only reason to move, and
    // by one cell at most: down if x lies below the cell's start (i > 0 then, since x >= x0),
    // up if x reached the next node (not past the last cell, which keeps x = back).
    i -= static_cast<int>(x < xs[i]);
    i += static_cast<int>(i < last_cell_) & static_cast<int>(x >= xs[i + 1]);  // xs[i+1] exists
    loc.i = i;
    loc.t = (x - xs[i]) * inv_width_[static_cast<std::size_t>(i)];
    return clamped;
  }

  int size() const noexcept { return static_cast<int>(x_.size()); }
  const double* nodes() const noexcept { return x_.data(); }
  double inverse_width(int cell) const noexcept { return inv_width_[static_cast<std::size_t>(cell)]; }  // 1 / width
  // The cubic stencils' node slopes as weights on three neighbouring values (the derivative at
  // node k of the parabola through them), made once here instead of per query: 9 per node, the
  // centred one on nodes k-1, k, k+1, then the one-sided ones on k, k+1, k+2 (forward) and on
  // k-2, k-1, k (backward); zeros where the nodes do not exist.
  const double* slope_weights(int node) const noexcept { return &slope_[static_cast<std::size_t>(node) * 9]; }
  const std::vector<double>& node_vector() const noexcept { return x_; }

 private:
  std::vector<double> x_;          // nodes (n)
  std::vector<double> inv_width_;  // 1 / (x[i+1] - x[i]) (n-1): a multiply instead of a divide
  std::vector<double> slope_;      // slope_weights (9 n)
  bool uniform_ = false;           // equal spacing: the cell comes from one multiply, no search
  double inv_h_ = 0.0;             // 1 / spacing when uniform
  double front_ = 0.0, back_ = 0.0;  // first and last node
  int last_cell_ = 0;              // n - 2
  // Non-uniform axes: cell of the start of each bucket [x0 + k w, x0 + (k+1) w), w <= 1/4 of the
  // smallest spacing (empty if that would need more than kMaxBuckets: binary search then).
  static constexpr int kMaxBuckets = 1 << 14;
  std::vector<int> bucket_cell_;
  double inv_bucket_ = 0.0;        // 1 / w
  int last_bucket_ = 0;            // buckets - 1
};

}  // namespace railtab::lookup::detail
