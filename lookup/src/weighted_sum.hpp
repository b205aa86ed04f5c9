// SPDX-License-Identifier: Apache-2.0
// Weighted sums of records (a record = NV consecutive values of a node, query layout in
// table_data.hpp), the inner loop of every interpolator. Two instruction sets with the same
// arithmetic: SSE2 (the x86-64 baseline, pairs of doubles) and AVX2 (quads, chosen at load when
// the CPU has it, no FMA). Every lane does the same multiplies and adds in the same order in both,
// so the results are bit-identical whichever runs. The records hold T = double or float
// (records.hpp); floats are converted to double as they are loaded (exact), except in the
// multilinear corner sums (corner_sum_*), which sum float records in float.
#pragma once

#include <cstddef>
#include <cstring>

#include <immintrin.h>

#include "grid.hpp"
#include "records.hpp"

namespace railtab::lookup::detail {

typedef double V2 __attribute__((vector_size(16)));
typedef double V4 __attribute__((vector_size(32)));

// Two values of T at p as doubles.
template <class T>
__attribute__((always_inline)) inline V2 load2(RecordPtr p) noexcept {
  if constexpr (sizeof(T) == sizeof(double)) {
    V2 v;
    std::memcpy(&v, p, sizeof v);
    return v;
  } else {
    return _mm_cvtps_pd(_mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(p))));
  }
}

// Running sums of NV values of T in SSE2 registers: NV/2 pairs, then for an odd NV a half-filled
// one (the bytes after a record's last value hold statuses, which must not enter the arithmetic).
template <int NV, class T>
struct SumsSse2 {
  static constexpr int kPairs = (NV + 1) / 2;
  V2 acc[kPairs];

  __attribute__((always_inline)) void zero() noexcept {
#pragma GCC unroll 16
    for (int k = 0; k < kPairs; ++k) acc[k] = V2{0.0, 0.0};
  }
  __attribute__((always_inline)) void add(double weight, RecordPtr r) noexcept {
    const V2 w = V2{weight, weight};
#pragma GCC unroll 16
    for (int k = 0; k < NV / 2; ++k) acc[k] += w * load2<T>(r + 2 * k * sizeof(T));
    if constexpr (NV % 2 != 0) acc[kPairs - 1] += w * V2{record_value<T>(r, NV - 1), 0.0};
  }
  // acc += weight x another sum's acc (the cubic contraction's outer dimensions).
  __attribute__((always_inline)) void add_sums(double weight, const SumsSse2& s) noexcept {
    const V2 w = V2{weight, weight};
#pragma GCC unroll 16
    for (int k = 0; k < kPairs; ++k) acc[k] += w * s.acc[k];
  }
  __attribute__((always_inline)) void store(double* out) const noexcept {
    double all[2 * kPairs];
    std::memcpy(all, acc, sizeof all);
    std::memcpy(out, all, NV * sizeof(double));
  }
};

#define RAILTAB_AVX2 __attribute__((target("avx2"), always_inline))

// Four values of T at p as doubles.
template <class T>
RAILTAB_AVX2 inline V4 load4(RecordPtr p) noexcept {
  if constexpr (sizeof(T) == sizeof(double)) {
    V4 v;
    std::memcpy(&v, p, sizeof v);
    return v;
  } else {
    return _mm256_cvtps_pd(_mm_loadu_ps(reinterpret_cast<const float*>(p)));
  }
}

// The same in AVX2 registers: NV/4 quads, then a pair and a half-filled pair as needed.
template <int NV, class T>
struct SumsAvx2 {
  static constexpr int kQuads = NV / 4;
  static constexpr bool kPair = NV % 4 >= 2;
  static constexpr bool kSingle = NV % 2 != 0;
  V4 quad[kQuads > 0 ? kQuads : 1];
  V2 pair, single;

