// SPDX-License-Identifier: Apache-2.0
// Interpolators over one block's records (layout in table_data.hpp). They see the grid only
// through per-axis cells (AxisLoc); grid.hpp finds the cells. No allocation, no throw.
#pragma once

#include "grid.hpp"
#include "table_data.hpp"

namespace railtab::lookup::detail {

// The multilinear kernel for a block of `n_dims` tabulated axes (0..kMaxDims) and records of
// `n_values` values (1..kMaxSlotValues), chosen once at load. It interpolates the block's
// values of slots [slot_begin, slot_end) at the cells loc[var] (indexed by state variable)
// straight into contact[slot - slot_begin].value, and copies the cell's status (query layout,
// table_data.hpp: every bit but kEveryCorner's ORed over the 2^D corners, those ANDed) into
// .part_status[part]. The corner weights and offsets are computed once for all slots; both
// counts are template parameters so the corner loop unrolls and the sums stay in registers.
// value_bytes: the records' value type (Block::value_bytes, 8 double or 4 float; float records of
// at most kMaxFloatValues values).
LinearKernel linear_kernel_for(int n_dims, int n_values, int value_bytes) noexcept;
// Float records hold at most this many values: the creep and wear block holds at most 6 (format
// 2.2's float32 outputs); kernels for more would only cost compile time (and code size).
inline constexpr int kMaxFloatValues = 8;

// Whether the AVX2 kernels run (the CPU has AVX2 and RAILTAB_LOOKUP_NO_AVX2 is unset or 0).
bool use_avx2() noexcept;

// Tensor-product cubic Hermite, 4 nodes per axis (fewer at the table edge), slopes from the
// parabola through 3 neighbouring nodes (exact for quadratics). Linear in the node values, so
// each axis reduces to 2-4 weights on consecutive nodes (StencilWeights) and the query is a
// weighted sum over the stencil's records (576 for the default scene's 5-D creep block, whose
// load and phi axes have 3 nodes), contracted one axis at a time. Status as in the linear kernel
// (the cell's). With a BlockGradient sink the same pass gives the exact derivatives too (the
// derivative query). Chosen at load by `n_values`.
CubicKernel cubic_kernel_for(int n_values, int value_bytes) noexcept;


// The one-sided sum of a jump cell (jump_side.hpp) for blocks with n_inner creepage dimensions
// (0..kMaxJumpInner) and records of n_values values of value_bytes each, chosen once at load.
inline constexpr int kMaxJumpInner = 3;  // xi, eta, phi
JumpKernel jump_kernel_for(int n_inner, int n_values, int value_bytes) noexcept;

// As the cubic with slopes limited per node so that 0 <= slope / secant <= 3 on both sides
// (Fritsch-Carlson sufficient condition; zero slope at a data extremum), which keeps the result
// C1 and free of overshoot. Nonlinear in the data: successive 1-D passes over the 4^D stencil.
// Chosen at load by the value type (SSE2 or AVX2 lanes, the same bytes); no derivatives (grad unused).
CubicKernel monotone_kernel_for(int value_bytes) noexcept;

}  // namespace railtab::lookup::detail
