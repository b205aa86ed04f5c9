// Interpolators over one block's records (layout in table_data.hpp). They see the grid only
// through per-axis cells (AxisLoc); grid.hpp finds the cells. No allocation, no throw.
#pragma once

#include "grid.hpp"
#include "table_data.hpp"

namespace railtab::lookup::detail {

// The multilinear kernel for a block of `n_dims` tabulated axes (0..kMaxDims) and records of
// `values_padded` values (even, 2..kMaxSlotValues), chosen once at load. It interpolates the block's values of slots [slot_begin, slot_end) at the cells
// loc[var] (indexed by state variable) straight into contact[slot - slot_begin].value, and
// combines the statuses of the cell's 2^D corner nodes into .part_status[part]: every bit but
// kConverged ORed, kConverged ANDed. The corner weights and offsets are computed once for all
// slots; both counts are template parameters so the corner loop unrolls and the sums stay in
// registers.
LinearKernel linear_kernel_for(int n_dims, int values_padded) noexcept;

// Tensor-product cubic Hermite, 4 nodes per axis (fewer at the table edge), slopes from the
// parabola through 3 neighbouring nodes (exact for quadratics); with `monotone`, slopes limited
// per node so that 0 <= slope / secant <= 3 on both sides (Fritsch-Carlson sufficient condition;
// zero slope at a data extremum), which keeps the result C1 and free of overshoot. Status as in
// the linear kernel (corners of the cell only, not the outer stencil nodes). Slots
// [slot_begin, slot_end) into contact[slot - slot_begin]; the per-axis stencils once for all.
void interpolate_cubic(const Block& block, const Axis* axes, const AxisLoc* loc, bool monotone,
                       int slot_begin, int slot_end, Contact* contact) noexcept;

}  // namespace railtab::lookup::detail