  RAILTAB_AVX2 void zero() noexcept {
#pragma GCC unroll 8
    for (int k = 0; k < kQuads; ++k) quad[k] = V4{0.0, 0.0, 0.0, 0.0};
    pair = single = V2{0.0, 0.0};
  }
  RAILTAB_AVX2 void add(double weight, RecordPtr r) noexcept {
    const V4 w4 = V4{weight, weight, weight, weight};
    const V2 w2 = V2{weight, weight};
#pragma GCC unroll 8
    for (int k = 0; k < kQuads; ++k) quad[k] += w4 * load4<T>(r + 4 * k * sizeof(T));
    if constexpr (kPair) pair += w2 * load2<T>(r + 4 * kQuads * sizeof(T));
    if constexpr (kSingle) single += w2 * V2{record_value<T>(r, NV - 1), 0.0};
  }
  RAILTAB_AVX2 void add_sums(double weight, const SumsAvx2& s) noexcept {
    const V4 w4 = V4{weight, weight, weight, weight};
    const V2 w2 = V2{weight, weight};
#pragma GCC unroll 8
    for (int k = 0; k < kQuads; ++k) quad[k] += w4 * s.quad[k];
    if constexpr (kPair) pair += w2 * s.pair;
    if constexpr (kSingle) single += w2 * s.single;
  }
  RAILTAB_AVX2 void store(double* out) const noexcept {
    double all[4 * (kQuads > 0 ? kQuads : 1) + 4];
    std::memcpy(all, quad, kQuads * sizeof(V4));
    std::memcpy(all + 4 * kQuads, &pair, sizeof pair);
    std::memcpy(all + 4 * kQuads + (kPair ? 2 : 0), &single, sizeof single);
    std::memcpy(out, all, NV * sizeof(double));
  }
};

// The 2^D corners of a cell depth first: dimension d splits the weight w of the corners below
// it into w (1 - t_d) at the lower node and w t_d at the upper one (stride[d] bytes further), so only D
// partial weights and addresses are live at a time and nothing goes through memory. Defined
// twice, for each instruction set (GCC inlines AVX2 code only into AVX2 functions).
#define RAILTAB_WALK_CORNERS(NAME, ATTRIBUTES)                                                   \
  template <int D, int d, class Sums>                                                           \
  ATTRIBUTES inline void NAME(RecordPtr p, double w, const double* t, const double* u,          \
                              const std::size_t* stride, Sums& sums) noexcept {                 \
    if constexpr (d == D) {                                                                     \
      sums.add(w, p);                                                                           \
    } else {                                                                                    \
      NAME<D, d + 1>(p, w * u[d], t, u, stride, sums);                                          \
      NAME<D, d + 1>(p + stride[d], w * t[d], t, u, stride, sums);                              \
    }                                                                                           \
  }
RAILTAB_WALK_CORNERS(walk_corners_sse2, __attribute__((always_inline)))
RAILTAB_WALK_CORNERS(walk_corners_avx2, RAILTAB_AVX2)
#undef RAILTAB_WALK_CORNERS


// ---- Float records in float arithmetic (the multilinear sums of corner_sum_*): a record of NV
// <= 8 floats is one vector of 4 (NV <= 4) or 8 lanes (two of 4 with SSE2), read whole (a float
// record is at least 16 bytes, or 32 when NV > 4: records.hpp), its status lanes cleared before
// any arithmetic (status bits read as floats are denormals, slow and meaningless). The cell is
// reduced one axis at a time, last axis first: lerp(a, b) = a + t (b - a), 2^D - 1 of them, in
// float. Both instruction sets do the same operations per lane in the same order (no FMA), so
// their results are the same bits. Against the double sum of the same records: within a few
// float roundings of the cell's largest |value| (D + 1 roundings of 2^-24 per level at most;
// test StoragePrecision.FloatArithmeticStaysWithinItsBound).
typedef float F4 __attribute__((vector_size(16)));
typedef int I4 __attribute__((vector_size(16)));

