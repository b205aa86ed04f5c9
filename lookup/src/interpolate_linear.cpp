// SPDX-License-Identifier: Apache-2.0
// The multilinear interpolator over one block's records (interpolate.hpp), its kernels for every
// (dimension count, value count, instruction set, value type), and the AVX2 choice.
#include <array>
#include <cstddef>
#include <cstdlib>
#include <utility>

#include "interpolate.hpp"
#include "interpolate_common.hpp"
#include "weighted_sum.hpp"

namespace railtab::lookup::detail {
namespace {

// Multilinear over the cell's 2^D corners, the fractions once for all slots; the status is the
// cell's, one read (query layout). kAvx2: the AVX2 corner sum (same results, chosen at load); T:
// the records' value type.
template <int D, int NV, bool kAvx2, class T>
void linear_kernel(const Block& b, const AxisLoc* loc, int slot_begin, int slot_end,
                   Contact* contact) noexcept {
  double t[D > 0 ? D : 1], u[D > 0 ? D : 1];
  std::size_t base = 0;
#pragma GCC unroll 8
  for (int d = 0; d < D; ++d) {
    const AxisLoc& l = loc[b.var[d]];
    base += static_cast<std::size_t>(l.i) * b.stride[d];
    t[d] = l.t;
    u[d] = 1.0 - l.t;
  }
  const auto sum = kAvx2 ? &corner_sum_avx2<D, NV, T> : &corner_sum_sse2<D, NV, T>;
  for (int s = slot_begin; s < slot_end; ++s) {
    RecordPtr data = b.data.data() + static_cast<std::size_t>(s) * b.slot_size + base;
    Contact& c = contact[s - slot_begin];
    if (b.first_output >= 0) {
      sum(data, t, u, b.stride, c.value + b.first_output);
    } else {
      double values[NV];
      sum(data, t, u, b.stride, values);
      store_values(b, values, c);
    }
    store_status(b, data, c);
  }
}

}  // namespace

// Kernels for every (D, value count) pair, instruction set and value type (T), looked up once
// at load.
template <int D, bool kAvx2, class T, int... V>
constexpr std::array<LinearKernel, sizeof...(V)> kernels_for_d(
    std::integer_sequence<int, V...>) noexcept {
  return {&linear_kernel<D, V + 1, kAvx2, T>...};
}
template <bool kAvx2, class T, int... D>
constexpr std::array<std::array<LinearKernel, kMaxValues<T>>, sizeof...(D)> kernel_table(
    std::integer_sequence<int, D...>) noexcept {
  return {kernels_for_d<D, kAvx2, T>(std::make_integer_sequence<int, kMaxValues<T>>())...};
}
template <bool kAvx2, class T>
constexpr auto kLinear = kernel_table<kAvx2, T>(std::make_integer_sequence<int, kMaxDims + 1>());

bool use_avx2() noexcept {
  if (const char* env = std::getenv("RAILTAB_LOOKUP_NO_AVX2"); env && *env && *env != '0')
    return false;
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
}

// The kernel of the table for this CPU (AVX2 or SSE2) and value type (value_bytes 4: float).
LinearKernel linear_kernel_for(int n_dims, int n_values, int value_bytes) noexcept {
  const bool avx2 = use_avx2();
  if (value_bytes == sizeof(float))
    return (avx2 ? kLinear<true, float> : kLinear<false, float>)[n_dims][n_values - 1];
  return (avx2 ? kLinear<true, double> : kLinear<false, double>)[n_dims][n_values - 1];
}

}  // namespace railtab::lookup::detail
