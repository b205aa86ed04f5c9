// SPDX-License-Identifier: Apache-2.0
// The cubic interpolators over one block's records (interpolate.hpp): the tensor cubic Hermite
// (with its derivatives) and the monotone cubic.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <immintrin.h>
#include <limits>
#include <utility>

#include "block_gradient.hpp"
#include "interpolate.hpp"
#include "interpolate_common.hpp"
#include "part_spec.hpp"
#include "weighted_sum.hpp"

namespace railtab::lookup::detail {
namespace {

// One axis of the cubic stencil: nodes j = 0..3 are i-1, i, i+1, i+2; 0 and 3 may be absent (a
// table edge, or a located contact jump between them and the cell: AxisLoc::cut_stencil).
// No member initialisers: make_cubic_axis writes every field, and zeroing the struct first was a
// rep stos on every call (a third of the function's time).
struct CubicAxis {
  std::size_t stride;    // bytes between neighbouring nodes
  std::size_t idx[4];    // node indices (absent ones unused)
  bool has_left;         // node i-1 exists
  bool has_right;        // node i+2 exists
  double x[4];           // node coordinates
  double c0[4];          // slope at node i   = sum_j c0[j] f[j]
  double c1[4];          // slope at node i+1 = sum_j c1[j] f[j]
  double h00, h01;       // Hermite value basis at t
  double h10, h11;       // Hermite slope basis at t, times the cell width
  double t;              // fraction in the cell
  double inv_width[3];   // 1 / (x[j + 1] - x[j]), the secants' (monotone cubic only: set_secant_widths)
};

CubicAxis make_cubic_axis(const Axis& axis, const AxisLoc& l, std::size_t stride) noexcept {
  CubicAxis a;
  for (int j = 0; j < 4; ++j) a.c0[j] = a.c1[j] = 0.0;
  const int n = axis.size();
  const double* xs = axis.nodes();
  const int i = l.i;
  a.stride = stride;
  a.has_left = i >= 1 && !(l.cut_stencil & 1);
  a.has_right = i + 2 <= n - 1 && !(l.cut_stencil & 2);
  for (int j = 0; j < 4; ++j) {
    const int node = std::clamp(i - 1 + j, 0, n - 1);
    a.idx[j] = static_cast<std::size_t>(node);
    a.x[j] = xs[node];
  }
  const double h = a.x[2] - a.x[1];
  // The parabolas' weights come from the axis (Axis::slope_weights: centred, forward, backward).
  const double* w0 = axis.slope_weights(i);
  const double* w1 = axis.slope_weights(i + 1);
  // Slope at node i: centred on (i-1, i, i+1) if possible, else one-sided on (i, i+1, i+2).
  if (a.has_left) {
    a.c0[0] = w0[0], a.c0[1] = w0[1], a.c0[2] = w0[2];
  } else if (a.has_right) {
    a.c0[1] = w0[3], a.c0[2] = w0[4], a.c0[3] = w0[5];
  } else {
    a.c0[1] = -1.0 / h, a.c0[2] = 1.0 / h;
  }
  // Slope at node i+1: centred on (i, i+1, i+2) if possible, else one-sided on (i-1, i, i+1).
  if (a.has_right) {
    a.c1[1] = w1[0], a.c1[2] = w1[1], a.c1[3] = w1[2];
  } else if (a.has_left) {
    a.c1[0] = w1[6], a.c1[1] = w1[7], a.c1[2] = w1[8];
  } else {
    a.c1[1] = -1.0 / h, a.c1[2] = 1.0 / h;
  }
  const double t = l.t, t2 = t * t, t3 = t2 * t;
  a.h00 = 2 * t3 - 3 * t2 + 1;
  a.h01 = -2 * t3 + 3 * t2;
  a.h10 = (t3 - 2 * t2 + t) * h;
  a.h11 = (t3 - t2) * h;
  a.t = t;
  return a;
}

// The monotone cubic's secant reciprocals (one multiply per secant at every stencil line, not a
// division; the widths of absent neighbours unused).
void set_secant_widths(CubicAxis& a) noexcept {
  for (int j = 0; j < 3; ++j) {
    const bool present = j == 1 || (j == 0 ? a.has_left : a.has_right);
    a.inv_width[j] = present ? 1.0 / (a.x[j + 1] - a.x[j]) : 0.0;
  }
}

// Limits a node slope m between secants s_left and s_right (equal at a table edge):
// zero at a data extremum, else same sign as the secants and at most 3x the smaller one.
// The bound depends on the node only, so neighbouring cells agree on it and the result stays C1.
double limit_slope(double m, double s_left, double s_right) noexcept {
  if (s_left * s_right <= 0.0) return 0.0;
  const double sign = s_right > 0.0 ? 1.0 : -1.0;
  const double bound = 3.0 * std::min(std::abs(s_left), std::abs(s_right));
  return sign * std::min(std::max(m * sign, 0.0), bound);
}

// Values of a larger magnitude are scaled down before the limited Hermite: their secants and
// slopes (differences over a node spacing) would overflow to infinity, and inf - inf is NaN.
constexpr double kScaleAbove = 0x1p500;  // about 3.3e150

double hermite(const CubicAxis& a, const double f[4], bool monotone) noexcept;

// The limited Hermite of values near the double range: by a power of two to |f| <= 1, which
// is exact, so the result is the unscaled one wherever that does not overflow.
double hermite_scaled(const CubicAxis& a, const double f[4], double magnitude) noexcept {
  const int exponent = std::ilogb(magnitude) + 1;
  double g[4];
  for (int j = 0; j < 4; ++j) g[j] = std::ldexp(f[j], -exponent);
  return std::ldexp(hermite(a, g, true), exponent);
}

double hermite(const CubicAxis& a, const double f[4], bool monotone) noexcept {
  const int lo = a.has_left ? 0 : 1, hi = a.has_right ? 3 : 2;
  if (monotone) {
    double magnitude = 0.0;
    for (int j = lo; j <= hi; ++j) magnitude = std::max(magnitude, std::abs(f[j]));
    if (magnitude > kScaleAbove && magnitude <= std::numeric_limits<double>::max())
      return hermite_scaled(a, f, magnitude);
  }
  double m0 = 0.0, m1 = 0.0;
  for (int j = lo; j <= hi; ++j) {
    m0 += a.c0[j] * f[j];
    m1 += a.c1[j] * f[j];
  }
  if (monotone) {
    const double delta = (f[2] - f[1]) * a.inv_width[1];
    const double left = a.has_left ? (f[1] - f[0]) * a.inv_width[0] : delta;
    const double right = a.has_right ? (f[3] - f[2]) * a.inv_width[2] : delta;
    m0 = limit_slope(m0, left, delta);
    m1 = limit_slope(m1, delta, right);
  }
  return a.h00 * f[1] + a.h01 * f[2] + a.h10 * m0 + a.h11 * m1;
}

// The cubic Hermite of one axis as weights on the 2-4 consecutive nodes of its stencil and, with
// `derivative`, the weights of its derivative (the basis differentiated; left unset otherwise:
// the value query does not pay for them), into `out`.
void cubic_weights(const CubicAxis& a, bool derivative, StencilWeights& out) noexcept {
  const int lo = a.has_left ? 0 : 1, hi = a.has_right ? 3 : 2;
  out.first = static_cast<int>(a.idx[lo]);
  out.count = hi - lo + 1;
  for (int j = lo; j <= hi; ++j)
    out.w[j - lo] = (j == 1 ? a.h00 : 0.0) + (j == 2 ? a.h01 : 0.0) + a.h10 * a.c0[j] + a.h11 * a.c1[j];
  if (!derivative) return;
  // d/dx of the basis: d h00 / dt / h, d h01 / dt / h; the slope basis's width cancels.
  const double t = a.t, t2 = t * t, h = a.x[2] - a.x[1];
  const double d00 = (6 * t2 - 6 * t) / h, d01 = (-6 * t2 + 6 * t) / h;
  const double d10 = 3 * t2 - 4 * t + 1, d11 = 3 * t2 - 2 * t;
  for (int j = lo; j <= hi; ++j)
    out.dw[j - lo] = (j == 1 ? d00 : 0.0) + (j == 2 ? d01 : 0.0) + d10 * a.c0[j] + d11 * a.c1[j];
}

// Tensor cubic Hermite contracted one dimension at a time (cubic_contract in weighted_sum.hpp),
// every record of the stencil read once. With `grad`, the same pass also gives each value's
// derivatives (grad[s - slot_begin], per unit of each block variable): the values are the same
// bytes either way. NV values of T per record, fixed at compile time as in the linear kernel.
template <int NV, bool kAvx2, class T>
void cubic_kernel(const Block& b, const Axis* axes, const AxisLoc* loc, int slot_begin, int slot_end,
                  Contact* contact, BlockGradient* grad) noexcept {
  const int n_dims = b.n_dims;
  std::size_t base = 0, cell = 0;
  StencilWeights sw[kMaxDims];
  for (int d = 0; d < n_dims; ++d) {
    const AxisLoc& l = loc[b.var[d]];
    cubic_weights(make_cubic_axis(axes[b.var[d]], l, b.stride[d]), grad != nullptr, sw[d]);
    base += static_cast<std::size_t>(sw[d].first) * b.stride[d];
    cell += static_cast<std::size_t>(l.i) * b.stride[d];
  }
  for (int s = slot_begin; s < slot_end; ++s) {
    RecordPtr data = b.data.data() + static_cast<std::size_t>(s) * b.slot_size;
    Contact& c = contact[s - slot_begin];
    if (grad) {
      double sums[(kMaxDims + 1) * NV];
      if constexpr (kAvx2) cubic_sum_avx2<true, NV, T>(data + base, sw, b.stride, n_dims, sums);
      else cubic_sum_sse2<true, NV, T>(data + base, sw, b.stride, n_dims, sums);
      BlockGradient& g = grad[s - slot_begin];
      for (int k = 0; k < NV; ++k) {
        g.value[k] = sums[k];
        for (double& x : g.d[k]) x = 0.0;
        for (int d = 0; d < n_dims; ++d) g.d[k][b.var[d]] = sums[(1 + d) * NV + k];
      }
      store_values(b, sums, c);
    } else {
      double values[NV];
      if constexpr (kAvx2) cubic_sum_avx2<false, NV, T>(data + base, sw, b.stride, n_dims, values);
      else cubic_sum_sse2<false, NV, T>(data + base, sw, b.stride, n_dims, values);
      store_values(b, values, c);
    }
    store_status(b, data + cell, c);
  }
}

// The values of every slot interpolated together at one stencil node (lane k: slot k / n_values,
// value k % n_values).
using ValueLanes = double[kMaxSlots * kMaxSlotValues];

// Where a stencil line's values come from: the results of the inner axes' lines (lanes), or, on
// the last axis, one slot's records themselves (no copy; floats converted to double, exact). Each
// gives a value, a pair or a quad of consecutive lanes k.. at stencil node j.
struct LaneSource {
  const ValueLanes* sub;
  double at(int j, int k) const noexcept { return sub[j][k]; }
  __attribute__((always_inline)) V2 pair(int j, int k) const noexcept {
    V2 v;
    std::memcpy(&v, &sub[j][k], sizeof v);
    return v;
  }
  RAILTAB_AVX2 V4 quad(int j, int k) const noexcept {
    V4 v;
    std::memcpy(&v, &sub[j][k], sizeof v);
    return v;
  }
};
template <class T>
struct RecordSource {
  RecordPtr rec[4];  // the stencil nodes' records (absent ones unused)
  double at(int j, int k) const noexcept { return record_value<T>(rec[j], k); }
  __attribute__((always_inline)) V2 pair(int j, int k) const noexcept { return load2<T>(rec[j] + k * sizeof(T)); }
  RAILTAB_AVX2 V4 quad(int j, int k) const noexcept { return load4<T>(rec[j] + k * sizeof(T)); }
};

// The lane primitives of the vector Hermite passes over lanes of V (scalar type S, I the integer
// vector of V's width, MASK all bits of an S but the sign): splat, abs, std::min and std::max
// lane by lane, and limit_slope with the scalar function's own comparisons. One definition for
// the double lanes (RAILTAB_HERMITE_LANES) and the float lanes (RAILTAB_HERMITE_FLOAT).
#define RAILTAB_LANE_LIMITER(V, I, S, MASK, ATTRIBUTES)                                                                         \
  static ATTRIBUTES V splat(S x) noexcept { return V{} + x; }                                                                   \
  static ATTRIBUTES V abs(V x) noexcept { return reinterpret_cast<V>(reinterpret_cast<I>(x) & (I{} + MASK)); }                  \
  static ATTRIBUTES V min(V a, V b) noexcept { return b < a ? b : a; }  /* std::min */                                          \
  static ATTRIBUTES V max(V a, V b) noexcept { return a < b ? b : a; }  /* std::max */                                          \
  /* limit_slope, lane by lane. */                                                                                              \
  static ATTRIBUTES V limit(V m, V s_left, V s_right) noexcept {                                                                \
    const V zero = splat(S(0));                                                                                                 \
    const V sign = s_right > S(0) ? splat(S(1)) : splat(S(-1));                                                                 \
    const V bound = S(3) * min(abs(s_left), abs(s_right));                                                                      \
    const V limited = sign * min(max(m * sign, zero), bound);                                                                   \
    return s_left * s_right <= S(0) ? zero : limited;                                                                           \
  }

// hermite(a, f, true) over lanes of V (two or four doubles), with each select written on the
// scalar function's own comparison and the same operations in the same order, so every lane gets
// the scalar function's bytes (GCC leaves the scalar loop unvectorised, its selects staying
// branches, and the limiter is most of a monotone cubic query). Defined twice, for each
// instruction set (GCC inlines AVX2 code only into AVX2 functions); LOAD: the source's reader.
#define RAILTAB_HERMITE_LANES(NAME, V, LOAD, ATTRIBUTES)                                                                        \
struct NAME {                                                                                                                   \
  typedef long long I __attribute__((vector_size(sizeof(V))));                                                                  \
  RAILTAB_LANE_LIMITER(V, I, double, 0x7fffffffffffffffLL, ATTRIBUTES)                                                          \
  /* Lanes [k, k + lanes of V) of the stencil's nodes lo .. hi into out; returns the largest |f| */                             \
  /* seen per lane (hermite's scaling test). */                                                                                 \
  template <bool kLeft, bool kRight, class Source>                                                                              \
  static ATTRIBUTES V step(const CubicAxis& a, const Source& src, int k, double* out) noexcept {                                \
    constexpr int lo = kLeft ? 0 : 1, hi = kRight ? 3 : 2;                                                                      \
    V f[4];                                                                                                                     \
    for (int j = lo; j <= hi; ++j) f[j] = src.LOAD(j, k);                                                                       \
    V largest = abs(f[lo]);                                                                                                     \
    for (int j = lo + 1; j <= hi; ++j) largest = max(largest, abs(f[j]));                                                       \
    V m0 = splat(0.0), m1 = splat(0.0);                                                                                         \
    for (int j = lo; j <= hi; ++j) {                                                                                            \
      m0 += a.c0[j] * f[j];                                                                                                     \
      m1 += a.c1[j] * f[j];                                                                                                     \
    }                                                                                                                           \
    const V delta = (f[2] - f[1]) * a.inv_width[1];                                                                             \
    const V left = kLeft ? (f[1] - f[0]) * a.inv_width[0] : delta;                                                              \
    const V right = kRight ? (f[3] - f[2]) * a.inv_width[2] : delta;                                                            \
    m0 = limit(m0, left, delta);                                                                                                \
    m1 = limit(m1, delta, right);                                                                                               \
    const V v = a.h00 * f[1] + a.h01 * f[2] + a.h10 * m0 + a.h11 * m1;                                                          \
    std::memcpy(&out[k], &v, sizeof v);                                                                                         \
    return largest;                                                                                                             \
  }                                                                                                                             \
};
RAILTAB_HERMITE_LANES(HermitePairs, V2, pair, __attribute__((always_inline)))
RAILTAB_HERMITE_LANES(HermiteQuads, V4, quad, RAILTAB_AVX2)
#undef RAILTAB_HERMITE_LANES

// Lanes k .. nv-1 one at a time through the scalar function. Returns the largest |value| of the
// stencil (NaN ignored, as hermite's own std::max does): above kScaleAbove the caller redoes the
// lanes with the scalar function, which scales them.
template <bool kLeft, bool kRight, class Source>
__attribute__((always_inline)) inline double hermite_tail(const CubicAxis& a, const Source& src, int k, int nv,
                                                          double largest, double* out) noexcept {
  for (; k < nv; ++k) {
    double f[4] = {0.0, src.at(1, k), src.at(2, k), 0.0};
    if (kLeft) f[0] = src.at(0, k);
    if (kRight) f[3] = src.at(3, k);
    for (int j = kLeft ? 0 : 1; j <= (kRight ? 3 : 2); ++j) largest = std::max(largest, std::abs(f[j]));
    out[k] = hermite(a, f, true);
  }
  return largest;
}
// Every lane of nv: pairs, then an odd last lane.
template <bool kLeft, bool kRight, class Source>
double limited_hermite_sse2(const CubicAxis& a, const Source& src, int nv, double* out) noexcept {
  using H = HermitePairs;
  V2 largest = H::splat(0.0);
  int k = 0;
  for (; k + 2 <= nv; k += 2) largest = H::max(largest, H::step<kLeft, kRight>(a, src, k, out));
  return hermite_tail<kLeft, kRight>(a, src, k, nv, std::max(largest[0], largest[1]), out);
}
// The same in quads, then a pair (AVX2, chosen at load: Block::monotone); the same bytes.
template <bool kLeft, bool kRight, class Source>
__attribute__((target("avx2"))) double limited_hermite_avx2(const CubicAxis& a, const Source& src, int nv,
                                                             double* out) noexcept {
  V4 largest = HermiteQuads::splat(0.0);
  int k = 0;
  for (; k + 4 <= nv; k += 4) largest = HermiteQuads::max(largest, HermiteQuads::step<kLeft, kRight>(a, src, k, out));
  double m = std::max(std::max(largest[0], largest[1]), std::max(largest[2], largest[3]));
  if (k + 2 <= nv) {
    const V2 pair = HermitePairs::step<kLeft, kRight>(a, src, k, out);
    m = std::max(m, std::max(pair[0], pair[1]));
    k += 2;
  }
  return hermite_tail<kLeft, kRight>(a, src, k, nv, m, out);
}

// One stencil line along axis a: lanes [0, nv) of its 2-4 nodes (src) into out.
template <bool kAvx2, class Source>
void limited_hermite_lanes(const CubicAxis& a, const Source& src, int nv, double* out) noexcept {
  auto run = [&](auto left, auto right) {
    if constexpr (kAvx2) return limited_hermite_avx2<left(), right()>(a, src, nv, out);
    else return limited_hermite_sse2<left(), right()>(a, src, nv, out);
  };
  using Yes = std::true_type;
  using No = std::false_type;
  double magnitude = 0.0;
  if (a.has_left && a.has_right) magnitude = run(Yes{}, Yes{});
  else if (a.has_left) magnitude = run(Yes{}, No{});
  else if (a.has_right) magnitude = run(No{}, Yes{});
  else magnitude = run(No{}, No{});
  if (magnitude <= kScaleAbove) return;
  // Rare (huge or infinite values): every lane again through the scalar function, which scales
  // the lanes that need it.
  for (int k = 0; k < nv; ++k) {
    double f[4] = {0.0, src.at(1, k), src.at(2, k), 0.0};
    if (a.has_left) f[0] = src.at(0, k);
    if (a.has_right) f[3] = src.at(3, k);
    out[k] = hermite(a, f, true);
  }
}

// ---- The last two axes of float records in float arithmetic: a record is one vector of 8 floats
// (AVX2; two of 4 with SSE2, or one of 4 for records of at most 4 values), its status lanes
// cleared; each of the last axis' stencil lines runs hermite(a, f, true) on it lane by lane with
// the axis' constants rounded to float, and the axis before it combines those lines' vectors the
// same way, in registers: one limiter for all values of a record instead of a quad and a pair of
// doubles, and no round trip through memory between the two axes (they hold 240 of the 256
// stencil lines of the default table's creep block per slot). Both instruction sets do the same
// float operations per lane in the same order (no FMA), so the same bits. Against the double
// limiter on the same records: within a few float roundings of the stencil's largest |value|
// (test StoragePrecision.FloatRecordsGiveTheBytesOfDoubleRecordsOrStayWithinTheFloatArithmeticBound).
struct FloatAxis {
  bool usable;  // every constant at most kFloatBelow (else the double limiter)
  bool has_left, has_right;
  std::size_t off[4];  // bytes from the stencil's node 0 to node j (absent nodes unused)
  float c0[4], c1[4], h00, h01, h10, h11, inv_width[3];
};
// Constants and values up to 2^60: the limiter's products and sums stay below 2^123, far from
// float's 2^128; a stencil with a larger |value| (or a NaN) is redone in double.
constexpr float kFloatBelow = 0x1p60f;

FloatAxis float_axis(const CubicAxis& a) noexcept {
  FloatAxis f;
  double largest = std::max({std::abs(a.h00), std::abs(a.h01), std::abs(a.h10), std::abs(a.h11)});
  for (int j = 0; j < 4; ++j) {
    f.c0[j] = static_cast<float>(a.c0[j]);
    f.c1[j] = static_cast<float>(a.c1[j]);
    f.off[j] = a.idx[j] * a.stride;
    largest = std::max({largest, std::abs(a.c0[j]), std::abs(a.c1[j])});
  }
  for (int j = 0; j < 3; ++j) {
    f.inv_width[j] = static_cast<float>(a.inv_width[j]);
    largest = std::max(largest, std::abs(a.inv_width[j]));
  }
  f.h00 = static_cast<float>(a.h00), f.h01 = static_cast<float>(a.h01);
  f.h10 = static_cast<float>(a.h10), f.h11 = static_cast<float>(a.h11);
  f.has_left = a.has_left, f.has_right = a.has_right;
  f.usable = largest <= kFloatBelow;  // false for a NaN too
  return f;
}

// hermite(a, f, true) in float lanes of V, with each select written on the scalar function's own
// comparison. The absent nodes' f are zero and their weights zero. Defined twice, for each
// instruction set.
#define RAILTAB_HERMITE_FLOAT(NAME, V, I, ATTRIBUTES)                                                                           \
struct NAME {                                                                                                                   \
  RAILTAB_LANE_LIMITER(V, I, float, 0x7fffffff, ATTRIBUTES)                                                                     \
  static ATTRIBUTES V hermite(const FloatAxis& a, const V* f) noexcept {                                                        \
    V m0 = splat(0.0f), m1 = splat(0.0f);                                                                                       \
    for (int j = 0; j < 4; ++j) {                                                                                               \
      m0 += a.c0[j] * f[j];                                                                                                     \
      m1 += a.c1[j] * f[j];                                                                                                     \
    }                                                                                                                           \
    const V delta = (f[2] - f[1]) * a.inv_width[1];                                                                             \
    const V left = a.has_left ? (f[1] - f[0]) * a.inv_width[0] : delta;                                                         \
    const V right = a.has_right ? (f[3] - f[2]) * a.inv_width[2] : delta;                                                       \
    m0 = limit(m0, left, delta);                                                                                                \
    m1 = limit(m1, delta, right);                                                                                               \
    return a.h00 * f[1] + a.h01 * f[2] + a.h10 * m0 + a.h11 * m1;                                                               \
  }                                                                                                                             \
  /* Lanes [at, at + lanes of V) of one slot's stencil over the last two axes (p, then q; node 0 */                             \
  /* of both at `base`) into out; largest gets the largest |value| per lane read or made. */                                    \
  static ATTRIBUTES V two_axes(const FloatAxis& p, const FloatAxis& q, RecordPtr base, int at, int nv,                          \
                               V& largest) noexcept {                                                                           \
    constexpr int kLanes = sizeof(V) / sizeof(float);                                                                           \
    I lane;                                                                                                                     \
    for (int k = 0; k < kLanes; ++k) lane[k] = at + k;                                                                          \
    const I keep = lane < nv;                                                                                                   \
    base += static_cast<std::size_t>(at) * sizeof(float);                                                                       \
    largest = splat(0.0f);                                                                                                      \
    V g[4];                                                                                                                     \
    for (int j = 0; j < 4; ++j) {                                                                                               \
      g[j] = splat(0.0f);                                                                                                       \
      if ((j == 0 && !p.has_left) || (j == 3 && !p.has_right)) continue;                                                        \
      V f[4];                                                                                                                   \
      for (int i = 0; i < 4; ++i) {                                                                                             \
        f[i] = splat(0.0f);                                                                                                     \
        if ((i == 0 && !q.has_left) || (i == 3 && !q.has_right)) continue;                                                      \
        I x;                                                                                                                    \
        std::memcpy(&x, base + p.off[j] + q.off[i], sizeof x);                                                                  \
        f[i] = reinterpret_cast<V>(x & keep);                                                                                   \
        largest = max(largest, abs(f[i]));                                                                                      \
      }                                                                                                                         \
      g[j] = hermite(q, f);                                                                                                     \
      largest = max(largest, abs(g[j]));                                                                                        \
    }                                                                                                                           \
    return hermite(p, g);                                                                                                       \
  }                                                                                                                             \
};
RAILTAB_HERMITE_FLOAT(FloatHermite4, F4, I4, __attribute__((always_inline)))
RAILTAB_HERMITE_FLOAT(FloatHermite8, F8, I8, RAILTAB_AVX2)
#undef RAILTAB_HERMITE_FLOAT
#undef RAILTAB_LANE_LIMITER

// True when every lane of `largest` is at most kFloatBelow (a NaN lane fails).
template <class V>
__attribute__((always_inline)) inline bool float_lanes_in_range(const V& largest) noexcept {
  constexpr int kLanes = sizeof(V) / sizeof(float);
  bool ok = true;
  for (int k = 0; k < kLanes; ++k) ok &= largest[k] <= kFloatBelow;
  return ok;
}
template <class V>
__attribute__((always_inline)) inline void store_float_lanes(const V& v, int at, int nv, double* out) noexcept {
  constexpr int kLanes = sizeof(V) / sizeof(float);
  for (int k = 0; k < kLanes && at + k < nv; ++k) out[at + k] = static_cast<double>(v[k]);
}

// One slot's stencil over the last two axes (p, q) of float records with nv values (16 bytes, or
// a multiple of 32 when nv > 4: records.hpp), node 0 at base, in float into out[0, nv). False,
// writing nothing, when a value is beyond 2^60 or NaN (the caller takes the double limiter).
__attribute__((always_inline)) inline bool float_two_axes_sse2(const FloatAxis& p, const FloatAxis& q, RecordPtr base,
                                                               int nv, double* out) noexcept {
  F4 largest;
  const F4 v0 = FloatHermite4::two_axes(p, q, base, 0, nv, largest);
  if (!float_lanes_in_range(largest)) return false;
  if (nv > 4) {
    const F4 v1 = FloatHermite4::two_axes(p, q, base, 4, nv, largest);
    if (!float_lanes_in_range(largest)) return false;
    store_float_lanes(v1, 4, nv, out);
  }
  store_float_lanes(v0, 0, nv, out);
  return true;
}
__attribute__((target("avx2"))) bool float_two_axes_avx2(const FloatAxis& p, const FloatAxis& q, RecordPtr base,
                                                         int nv, double* out) noexcept {
  if (nv <= 4) return float_two_axes_sse2(p, q, base, nv, out);  // a 16-byte record: one vector of 4
  F8 largest;
  const F8 v = FloatHermite8::two_axes(p, q, base, 0, nv, largest);
  if (!float_lanes_in_range(largest)) return false;
  store_float_lanes(v, 0, nv, out);
  return true;
}

struct MonotoneContext {
  RecordPtr data;           // record of node 0 of the first slot's grid
  int n_slots;              // slots interpolated together, grids slot_size bytes apart
  std::size_t slot_size;    // bytes per slot grid
  int n_dims;               // D
  int n_values;             // interpolated values per record
  const CubicAxis* axes;    // per dimension
  const FloatAxis* last2;   // float records: the last two axes' constants in float (both usable: the float limiter)
};

// Successive 1-D limited Hermite passes: interpolate the sub-grid of each stencil node along the
// remaining axes, then combine the (up to) 4 results along this axis. All slots in one walk
// (out[slot * n_values + k]), so the stencil recursion runs once per query; the last axis reads
// each slot's records in place. Depth <= 6, at most 2.3 KB of stack per level.
template <bool kAvx2, class T>
void monotone_recurse(const MonotoneContext& c, int d, std::size_t offset, double* out) noexcept {
  if (d == c.n_dims) {  // a table without axes: the one record
    for (int s = 0; s < c.n_slots; ++s)
      for (int k = 0; k < c.n_values; ++k)
        out[s * c.n_values + k] = record_value<T>(c.data + static_cast<std::size_t>(s) * c.slot_size + offset, k);
    return;
  }
  const CubicAxis& a = c.axes[d];
  const int lo = a.has_left ? 0 : 1, hi = a.has_right ? 3 : 2;
  if (d + 1 == c.n_dims) {  // the last axis: each slot's stencil records
    for (int s = 0; s < c.n_slots; ++s) {
      RecordSource<T> src;
      for (int j = lo; j <= hi; ++j)
        src.rec[j] = c.data + static_cast<std::size_t>(s) * c.slot_size + offset + a.idx[j] * a.stride;
      limited_hermite_lanes<kAvx2>(a, src, c.n_values, out + s * c.n_values);
    }
    return;
  }
  if constexpr (sizeof(T) == sizeof(float)) {
    if (d + 2 == c.n_dims && c.last2[0].usable && c.last2[1].usable) {  // the last two axes in float, every slot
      bool ok = true;
      for (int s = 0; s < c.n_slots && ok; ++s) {
        RecordPtr base = c.data + static_cast<std::size_t>(s) * c.slot_size + offset;
        double* o = out + s * c.n_values;
        if constexpr (kAvx2) ok = float_two_axes_avx2(c.last2[0], c.last2[1], base, c.n_values, o);
        else ok = float_two_axes_sse2(c.last2[0], c.last2[1], base, c.n_values, o);
      }
      if (ok) return;  // else (rare: huge or NaN values) every slot again in double
    }
  }
  ValueLanes sub[4];
  for (int j = lo; j <= hi; ++j) monotone_recurse<kAvx2, T>(c, d + 1, offset + a.idx[j] * a.stride, sub[j]);
  limited_hermite_lanes<kAvx2>(a, LaneSource{sub}, c.n_values * c.n_slots, out);
}

template <bool kAvx2, class T>
void monotone_kernel(const Block& block, const Axis* axes, const AxisLoc* loc, int slot_begin, int slot_end,
                     Contact* contact, BlockGradient*) noexcept {
  CubicAxis ax[kMaxDims];
  std::size_t cell = 0;
  for (int d = 0; d < block.n_dims; ++d) {
    ax[d] = make_cubic_axis(axes[block.var[d]], loc[block.var[d]], block.stride[d]);
    set_secant_widths(ax[d]);
    cell += static_cast<std::size_t>(loc[block.var[d]].i) * block.stride[d];
  }
  const int n = slot_end - slot_begin;
  RecordPtr first = block.data.data() + static_cast<std::size_t>(slot_begin) * block.slot_size;
  FloatAxis last2[2];
  last2[0].usable = last2[1].usable = false;
  if (sizeof(T) == sizeof(float) && block.n_dims >= 2)
    for (int k = 0; k < 2; ++k) last2[k] = float_axis(ax[block.n_dims - 2 + k]);
  const MonotoneContext c{first, n, block.slot_size, block.n_dims, block.n_values, ax, last2};
  ValueLanes values;
  monotone_recurse<kAvx2, T>(c, 0, 0, values);
  for (int s = 0; s < n; ++s) {
    store_values(block, values + s * block.n_values, contact[s]);
    store_status(block, first + static_cast<std::size_t>(s) * block.slot_size + cell, contact[s]);
  }
}

}  // namespace

template <bool kAvx2, class T, int... V>
constexpr std::array<CubicKernel, sizeof...(V)> cubic_table(
    std::integer_sequence<int, V...>) noexcept {
  return {&cubic_kernel<V + 1, kAvx2, T>...};
}
template <bool kAvx2, class T>
constexpr auto kCubic = cubic_table<kAvx2, T>(std::make_integer_sequence<int, kMaxValues<T>>());

CubicKernel cubic_kernel_for(int n_values, int value_bytes) noexcept {
  const bool avx2 = use_avx2();
  if (value_bytes == sizeof(float)) return (avx2 ? kCubic<true, float> : kCubic<false, float>)[n_values - 1];
  return (avx2 ? kCubic<true, double> : kCubic<false, double>)[n_values - 1];
}

CubicKernel monotone_kernel_for(int value_bytes) noexcept {
  const bool avx2 = use_avx2();
  if (value_bytes == sizeof(float)) return avx2 ? &monotone_kernel<true, float> : &monotone_kernel<false, float>;
  return avx2 ? &monotone_kernel<true, double> : &monotone_kernel<false, double>;
}

}  // namespace railtab::lookup::detail