// The lanes of a float record as two halves of 4 (hi unused when NV <= 4).
template <int NV>
struct FloatLanes {
  static constexpr bool kTwo = NV > 4;
  F4 lo, hi;
};
template <int NV>
__attribute__((always_inline)) inline FloatLanes<NV> lerp(const FloatLanes<NV>& a, const FloatLanes<NV>& b,
                                                        F4 t) noexcept {
  FloatLanes<NV> r;
  r.lo = a.lo + t * (b.lo - a.lo);
  if constexpr (FloatLanes<NV>::kTwo) r.hi = a.hi + t * (b.hi - a.hi);
  return r;
}
// Lanes [first, first + 4) of NV values: all bits where the lane holds a value, 0 elsewhere.
template <int NV>
constexpr I4 value_mask(int first) noexcept {
  return I4{first + 0 < NV ? -1 : 0, first + 1 < NV ? -1 : 0, first + 2 < NV ? -1 : 0, first + 3 < NV ? -1 : 0};
}
template <int NV>
__attribute__((always_inline)) inline FloatLanes<NV> load_lanes(RecordPtr p) noexcept {
  FloatLanes<NV> r;
  I4 x;
  std::memcpy(&x, p, sizeof x);
  r.lo = reinterpret_cast<F4>(x & value_mask<NV>(0));
  if constexpr (FloatLanes<NV>::kTwo) {
    std::memcpy(&x, p + sizeof x, sizeof x);
    r.hi = reinterpret_cast<F4>(x & value_mask<NV>(4));
  }
  return r;
}
template <int D, int d, int NV>
__attribute__((always_inline)) inline FloatLanes<NV> lerp_walk_sse2(RecordPtr p, const F4* t,
                                                                  const std::size_t* stride) noexcept {
  if constexpr (d == D) {
    return load_lanes<NV>(p);
  } else {
    const FloatLanes<NV> a = lerp_walk_sse2<D, d + 1, NV>(p, t, stride);
    const FloatLanes<NV> b = lerp_walk_sse2<D, d + 1, NV>(p + stride[d], t, stride);
    return lerp(a, b, t[d]);
  }
}

// The AVX2 form: a record of 5-8 values in one vector of 8 (the same lanes as lo, hi above).
typedef float F8 __attribute__((vector_size(32)));
typedef int I8 __attribute__((vector_size(32)));
template <int NV>
RAILTAB_AVX2 inline F8 load8(RecordPtr p) noexcept {
  I8 x;
  std::memcpy(&x, p, sizeof x);
  const I4 lo = value_mask<NV>(0), hi = value_mask<NV>(4);
  return reinterpret_cast<F8>(x & I8{lo[0], lo[1], lo[2], lo[3], hi[0], hi[1], hi[2], hi[3]});
}
template <int D, int d, int NV>
RAILTAB_AVX2 inline F8 lerp_walk_avx2(RecordPtr p, const F8* t, const std::size_t* stride) noexcept {
  if constexpr (d == D) {
    return load8<NV>(p);
  } else {
    const F8 a = lerp_walk_avx2<D, d + 1, NV>(p, t, stride);
    const F8 b = lerp_walk_avx2<D, d + 1, NV>(p + stride[d], t, stride);
    return a + t[d] * (b - a);
  }
}

// Stores lanes 0 .. NV-1 as doubles.
template <int NV>
__attribute__((always_inline)) inline void store_lanes(const float* lanes, double* out) noexcept {
#pragma GCC unroll 8
  for (int k = 0; k < NV; ++k) out[k] = static_cast<double>(lanes[k]);
}

// The float form of corner_sum_* in vectors of 4 (SSE2; with AVX2 for records of at most 4 values).
template <int D, int NV>
__attribute__((always_inline)) inline void float_corner_sum_sse2(RecordPtr p, const double* t,
                                                                 const std::size_t* stride, double* out) noexcept {
  F4 tf[D];
#pragma GCC unroll 8
  for (int d = 0; d < D; ++d) {
    const float x = static_cast<float>(t[d]);
    tf[d] = F4{x, x, x, x};
  }
  const FloatLanes<NV> r = lerp_walk_sse2<D, 0, NV>(p, tf, stride);
  float lanes[8];
  std::memcpy(lanes, &r.lo, sizeof r.lo);
  if constexpr (FloatLanes<NV>::kTwo) std::memcpy(lanes + 4, &r.hi, sizeof r.hi);
  store_lanes<NV>(lanes, out);
}

