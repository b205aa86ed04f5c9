// Grid side of the lookup: one axis of nodes and the search that places a query value in a cell.
// Kept apart from the interpolators (interpolate.hpp), which only see (cell, fraction) pairs.
#pragma once

#include <cstddef>
#include <vector>

namespace railtab::lookup::detail {

// State variables in table order (docs/table-format.md: y, roll, load, xi, eta, phi).
enum Var : int { kVarY = 0, kVarRoll, kVarLoad, kVarXi, kVarEta, kVarPhi, kNumVars };
const char* var_name(int var);  // "y", "roll", ...

// Where a query value falls: between nodes i and i+1, at fraction t of the cell.
struct AxisLoc {
  int i = 0;       // cell index, 0 .. n-2
  double t = 0.0;  // position in the cell, 0 .. 1 (after clamping)
};

// One tabulated axis: strictly increasing nodes, length >= 2.
class Axis {
 public:
  Axis() = default;
  explicit Axis(std::vector<double> nodes);  // nodes already validated by the loader

  // Places x in its cell; x outside [front, back] is clamped to the edge and the call returns
  // true (the caller flags kOutOfRange). x must be finite. No allocation, no throw.
  bool locate(double x, AxisLoc& loc) const noexcept;

  int size() const noexcept { return static_cast<int>(x_.size()); }
  const double* nodes() const noexcept { return x_.data(); }
  const std::vector<double>& node_vector() const noexcept { return x_; }

 private:
  std::vector<double> x_;          // nodes (n)
  std::vector<double> inv_width_;  // 1 / (x[i+1] - x[i]) (n-1): a multiply instead of a divide
  bool uniform_ = false;           // equal spacing: the cell comes from one multiply, no search
  double inv_h_ = 0.0;             // 1 / spacing when uniform
};

}  // namespace railtab::lookup::detail
