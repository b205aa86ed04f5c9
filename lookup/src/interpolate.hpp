// Interpolators over one block's records (layout in table_data.hpp). They see the grid only
// through per-axis cells (AxisLoc); grid.hpp finds the cells. No allocation, no throw.
#pragma once

#include "grid.hpp"
#include "table_data.hpp"

namespace railtab::lookup::detail {

// Interpolates the n_values values of `block` at the cells loc[var] (indexed by state variable)
// into values[0 .. values_padded-1], and combines the statuses of the cell's 2^D corner nodes
// into status[0 .. n_status-1]: every bit but kConverged ORed, kConverged ANDed.
void interpolate_linear(const Block& block, const AxisLoc* loc, double* values,
                        StatusBits* status) noexcept;

// Tensor-product cubic Hermite, 4 nodes per axis (fewer at the table edge), slopes from the
// parabola through 3 neighbouring nodes (exact for quadratics); with `monotone`, slopes limited
// per node so that 0 <= slope / secant <= 3 on both sides (Fritsch-Carlson sufficient condition;
// zero slope at a data extremum), which keeps the result C1 and free of overshoot. Status as in
// interpolate_linear (corners of the cell only, not the outer stencil nodes).
void interpolate_cubic(const Block& block, const Axis* axes, const AxisLoc* loc, bool monotone,
                       double* values, StatusBits* status) noexcept;

}  // namespace railtab::lookup::detail