// Multilinear sum over the cell's 2^D corners (corner 0 at `p`; t = fractions, u = 1 - t) into
// out[0..NV-1]: the corner walk unrolls completely and the sums stay in registers. Not inlined
// into the caller's slot loop on purpose: inlined, GCC hoists all 2^D corner addresses out of
// it and spills them. Double records: in double (weights by corner, one running sum); float
// records: in float, axis by axis (above).
template <int D, int NV, class T>
__attribute__((noinline)) void corner_sum_sse2(RecordPtr p, const double* t, const double* u,
                                               const std::size_t* stride, double* out) noexcept {
  if constexpr (sizeof(T) == sizeof(float) && D > 0) {
    (void)u;
    float_corner_sum_sse2<D, NV>(p, t, stride, out);
  } else {
    SumsSse2<NV, T> sums;
    sums.zero();
    walk_corners_sse2<D, 0>(p, 1.0, t, u, stride, sums);
    sums.store(out);
  }
}

template <int D, int NV, class T>
__attribute__((noinline, target("avx2"))) void corner_sum_avx2(RecordPtr p, const double* t,
                                                               const double* u,
                                                               const std::size_t* stride,
                                                               double* out) noexcept {
  if constexpr (sizeof(T) == sizeof(float) && D > 0 && NV > 4) {
    (void)u;
    F8 tf[D];
#pragma GCC unroll 8
    for (int d = 0; d < D; ++d) {
      const float x = static_cast<float>(t[d]);
      tf[d] = F8{x, x, x, x, x, x, x, x};
    }
    const F8 r = lerp_walk_avx2<D, 0, NV>(p, tf, stride);
    float lanes[8];
    std::memcpy(lanes, &r, sizeof r);
    store_lanes<NV>(lanes, out);
  } else if constexpr (sizeof(T) == sizeof(float) && D > 0) {  // one vector of 4: the SSE2 form
    (void)u;
    float_corner_sum_sse2<D, NV>(p, t, stride, out);
  } else {
    SumsAvx2<NV, T> sums;
    sums.zero();
    walk_corners_avx2<D, 0>(p, 1.0, t, u, stride, sums);
    sums.store(out);
  }
}

// One axis of a tensor cubic stencil as weights on its 2-4 consecutive nodes (interpolate_cubic.cpp,
// cubic_weights): value weights, and the weights of the derivative along the axis. No member
// initialisers: cubic_weights writes the entries the contraction reads (an array of these zeroed
// per block call was a rep stos of 560 bytes).
struct StencilWeights {
  int first;      // first stencil node (index on the axis)
  int count;      // stencil nodes (2..4)
  double w[4];    // value weights, [0, count)
  double dw[4];   // derivative weights [1 / axis unit], [0, count) (when asked for)
};

