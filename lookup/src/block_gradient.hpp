// SPDX-License-Identifier: Apache-2.0
// Exact derivatives of one block's interpolant (Table::query_derivatives, derivatives.cpp): the
// values of one slot and their partial derivatives with respect to the block's coordinates, for
// the multilinear kernel of a cell no jump cuts and for the one-sided linear rule of a cut cell
// (jump_side.hpp). Same cells and one-sided pieces as the value kernels (interpolate_linear.cpp,
// jump_side.cpp); nothing here changes a value the query returns. The cubic kernel gives its
// derivatives itself, from its own pass (query_generic with a BlockGradient sink).
#pragma once

#include <cstddef>

#include "grid.hpp"
#include "jump_piece.hpp"
#include "records.hpp"
#include "table_data.hpp"

namespace railtab::lookup::detail {

// One slot's values (record order, Block::output_of) and d value / d coordinate per state
// variable: per SI unit of the variable on a physical axis, per unit of v on a normalised creep
// axis (creep_map.hpp); 0 for variables the block is not tabulated over.
struct BlockGradient {
  double value[kMaxSlotValues];
  double d[kMaxSlotValues][kNumVars];
};

// The query of slots [slot_begin, slot_end) (valid slots) of wheel w (0 or 1, else every contact
// kInvalidInput) without the fused fast path (table.cpp): values and statuses into
// contact[0 .. slot_end - slot_begin - 1]; returns the query bits (kOutOfRange, kInvalidInput).
// grads: null, or (cubic method) grads[block][s - slot_begin] receives each block's values and
// their derivatives from the same pass (the derivative query, derivatives.cpp); a cut cell
// (jump_side.hpp) leaves them unset.
StatusBits query_generic(const TableData& d, int w, const State& state, int slot_begin, int slot_end,
                         Contact* contact, BlockGradient (*grads)[kMaxSlots]) noexcept;

// Multilinear value and derivatives with respect to the cell fractions t[0 .. n-1] of n_values
// values of T (double or float) at the 2^n corners of the cell whose first record is `p`
// (stride: bytes between neighbouring nodes per dimension). out_dt[k][dim] = d value_k / d t_dim.
template <class T>
void multilinear_gradient(RecordPtr p, int n, const std::size_t* stride, const double* t,
                          int n_values, double* value, double (*out_dt)[kMaxDims]) noexcept;

// 1 / width of the cell `loc` lies in.
inline double inverse_width(const Axis& axis, const AxisLoc& loc) noexcept { return axis.inverse_width(loc.i); }

// A cell no jump cuts: the multilinear kernel's interpolant.
void linear_gradient(const Block& b, const Axis* axes, const AxisLoc* loc, int slot,
                     BlockGradient& g) noexcept;

// d piece.t / d y of a jump piece at load node `load_node` (absolute index) for the query's y:
// 1 / (to - from) while the fraction is inside [0, 1], 0 where it is clamped (the one-sided value
// at the jump is held) or the piece is one node.
double piece_slope(const JumpWheel& j, const Axis& y_axis, std::size_t load_node, const Piece& piece,
                   double yq) noexcept;

// A cut cell: the one-sided linear rule of interpolate_jump_cell for block `bi` of wheel w, the
// creepage cell at loc (for a normalised creep block: its v cells), `pieces` from query_pieces.
void jump_gradient(const TableData& d, int w, int bi, const AxisLoc* loc, const Piece (*pieces)[2],
                   int slot, BlockGradient& g) noexcept;

// A cut cell's reciprocal creepage scales (one_sided_node_values of the normal part's pieces,
// `pieces` from query_pieces) and their derivatives with respect to y and load (dinv rows over the
// state variables, the others 0).
void one_sided_scales_gradient(const TableData& d, int w, const AxisLoc* loc, const Piece (*pieces)[2], int slot,
                               double inv[3], double (*dinv)[kNumVars]) noexcept;

// The rows out[b.output_of[k]] of a normalised creep block's values: g's derivatives with respect
// to y, roll and load, plus those along the block's v coordinates (per unit v) chained through
// dv[q][var] = d v_q / d var.
void chain_creep_coordinates(const Block& b, const BlockGradient& g, const double (*dv)[kNumVars],
                             double (*out)[kNumVars]) noexcept;

}  // namespace railtab::lookup::detail
