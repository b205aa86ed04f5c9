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

// Derivative at e of the parabola through (p[0], p[1], p[2]), as weights on the three values
// (interpolate.cpp's cubic slopes).
void parabola_slope(const double p[3], double e, double w[3]) noexcept {
  w[0] = ((e - p[1]) + (e - p[2])) / ((p[0] - p[1]) * (p[0] - p[2]));
  w[1] = ((e - p[0]) + (e - p[2])) / ((p[1] - p[0]) * (p[1] - p[2]));
  w[2] = ((e - p[0]) + (e - p[1])) / ((p[2] - p[0]) * (p[2] - p[1]));
}

// One axis of the cubic stencil as weights on its 2-4 consecutive nodes, and the weights of the
// derivative with respect to the axis's variable: the stencil, slopes and Hermite basis of
// interpolate.cpp's make_cubic_axis / cubic_weights, the basis differentiated.
struct StencilWeights {
  int first = 0;     // first stencil node
  int count = 0;     // stencil nodes (2..4)
  double w[4] = {};  // value weights
  double dw[4] = {}; // derivative weights [1 / axis unit]
};

StencilWeights cubic_stencil(const Axis& axis, const AxisLoc& l) noexcept {
  const int n = axis.size();
  const double* xs = axis.nodes();
  const int i = l.i;
  const bool has_left = i >= 1 && !(l.cut_stencil & 1);
  const bool has_right = i + 2 <= n - 1 && !(l.cut_stencil & 2);
  double x[4];
  for (int j = 0; j < 4; ++j) x[j] = xs[std::clamp(i - 1 + j, 0, n - 1)];
  const double h = x[2] - x[1];
  double c0[4] = {}, c1[4] = {}, w[3];
  if (has_left) {
    parabola_slope(&x[0], x[1], w);
    c0[0] = w[0], c0[1] = w[1], c0[2] = w[2];
  } else if (has_right) {
    parabola_slope(&x[1], x[1], w);
    c0[1] = w[0], c0[2] = w[1], c0[3] = w[2];
  } else {
    c0[1] = -1.0 / h, c0[2] = 1.0 / h;
  }
  if (has_right) {
    parabola_slope(&x[1], x[2], w);
    c1[1] = w[0], c1[2] = w[1], c1[3] = w[2];
  } else if (has_left) {
    parabola_slope(&x[0], x[2], w);
    c1[0] = w[0], c1[1] = w[1], c1[2] = w[2];
  } else {
    c1[1] = -1.0 / h, c1[2] = 1.0 / h;
  }
  const double t = l.t, t2 = t * t, t3 = t2 * t;
  const double h00 = 2 * t3 - 3 * t2 + 1, h01 = -2 * t3 + 3 * t2;
  const double h10 = (t3 - 2 * t2 + t) * h, h11 = (t3 - t2) * h;
  // d/dx = d/dt / h.
  const double d00 = (6 * t2 - 6 * t) / h, d01 = (-6 * t2 + 6 * t) / h;
  const double d10 = 3 * t2 - 4 * t + 1, d11 = 3 * t2 - 2 * t;
  const int lo = has_left ? 0 : 1, hi = has_right ? 3 : 2;
  StencilWeights s;
  s.first = std::clamp(i - 1 + lo, 0, n - 1);
  s.count = hi - lo + 1;
  for (int j = lo; j <= hi; ++j) {
    s.w[j - lo] = (j == 1 ? h00 : 0.0) + (j == 2 ? h01 : 0.0) + h10 * c0[j] + h11 * c1[j];
    s.dw[j - lo] = (j == 1 ? d00 : 0.0) + (j == 2 ? d01 : 0.0) + d10 * c0[j] + d11 * c1[j];
  }
  return s;
}