// The tensor cubic over a stencil, contracted one dimension at a time, depth first: dimension
// `dim` sums the results of dimensions dim+1 .. n-1 at each of its stencil nodes with the value
// weights. With kGrad it also sums their derivatives with the value weights and their values
// with the derivative weights (the derivative along dim). out[0] is the value; out[1 + e] the
// derivative along dimension dim + e. The value channel is the same arithmetic with or without
// kGrad, so the value query and the derivative query agree bit for bit. The last (unit-stride)
// dimension reads the records and the one before it folds them, in registers; the outer ones
// keep running sums per dimension. Defined twice, for each instruction set; n >= 1.
#define RAILTAB_CUBIC_CONTRACT(NAME, SUMS, INLINE)                                                 \
  template <bool kGrad, int NV, class T>                                                        \
  INLINE void NAME##_last(RecordPtr p, const StencilWeights& s, std::size_t stride,             \
                          SUMS<NV, T>* out) noexcept {                                          \
    SUMS<NV, T> v, dv; /* locals: the records' char pointer may alias *out */                   \
    v.zero();                                                                                   \
    if constexpr (kGrad) dv.zero();                                                             \
    for (int j = 0; j < s.count; ++j, p += stride) {                                            \
      v.add(s.w[j], p);                                                                         \
      if constexpr (kGrad) dv.add(s.dw[j], p);                                                  \
    }                                                                                           \
    out[0] = v;                                                                                 \
    if constexpr (kGrad) out[1] = dv;                                                           \
  }                                                                                             \
  template <bool kGrad, int NV, class T>                                                        \
  INLINE void NAME##_two(RecordPtr p, const StencilWeights* sw, const std::size_t* stride,      \
                         SUMS<NV, T>* out) noexcept {                                           \
    SUMS<NV, T> v, d0, d1;                                                                      \
    v.zero();                                                                                   \
    if constexpr (kGrad) d0.zero(), d1.zero();                                                  \
    for (int j = 0; j < sw[0].count; ++j, p += stride[0]) {                                     \
      SUMS<NV, T> sub[2];                                                                       \
      NAME##_last<kGrad>(p, sw[1], stride[1], sub);                                             \
      v.add_sums(sw[0].w[j], sub[0]);                                                           \
      if constexpr (kGrad) {                                                                    \
        d0.add_sums(sw[0].dw[j], sub[0]);                                                       \
        d1.add_sums(sw[0].w[j], sub[1]);                                                        \
      }                                                                                         \
    }                                                                                           \
    out[0] = v;                                                                                 \
    if constexpr (kGrad) out[1] = d0, out[2] = d1;                                              \
  }                                                                                             \
  /* acc (channels as out's, for dimension d) += the sums of dimension d + 1 at node j of d */  \
  template <bool kGrad, int NV, class T>                                                        \
  INLINE void NAME##_fold(SUMS<NV, T>* acc, const SUMS<NV, T>* sub, int sub_channels,           \
                          const StencilWeights& s, int j) noexcept {                            \
    acc[0].add_sums(s.w[j], sub[0]);                                                            \
    if constexpr (kGrad) {                                                                      \
      acc[1].add_sums(s.dw[j], sub[0]);                                                         \
      for (int e = 1; e < sub_channels; ++e) acc[1 + e].add_sums(s.w[j], sub[e]);               \
    }                                                                                           \
  }                                                                                             \
  /* Dimensions 0 .. n-3 by a mixed-radix counter (no calls): acc[d] holds dimension d's */     \
  /* running sums, folded into acc[d - 1] when its counter wraps. */                            \
  template <bool kGrad, int NV, class T>                                                        \
  INLINE void NAME(RecordPtr p, const StencilWeights* sw, const std::size_t* stride, int n,     \
                   SUMS<NV, T>* out) noexcept {                                                 \
    if (n == 1) return NAME##_last<kGrad>(p, sw[0], stride[0], out);                            \
    if (n == 2) return NAME##_two<kGrad>(p, sw, stride, out);                                   \
    const int outer = n - 2;                                                                    \
    auto channels = [n](int d) { return kGrad ? n - d + 1 : 1; };                               \
    SUMS<NV, T> acc[kNumVars][kGrad ? kNumVars + 1 : 1];                                        \
    int idx[kNumVars] = {};                                                                     \
    for (int d = 0; d < outer; ++d)                                                             \
      for (int c = 0; c < channels(d); ++c) acc[d][c].zero();                                   \
    std::size_t off = 0;                                                                        \
    for (;;) {                                                                                  \
      SUMS<NV, T> sub[3];                                                                       \
      NAME##_two<kGrad>(p + off, sw + outer, stride + outer, sub);                              \
      NAME##_fold<kGrad>(acc[outer - 1], sub, channels(outer), sw[outer - 1], idx[outer - 1]);  \
      for (int d = outer - 1;; --d) {                                                           \
        off += stride[d];                                                                       \
        if (++idx[d] < sw[d].count) break;                                                      \
        off -= static_cast<std::size_t>(idx[d]) * stride[d];                                    \
        idx[d] = 0;                                                                             \
        if (d == 0) {                                                                           \
          for (int c = 0; c < channels(0); ++c) out[c] = acc[0][c];                             \
          return;                                                                               \
        }                                                                                       \
        NAME##_fold<kGrad>(acc[d - 1], acc[d], channels(d), sw[d - 1], idx[d - 1]);             \
        for (int c = 0; c < channels(d); ++c) acc[d][c].zero();                                 \
      }                                                                                         \
    }                                                                                           \
  }
RAILTAB_CUBIC_CONTRACT(cubic_contract_sse2, SumsSse2, __attribute__((always_inline)) inline)
RAILTAB_CUBIC_CONTRACT(cubic_contract_avx2, SumsAvx2, RAILTAB_AVX2 inline)
#undef RAILTAB_CUBIC_CONTRACT

