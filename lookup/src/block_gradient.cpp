// SPDX-License-Identifier: Apache-2.0
// Exact derivatives of one block's interpolant (block_gradient.hpp).
#include "block_gradient.hpp"

#include <algorithm>
#include <cstring>

#include "interpolate.hpp"  // use_avx2
#include "weighted_sum.hpp"

namespace railtab::lookup::detail {

namespace {

// multilinear_gradient for N dimensions (cell_gradient in weighted_sum.hpp), compiled for SSE2
// and for AVX2 (the same operations in the same order, no fused multiply-add: the same bits
// either way).
template <int N, class T>
void gradient_sse2(RecordPtr p, const std::size_t* stride, const double* t, int n_values, double* value,
                   double (*out_dt)[kMaxDims]) noexcept {
  cell_gradient_sse2<N, T>(p, stride, t, n_values, value, out_dt);
}
template <int N, class T>
__attribute__((target("avx2"))) void gradient_avx2(RecordPtr p, const std::size_t* stride, const double* t,
                                                   int n_values, double* value, double (*out_dt)[kMaxDims]) noexcept {
  cell_gradient_avx2<N, T>(p, stride, t, n_values, value, out_dt);
}

template <int N, class T>
void gradient_dims(RecordPtr p, const std::size_t* stride, const double* t, int n_values, double* value,
                   double (*out_dt)[kMaxDims]) noexcept {
  static const bool avx2 = use_avx2();
  if (avx2) gradient_avx2<N, T>(p, stride, t, n_values, value, out_dt);
  else gradient_sse2<N, T>(p, stride, t, n_values, value, out_dt);
}

}  // namespace

// The switches below name every dimension count up to kMaxDims (y, roll, yaw, load and the three
// creepages): the default is the largest.
static_assert(kMaxDims == 7);

template <class T>
void multilinear_gradient(RecordPtr p, int n, const std::size_t* stride, const double* t, int n_values,
                          double* value, double (*out_dt)[kMaxDims]) noexcept {
  switch (n) {
    case 0: gradient_dims<0, T>(p, stride, t, n_values, value, out_dt); break;
    case 1: gradient_dims<1, T>(p, stride, t, n_values, value, out_dt); break;
    case 2: gradient_dims<2, T>(p, stride, t, n_values, value, out_dt); break;
    case 3: gradient_dims<3, T>(p, stride, t, n_values, value, out_dt); break;
    case 4: gradient_dims<4, T>(p, stride, t, n_values, value, out_dt); break;
    case 5: gradient_dims<5, T>(p, stride, t, n_values, value, out_dt); break;
    case 6: gradient_dims<6, T>(p, stride, t, n_values, value, out_dt); break;
    default: gradient_dims<kMaxDims, T>(p, stride, t, n_values, value, out_dt); break;
  }
}
template void multilinear_gradient<double>(RecordPtr, int, const std::size_t*, const double*, int, double*,
                                           double (*)[kMaxDims]) noexcept;
template void multilinear_gradient<float>(RecordPtr, int, const std::size_t*, const double*, int, double*,
                                          double (*)[kMaxDims]) noexcept;

namespace {

void clear(BlockGradient& g, int n_values) noexcept {
  for (int k = 0; k < n_values; ++k)
    for (double& x : g.d[k]) x = 0.0;
}

void block_multilinear(const Block& b, RecordPtr p, int n, const std::size_t* stride, const double* t,
                       double* value, double (*dt)[kMaxDims]) noexcept {
  if (b.value_bytes == sizeof(float)) multilinear_gradient<float>(p, n, stride, t, b.n_values, value, dt);
  else multilinear_gradient<double>(p, n, stride, t, b.n_values, value, dt);
}

}  // namespace

void linear_gradient(const Block& b, const Axis* axes, const AxisLoc* loc, int slot, BlockGradient& g) noexcept {
  clear(g, b.n_values);
  std::size_t base = 0;
  double t[kMaxDims];
  for (int dim = 0; dim < b.n_dims; ++dim) {
    const AxisLoc& l = loc[b.var[dim]];
    base += static_cast<std::size_t>(l.i) * b.stride[dim];
    t[dim] = l.t;
  }
  double dt[kMaxSlotValues][kMaxDims];
  RecordPtr p = b.data.data() + static_cast<std::size_t>(slot) * b.slot_size + base;
  block_multilinear(b, p, b.n_dims, b.stride, t, g.value, dt);
  for (int dim = 0; dim < b.n_dims; ++dim) {
    const int var = b.var[dim];
    const double inv = inverse_width(axes[var], loc[var]);
    for (int k = 0; k < b.n_values; ++k) g.d[k][var] = dt[k][dim] * inv;
  }
}

double piece_slope(const JumpWheel& j, const Axis& y_axis, std::size_t load_node, const Piece& piece,
                   double yq) noexcept {
  auto position = [&](const End& e) {
    return e.sample ? j.y[0][load_node][static_cast<std::size_t>(e.index)] : y_axis.nodes()[e.index];
  };
  const double from = position(piece.a), to = position(piece.b);
  if (!(to > from)) return 0.0;
  const double raw = (yq - from) / (to - from);
  return raw >= 0.0 && raw <= 1.0 ? 1.0 / (to - from) : 0.0;
}

void jump_gradient(const TableData& d, int w, int bi, const AxisLoc* loc, const Piece (*pieces)[2], int slot,
                   BlockGradient& g) noexcept {
  const Block& b = d.block[w][bi];
  const JumpWheel& j = d.jumps[w];
  const JumpSamples& js = j.samples[bi];
  const int nv = b.n_values, inner0 = js.inner0, n_inner = js.n_inner, ld = js.load_dim;
  const int nodes = j.load_axis ? 2 : 1;
  const int lc = j.load_axis ? loc[kVarLoad].i : 0;
  const double weight[2] = {j.load_axis ? 1.0 - loc[kVarLoad].t : 1.0, j.load_axis ? loc[kVarLoad].t : 0.0};
  const double* x = d.axis[kVarY].nodes();
  const double yq = x[loc[kVarY].i] + loc[kVarY].t * (x[loc[kVarY].i + 1] - x[loc[kVarY].i]);
  // The creepage cell (as creep_cell in jump_side.cpp).
  std::size_t base = 0;
  double t[kMaxDims];
  for (int q = 0; q < n_inner; ++q) {
    const AxisLoc& l = loc[b.var[inner0 + q]];
    base += static_cast<std::size_t>(l.i) * b.stride[inner0 + q];
    t[q] = l.t;
  }
  clear(g, nv);
  double piece_value[2][kMaxSlotValues] = {};
  for (int k = 0; k < nv; ++k) g.value[k] = 0.0;
  const std::size_t s = static_cast<std::size_t>(slot);
  for (int k = 0; k < nodes; ++k) {
    const Piece& piece = pieces[js.list][k];
    const std::size_t lnode = static_cast<std::size_t>(lc + k);
    auto slice = [&](const End& e) -> RecordPtr {
      if (e.sample)
        return js.data.data() + s * js.slot_stride + lnode * js.load_stride +
               static_cast<std::size_t>(e.index) * js.jump_stride + static_cast<std::size_t>(e.side) * js.side_stride;
      return b.data.data() + s * b.slot_size + static_cast<std::size_t>(e.index) * b.stride[0] +
             (ld >= 0 ? lnode * b.stride[ld] : 0);
    };
    double va[kMaxSlotValues], vb[kMaxSlotValues], da[kMaxSlotValues][kMaxDims], db[kMaxSlotValues][kMaxDims];
    block_multilinear(b, slice(piece.a) + base, n_inner, b.stride + inner0, t, va, da);
    block_multilinear(b, slice(piece.b) + base, n_inner, b.stride + inner0, t, vb, db);
    const double pt = piece.t, slope = piece_slope(j, d.axis[kVarY], lnode, piece, yq);
    for (int v = 0; v < nv; ++v) {
      piece_value[k][v] = (1.0 - pt) * va[v] + pt * vb[v];
      g.value[v] += weight[k] * piece_value[k][v];
      g.d[v][kVarY] += weight[k] * (vb[v] - va[v]) * slope;
      for (int q = 0; q < n_inner; ++q)
        g.d[v][b.var[inner0 + q]] += weight[k] * ((1.0 - pt) * da[v][q] + pt * db[v][q]);
    }
  }
  for (int q = 0; q < n_inner; ++q) {
    const int var = b.var[inner0 + q];
    const double inv = inverse_width(d.axis[var], loc[var]);
    for (int v = 0; v < nv; ++v) g.d[v][var] *= inv;
  }
  // The two load nodes' pieces are blended with the load weights, for a block over y alone too
  // (its pieces differ where the two load nodes' jumps do).
  if (j.load_axis) {
    const double inv = inverse_width(d.axis[kVarLoad], loc[kVarLoad]);
    for (int v = 0; v < nv; ++v) g.d[v][kVarLoad] = (piece_value[1][v] - piece_value[0][v]) * inv;
  }
}

void one_sided_scales_gradient(const TableData& d, int w, const AxisLoc* loc, const Piece (*pieces)[2], int slot,
                               double inv[3], double (*dinv)[kNumVars]) noexcept {
  const CreepMap& map = d.creep_map;
  const JumpWheel& j = d.jumps[w];
  for (int c = 0; c < 3; ++c)
    for (int var = 0; var < kNumVars; ++var) dinv[c][var] = 0.0;
  const int nodes = j.load_axis ? 2 : 1, lc = j.load_axis ? loc[kVarLoad].i : 0;
  const double weight[2] = {j.load_axis ? 1.0 - loc[kVarLoad].t : 1.0, j.load_axis ? loc[kVarLoad].t : 0.0};
  const double* x = d.axis[kVarY].nodes();
  const AxisLoc& ly = loc[kVarY];
  const double yq = x[ly.i] + ly.t * (x[ly.i + 1] - x[ly.i]);
  const double* grid = map.scale[w].data() + static_cast<std::size_t>(slot) * map.nodes * 3;
  const double* at_jump = slot_at_jump(j, j.inv_scale, 3, slot);
  double node_inv[2][3] = {};
  inv[0] = inv[1] = inv[2] = 0.0;
  for (int k = 0; k < nodes; ++k) {
    const std::size_t lnode = static_cast<std::size_t>(lc + k);
    const Piece& piece = pieces[0][k];
    const double* a = node_end_values(map, j, grid, at_jump, 3, lnode, piece.a);
    const double* b = node_end_values(map, j, grid, at_jump, 3, lnode, piece.b);
    const double slope = piece_slope(j, d.axis[kVarY], lnode, piece, yq);
    for (int c = 0; c < 3; ++c) {
      node_inv[k][c] = (1.0 - piece.t) * a[c] + piece.t * b[c];
      inv[c] += weight[k] * node_inv[k][c];
      dinv[c][kVarY] += weight[k] * (b[c] - a[c]) * slope;
    }
  }
  if (j.load_axis) {
    const double iw = inverse_width(d.axis[kVarLoad], loc[kVarLoad]);
    for (int c = 0; c < 3; ++c) dinv[c][kVarLoad] = (node_inv[1][c] - node_inv[0][c]) * iw;
  }
}

void chain_creep_coordinates(const Block& b, const BlockGradient& g, const double (*dv)[kNumVars],
                             double (*out)[kNumVars]) noexcept {
  for (int k = 0; k < b.n_values; ++k) {
    double* row = out[b.output_of[k]];
    const double* gk = g.d[k];
    for (int var = 0; var < kNumVars; ++var)
      row[var] = (is_creepage(var) ? 0.0 : gk[var]) + gk[kVarXi] * dv[0][var] + gk[kVarXi + 1] * dv[1][var] +
                 gk[kVarXi + 2] * dv[2][var];
  }
}

}  // namespace railtab::lookup::detail