// The cubic cell's value and gradient sums for N dimensions, the values in chunks of L lanes (as
// multilinear_gradient_n): the outer dimensions 0 .. N-2 by a mixed-radix counter, the last
// (unit-stride) one inside, every record read once.
template <int N, int L, class T>
__attribute__((always_inline)) inline void cubic_sum_n(const std::size_t* stride, const StencilWeights* sw,
                                                       RecordPtr p, int n_values, double* out_value,
                                                       double (*out_dt)[kMaxDims]) noexcept {
  constexpr int kLast = N - 1;
  const StencilWeights& in = sw[kLast];
  for (int k0 = 0; k0 < n_values; k0 += L) {
    const int lanes = std::min(L, n_values - k0);
    double value[L] = {}, dt[N][L] = {};
    int idx[N > 1 ? N - 1 : 1] = {};
    for (;;) {
      std::size_t off = 0;
      double weight = 1.0, dweight[N > 1 ? N - 1 : 1];
      for (int dim = 0; dim < kLast; ++dim) {
        off += static_cast<std::size_t>(idx[dim]) * stride[dim];
        dweight[dim] = 1.0;
      }
      for (int dim = 0; dim < kLast; ++dim) {
        for (int e = 0; e < kLast; ++e) dweight[e] *= e == dim ? sw[dim].dw[idx[dim]] : sw[dim].w[idx[dim]];
        weight *= sw[dim].w[idx[dim]];
      }
      // The inner axis: its value and derivative sums per value.
      double a[L] = {}, da[L] = {};
      RecordPtr r = p + off;
      for (int j = 0; j < in.count; ++j, r += stride[kLast]) {
        const double wj = in.w[j], dwj = in.dw[j];
        for (int k = 0; k < L; ++k) {
          const double f = k < lanes ? record_value<T>(r, k0 + k) : 0.0;
          a[k] += wj * f;
          da[k] += dwj * f;
        }
      }
      for (int k = 0; k < L; ++k) {
        value[k] += weight * a[k];
        dt[kLast][k] += weight * da[k];
        for (int dim = 0; dim < kLast; ++dim) dt[dim][k] += dweight[dim] * a[k];
      }
      int dim = kLast - 1;
      while (dim >= 0 && ++idx[dim] == sw[dim].count) idx[dim--] = 0;
      if (dim < 0) break;
    }
    for (int k = 0; k < lanes; ++k) {
      out_value[k0 + k] = value[k];
      for (int dim = 0; dim < N; ++dim) out_dt[k0 + k][dim] = dt[dim][k];
    }
  }
}

template <int N, int L, class T>
void cubic_sse2(const std::size_t* stride, const StencilWeights* sw, RecordPtr p, int n_values, double* value,
                double (*dt)[kMaxDims]) noexcept {
  cubic_sum_n<N, L, T>(stride, sw, p, n_values, value, dt);
}
template <int N, int L, class T>
__attribute__((target("avx2"))) void cubic_avx2(const std::size_t* stride, const StencilWeights* sw, RecordPtr p,
                                                int n_values, double* value, double (*dt)[kMaxDims]) noexcept {
  cubic_sum_n<N, L, T>(stride, sw, p, n_values, value, dt);
}

template <int N, class T>
void cubic_dims(const std::size_t* stride, const StencilWeights* sw, RecordPtr p, int n_values, double* value,
                double (*dt)[kMaxDims]) noexcept {
  static const bool avx2 = use_avx2();
#define RAILTAB_CUBIC_LANES(L)                                                                          \
  return avx2 ? cubic_avx2<N, L, T>(stride, sw, p, n_values, value, dt)                                 \
              : cubic_sse2<N, L, T>(stride, sw, p, n_values, value, dt)
  if (n_values <= 2) RAILTAB_CUBIC_LANES(2);
  if (n_values <= 3) RAILTAB_CUBIC_LANES(3);
  if (n_values <= 4) RAILTAB_CUBIC_LANES(4);
  if (n_values <= 6) RAILTAB_CUBIC_LANES(6);
  RAILTAB_CUBIC_LANES(8);
#undef RAILTAB_CUBIC_LANES
}

template <class T>
void cubic_sum(const Block& b, const StencilWeights* sw, RecordPtr p, BlockGradient& g) noexcept {
  double dt[kMaxSlotValues][kMaxDims];
  switch (b.n_dims) {
    case 1: cubic_dims<1, T>(b.stride, sw, p, b.n_values, g.value, dt); break;
    case 2: cubic_dims<2, T>(b.stride, sw, p, b.n_values, g.value, dt); break;
    case 3: cubic_dims<3, T>(b.stride, sw, p, b.n_values, g.value, dt); break;
    case 4: cubic_dims<4, T>(b.stride, sw, p, b.n_values, g.value, dt); break;
    case 5: cubic_dims<5, T>(b.stride, sw, p, b.n_values, g.value, dt); break;
    case 6: cubic_dims<6, T>(b.stride, sw, p, b.n_values, g.value, dt); break;
    default: cubic_dims<kMaxDims, T>(b.stride, sw, p, b.n_values, g.value, dt); break;
  }
  for (int k = 0; k < b.n_values; ++k)
    for (int dim = 0; dim < b.n_dims; ++dim) g.d[k][b.var[dim]] = dt[k][dim];
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

void cubic_gradient(const Block& b, const Axis* axes, const AxisLoc* loc, int slot, BlockGradient& g) noexcept {
  if (b.n_dims == 0) {
    linear_gradient(b, axes, loc, slot, g);
    return;
  }
  clear(g, b.n_values);
  StencilWeights sw[kMaxDims];
  std::size_t base = 0;
  for (int dim = 0; dim < b.n_dims; ++dim) {
    sw[dim] = cubic_stencil(axes[b.var[dim]], loc[b.var[dim]]);
    base += static_cast<std::size_t>(sw[dim].first) * b.stride[dim];
  }
  RecordPtr p = b.data.data() + static_cast<std::size_t>(slot) * b.slot_size + base;
  if (b.value_bytes == sizeof(float)) cubic_sum<float>(b, sw, p, g);
  else cubic_sum<double>(b, sw, p, g);
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