// The cubic contraction of one slot's stencil (first record at p, n >= 0 dimensions) into
// out[c * NV + k]: channel c (0 the value, 1 + dim the derivative along dim when kGrad), value k.
#define RAILTAB_CUBIC_SUM(NAME, SUMS, CONTRACT, ATTRIBUTES)                                     \
  template <bool kGrad, int NV, class T>                                                        \
  ATTRIBUTES void NAME(RecordPtr p, const StencilWeights* sw, const std::size_t* stride, int n, \
                       double* out) noexcept {                                                  \
    SUMS<NV, T> sums[kNumVars + 1];                                                             \
    if (n == 0) {                                                                               \
      sums[0].zero();                                                                           \
      sums[0].add(1.0, p);                                                                      \
    } else {                                                                                    \
      CONTRACT<kGrad>(p, sw, stride, n, sums);                                                  \
    }                                                                                           \
    for (int c = 0; c < (kGrad ? n + 1 : 1); ++c) sums[c].store(out + c * NV);                  \
  }
RAILTAB_CUBIC_SUM(cubic_sum_sse2, SumsSse2, cubic_contract_sse2, __attribute__((noinline)))
RAILTAB_CUBIC_SUM(cubic_sum_avx2, SumsAvx2, cubic_contract_avx2, __attribute__((noinline, target("avx2"))))
#undef RAILTAB_CUBIC_SUM

// One-sided sum of a jump cell (jump_side.cpp): per end (a grid node or a one-sided sample slice of
// the query's side, in the caller's order) with weight end_w[e], the 2^NI creepage corners
// (weights corner_w, offsets corner_off): every record weighted by end_w[e] x corner_w[c]. The
// same products and sums, in the same order, as the scalar loop it replaces, lane by lane.
#define RAILTAB_JUMP_SUM(NAME, SUMS, ATTRIBUTES)                                                  \
  template <int NI, int NV, class T>                                                            \
  ATTRIBUTES void NAME(const RecordPtr* end, const double* end_w, int n_ends,                  \
                       const double* corner_w, const std::size_t* corner_off,                  \
                       double* out) noexcept {                                                 \
    SUMS<NV, T> sums;                                                                           \
    sums.zero();                                                                                \
    for (int e = 0; e < n_ends; ++e) {                                                          \
      _Pragma("GCC unroll 8") for (int c = 0; c < (1 << NI); ++c)                               \
        sums.add(end_w[e] * corner_w[c], end[e] + corner_off[c]);                               \
    }                                                                                           \
    sums.store(out);                                                                            \
  }
RAILTAB_JUMP_SUM(jump_sum_sse2, SumsSse2, __attribute__((noinline)))
RAILTAB_JUMP_SUM(jump_sum_avx2, SumsAvx2, __attribute__((noinline, target("avx2"))))
#undef RAILTAB_JUMP_SUM

// ---- The multilinear interpolant's value and its derivatives with respect to the cell fractions
// (the derivative query: block_gradient.cpp, fast_path.cpp). One lane group of a record at a
// time: 4 values (AVX2), 2, or 1 (the other lane 0; a record's bytes after its last value hold
// statuses, which must not enter the arithmetic).
template <class T>
struct LoadQuad {
  std::size_t at;  // bytes from the record's start
  RAILTAB_AVX2 V4 operator()(RecordPtr r) const noexcept { return load4<T>(r + at); }
};
template <class T>
struct LoadPair {
  std::size_t at;
  __attribute__((always_inline)) V2 operator()(RecordPtr r) const noexcept { return load2<T>(r + at); }
};
template <class T>
struct LoadSingle {
  std::size_t at;
  __attribute__((always_inline)) V2 operator()(RecordPtr r) const noexcept {
    T x;
    std::memcpy(&x, r + at, sizeof x);
    return V2{static_cast<double>(x), 0.0};
  }
};

