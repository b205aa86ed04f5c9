// SPDX-License-Identifier: Apache-2.0
// Table::query_derivatives: the query's values plus the exact partial derivatives of its
// interpolant with respect to every state variable (docs/lookup.md, "Derivatives"). The values
// are query()'s own; the derivatives come from the same cells, stencils and one-sided pieces
// (block_gradient.hpp) and, with normalised creep coordinates, the chain rule through the slot's
// scales, the coordinate map, the saturation law and the normal force (creep_map.hpp).
#include <algorithm>
#include <cmath>

#include "block_gradient.hpp"
#include "creep_map.hpp"
#include "jump_piece.hpp"
#include "railtab/lookup.hpp"
#include "table_data.hpp"

namespace railtab::lookup {
namespace detail {
namespace {

// The public Variable numbers are the internal Var ones.
constexpr bool same(int a, int b) { return a == b; }
static_assert(same(kNumVars, kNumVariables) && same(kVarY, kY) && same(kVarRoll, kRoll) && same(kVarLoad, kLoad) &&
              same(kVarXi, kXi) && same(kVarEta, kEta) && same(kVarPhi, kPhi) && same(kVarYaw, kYaw));

// Where the query lies, as locate_state (table.cpp) places it, and which variables are held at
// the table's edge (their derivative is 0: the value does not change there).
struct Location {
  AxisLoc loc[kNumVars];
  double creepage[3] = {};       // normalised creep coordinates: physical creepages, clamped
  bool frozen[kNumVars] = {};    // clamped to the table's range
  bool cut = false;              // a located jump may cut the cell (one-sided, jump_side.hpp)
  Piece pieces[2][2];            // the cut cell's pieces (query_pieces)
  int slot_begin = 0;            // first slot queried (Captured's slot 0)
};

void locate(const TableData& d, int w, const State& state, Location& at) noexcept {
  double v[kNumVars];
  table_variables(d, state, v);
  const CreepMap& map = d.creep_map;
  for (int k = 0; k < d.n_located; ++k) {
    const int var = d.located_var[k];
    at.frozen[var] = d.axis[var].locate_fast(v[var], at.loc[var]);
  }
  for (int k = 0; k < d.n_clamped; ++k) {
    const int c = d.clamped_var[k] - kVarXi;
    const double x = v[kVarXi + c];
    at.frozen[kVarXi + c] = x < map.lo[c] || x > map.hi[c];
    at.creepage[c] = std::min(std::max(x, map.lo[c]), map.hi[c]);
  }
  if (map.active)
    for (int c = 0; c < 3; ++c)
      if (!map.swept[c]) at.creepage[c] = d.fixed[kVarXi + c] ? d.fixed_value[kVarXi + c] : 0.0;
  at.cut = d.has_jumps && jump_cell(d, w, at.loc);
  if (d.has_jumps && !at.cut && d.method != Method::kLinear) cubic_stencil_limits(d, w, at.loc);
  if (at.cut) query_pieces(d.jumps[w], d.axis[kVarY], at.loc, d.jumps[w].load_axis ? 2 : 1, at.pieces);
}

// One slot's outputs and d output / d variable (`d` the caller's, zeroed), built block by block
// as the query writes them.
struct SlotGradient {
  double value[kNumOutputs] = {};  // 0 for parts the table does not hold, as the query's
  double (*d)[kNumVars] = nullptr;
};

// Each block's values and derivatives per slot from the cubic kernel's own pass (query_generic).
using Captured = BlockGradient[kNumParts][kMaxSlots];

// One block's values and derivatives for one slot: one-sided in a cut cell, the multilinear
// cell's, or the cubic kernel's as the query's pass left them in `captured` (into `scratch` or
// from `captured`).
const BlockGradient& block_gradient(const TableData& d, int w, int bi, const Location& at, const AxisLoc* loc,
                                    int slot, const Captured& captured, BlockGradient& scratch) noexcept {
  if (at.cut) jump_gradient(d, w, bi, loc, at.pieces, slot, scratch);
  else if (d.method == Method::kLinear) linear_gradient(d.block[w][bi], d.axis, loc, slot, scratch);
  else return captured[bi][slot - at.slot_begin];
  return scratch;
}

// The slot's reciprocal creepage scales and their derivatives with respect to y, roll, yaw and load:
// multilinear over the normal part's grid (interpolate_scales), or in a cut cell one-sided from
// the pieces of every jump (one_sided_scales in jump_side.cpp).
void scales(const TableData& d, int w, const Location& at, int slot, double inv[3], double dinv[3][kNumVars]) noexcept {
  const CreepMap& map = d.creep_map;
  for (int c = 0; c < 3; ++c)
    for (int var = 0; var < kNumVars; ++var) dinv[c][var] = 0.0;
  const std::size_t s = static_cast<std::size_t>(slot);
  if (!at.cut) {
    std::size_t origin = 0, stride[kMaxNormalDims];
    double t[kMaxNormalDims], dt[3][kMaxDims];
    for (int k = 0; k < map.n_dims; ++k) {
      const AxisLoc& l = at.loc[map.var[k]];
      origin += static_cast<std::size_t>(l.i) * map.stride[k];
      stride[k] = map.stride[k] * 3 * sizeof(double);
      t[k] = l.t;
    }
    const double* p = map.scale[w].data() + (s * map.nodes + origin) * 3;
    multilinear_gradient<double>(reinterpret_cast<RecordPtr>(p), map.n_dims, stride, t, 3, inv, dt);
    for (int k = 0; k < map.n_dims; ++k) {
      const int var = map.var[k];
      const double iw = inverse_width(d.axis[var], at.loc[var]);
      for (int c = 0; c < 3; ++c) dinv[c][var] = dt[c][k] * iw;
    }
    return;
  }
  one_sided_scales_gradient(d, w, at.loc, at.pieces, slot, inv, dinv);
}

// The normalised creep block of one slot: its v cells at the slot's scales, its gradient chained
// through v to y, roll, load and the physical creepages, then the forces scaled back to N
// (denormalise_creep) with their derivatives.
void normalised_creep(const TableData& d, int w, int bi, const Location& at, int slot, const Captured& captured,
                      SlotGradient& out) noexcept {
  const CreepMap& map = d.creep_map;
  const Block& b = d.block[w][bi];
  double inv[3], dinv[3][kNumVars];
  scales(d, w, at, slot, inv, dinv);
  AxisLoc loc[kNumVars];
  std::copy(at.loc, at.loc + kNumVars, loc);
  double xn[3], dxn[3][kNumVars] = {}, dv[3][kNumVars] = {};
  for (int k = 0; k < 3; ++k) {
    const int cv = kVarXi + k;
    xn[k] = at.creepage[k] * inv[k];
    for (int var = 0; var < kNumVars; ++var)
      if (!is_creepage(var)) dxn[k][var] = at.creepage[k] * dinv[k][var];
    if (map.swept[k] && !at.frozen[cv]) dxn[k][cv] = inv[k];
    if (!map.swept[k]) continue;
    d.axis[cv].locate_fast(creep_coordinate_normalised(xn[k] * map.kinv[k], map.lo_k[k] * inv[k], map.hi_k[k] * inv[k]),
                           loc[cv]);
    coordinate_gradient(map, k, xn[k], inv[k], dxn[k], dinv[k], dv[k]);
  }
  BlockGradient scratch;
  const BlockGradient& g = block_gradient(d, w, bi, at, loc, slot, captured, scratch);
  for (int k = 0; k < b.n_values; ++k) out.value[b.output_of[k]] = g.value[k];
  chain_creep_coordinates(b, g, dv, out.d);
  if (!d.has_part[kCreep]) return;
  const double angle = out.value[kContactAngle];
  double cos_angle, sin_angle;
  angle_cos_sin(angle, cos_angle, sin_angle);
  denormalise_creep_gradient(map, xn, dxn, out.value, cos_angle, sin_angle, out.d);
}

void slot_gradient(const TableData& d, int w, const Location& at, int slot, const Captured& captured,
                   SlotGradient& out) noexcept {
  for (int bi = 0; bi < d.n_blocks; ++bi) {
    if (d.creep_map.active && bi == d.creep_block) {
      normalised_creep(d, w, bi, at, slot, captured, out);
      continue;
    }
    const Block& b = d.block[w][bi];
    BlockGradient scratch;
    const BlockGradient& g = block_gradient(d, w, bi, at, at.loc, slot, captured, scratch);
    for (int k = 0; k < b.n_values; ++k) {
      const int o = b.output_of[k];
      out.value[o] = g.value[k];
      for (int var = 0; var < kNumVars; ++var) out.d[o][var] = g.d[k][var];
    }
  }
}

}  // namespace
}  // namespace detail

const char* variable_name(int variable) noexcept { return detail::var_name(variable); }

bool Table::derivatives_supported() const noexcept { return data_->method != Method::kMonotoneCubic; }

namespace detail {
namespace {

// Values and derivatives of slots [slot_begin, slot_end) (valid) of wheel w into contact[0 ..]
// and deriv[0 ..]; q gets the query bits. Returns false for a method without derivatives.
bool slot_range_derivatives(const TableData& d, int w, const State& state, int slot_begin, int slot_end,
                            Contact* contact, double (*deriv)[kNumOutputs][kNumVars], StatusBits& q) noexcept {
  if (d.fast.derivatives && (w == 0 || w == 1) &&  // fast_path.hpp; false: not finite, or a cut cell
      d.fast.derivatives(d, w, state, slot_begin, slot_end, contact, deriv, q))
    return true;
  // The cubic kernel's derivatives come from the value pass itself (captured); the other
  // methods' from the block gradients below.
  Captured captured;
  q = query_generic(d, w, state, slot_begin, slot_end, contact, d.method == Method::kCubic ? captured : nullptr);
  const int n = slot_end - slot_begin;
  for (int s = 0; s < n; ++s)
    for (auto& row : deriv[s])
      for (double& x : row) x = 0.0;  // parts the table does not hold, untabulated variables
  if (d.method == Method::kMonotoneCubic) return false;
  if (q & status::kInvalidInput) return true;
  Location at;
  locate(d, w, state, at);
  at.slot_begin = slot_begin;
  for (int s = 0; s < n; ++s) {
    SlotGradient g;
    g.d = deriv[s];
    slot_gradient(d, w, at, slot_begin + s, captured, g);
    for (int var = 0; var < kNumVars; ++var)
      if (at.frozen[var])
        for (int o = 0; o < kNumOutputs; ++o) deriv[s][o][var] = 0.0;
    // A table over |yaw|: d/d yaw = sign(yaw) d/d|yaw|, and 0 at yaw = 0 (an even function's).
    if (d.yaw_even && !(state.yaw > 0.0)) {
      const double sign = state.yaw < 0.0 ? -1.0 : 0.0;
      for (int o = 0; o < kNumOutputs; ++o) deriv[s][o][kVarYaw] *= sign;
    }
  }
  return true;
}

}  // namespace
}  // namespace detail

bool Table::query_derivatives(Wheel wheel, const State& state, Result& result, Derivatives& derivatives) const noexcept {
  const detail::TableData& d = *data_;
  result.n_slots = d.n_slots;
  return detail::slot_range_derivatives(d, static_cast<int>(wheel), state, 0, d.n_slots, result.contact,
                                        derivatives.d, result.status);
}

bool Table::query_slot_derivatives(Wheel wheel, const State& state, int slot, Contact& contact,
                                   SlotDerivatives& derivatives) const noexcept {
  const detail::TableData& d = *data_;
  if (slot < 0 || slot >= d.n_slots) {  // as query_slot: zeros and kInvalidInput
    contact = Contact{};
    contact.status = status::kInvalidInput;
    derivatives = SlotDerivatives{};
    return derivatives_supported();
  }
  StatusBits q = 0;
  return detail::slot_range_derivatives(d, static_cast<int>(wheel), state, slot, slot + 1, &contact,
                                        &derivatives.d, q);
}

}  // namespace railtab::lookup