// The cell's 2^(N-D) corners below dimension D, depth first as walk_corners (corner at p, the
// upper node along dimension d stride[d] bytes further): v = the interpolated value over
// dimensions D .. N-1 at fractions t, g[r] = d v / d t[D + r]. Each dimension's pair (lo, hi) gives
// g = hi - lo and v = lo + t g; the derivatives found below are interpolated the same way. Only
// O(N^2) vectors are live at a time. No fused multiply-add: the same bits with either instruction set.
#define RAILTAB_GRADIENT_WALK(NAME, ATTRIBUTES)                                                  \
  template <int N, int D, class V, class Load>                                                  \
  ATTRIBUTES inline void NAME(RecordPtr p, const std::size_t* stride, const double* t,          \
                              const Load& load, V& v, V* g) noexcept {                          \
    if constexpr (D == N) {                                                                     \
      v = load(p);                                                                              \
    } else {                                                                                    \
      constexpr int kBelow = N - D - 1 > 0 ? N - D - 1 : 1;                                     \
      V lo, hi, glo[kBelow], ghi[kBelow];                                                       \
      NAME<N, D + 1>(p, stride, t, load, lo, glo);                                              \
      NAME<N, D + 1>(p + stride[D], stride, t, load, hi, ghi);                                  \
      const double tt = t[D];                                                                   \
      g[0] = hi - lo;                                                                           \
      v = lo + tt * g[0];                                                                       \
      for (int r = 0; r + 1 < N - D; ++r) g[r + 1] = glo[r] + tt * (ghi[r] - glo[r]);           \
    }                                                                                           \
  }
RAILTAB_GRADIENT_WALK(gradient_walk_sse2, __attribute__((always_inline)))
RAILTAB_GRADIENT_WALK(gradient_walk_avx2, RAILTAB_AVX2)
#undef RAILTAB_GRADIENT_WALK

// Stores one lane group's value and derivatives into value[k0 ..], dt[k0 ..][0 .. N-1].
template <int N, class V>
__attribute__((always_inline)) inline void store_gradient(const V& v, const V* g, int k0, int lanes, double* value,
                                                          double (*dt)[kNumVars]) noexcept {
  constexpr int kLanes = sizeof(V) / sizeof(double);
  double x[kLanes];
  std::memcpy(x, &v, sizeof x);
  for (int k = 0; k < lanes; ++k) value[k0 + k] = x[k];
  for (int dim = 0; dim < N; ++dim) {
    std::memcpy(x, &g[dim], sizeof x);
    for (int k = 0; k < lanes; ++k) dt[k0 + k][dim] = x[k];
  }
}

// Value and d value / d t[dim] of n_values values of T over the N-dimensional cell at p, every
// lane group walked once: value[k], dt[k][dim]. The SSE2 variant in pairs, the AVX2 one in quads
// first.
template <int N, class T>
__attribute__((always_inline)) inline void cell_gradient_sse2(RecordPtr p, const std::size_t* stride, const double* t,
                                                             int n_values, double* value, double (*dt)[kNumVars]) noexcept {
  int k = 0;
  for (; k + 2 <= n_values; k += 2) {
    V2 v, g[N > 0 ? N : 1];
    gradient_walk_sse2<N, 0>(p, stride, t, LoadPair<T>{k * sizeof(T)}, v, g);
    store_gradient<N>(v, g, k, 2, value, dt);
  }
  if (k < n_values) {
    V2 v, g[N > 0 ? N : 1];
    gradient_walk_sse2<N, 0>(p, stride, t, LoadSingle<T>{k * sizeof(T)}, v, g);
    store_gradient<N>(v, g, k, 1, value, dt);
  }
}
template <int N, class T>
RAILTAB_AVX2 inline void cell_gradient_avx2(RecordPtr p, const std::size_t* stride, const double* t, int n_values,
                                            double* value, double (*dt)[kNumVars]) noexcept {
  int k = 0;
  for (; k + 4 <= n_values; k += 4) {
    V4 v, g[N > 0 ? N : 1];
    gradient_walk_avx2<N, 0>(p, stride, t, LoadQuad<T>{k * sizeof(T)}, v, g);
    store_gradient<N>(v, g, k, 4, value, dt);
  }
  if (k + 2 <= n_values) {
    V2 v, g[N > 0 ? N : 1];
    gradient_walk_avx2<N, 0>(p, stride, t, LoadPair<T>{k * sizeof(T)}, v, g);
    store_gradient<N>(v, g, k, 2, value, dt);
    k += 2;
  }
  if (k < n_values) {
    V2 v, g[N > 0 ? N : 1];
    gradient_walk_avx2<N, 0>(p, stride, t, LoadSingle<T>{k * sizeof(T)}, v, g);
    store_gradient<N>(v, g, k, 1, value, dt);
  }
}

}  // namespace railtab::lookup::detail
