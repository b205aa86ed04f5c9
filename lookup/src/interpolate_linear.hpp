// SPDX-License-Identifier: Apache-2.0
// The multilinear kernel (interpolate.hpp, linear_kernel_for) and its tables of instantiations,
// shared by interpolate_linear.cpp (the SSE2 kernels) and interpolate_linear_avx2.cpp (the AVX2
// kernels): two files, so that a parallel build compiles the two instruction sets on separate
// cores (together they were over 250 s of one core under ASan).
#pragma once

#include <array>
#include <cstddef>
#include <utility>

#include "interpolate.hpp"
#include "interpolate_common.hpp"
#include "weighted_sum.hpp"

namespace railtab::lookup::detail {

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

// The kernel of one instruction set for a block of this shape and value type (value_bytes 4:
// float); each instruction set's instantiations are made in its own file.
template <bool kAvx2>
LinearKernel linear_kernel_in_table(int n_dims, int n_values, int value_bytes) noexcept {
  if (value_bytes == sizeof(float)) return kLinear<kAvx2, float>[n_dims][n_values - 1];
  return kLinear<kAvx2, double>[n_dims][n_values - 1];
}
LinearKernel linear_kernel_avx2(int n_dims, int n_values, int value_bytes) noexcept;  // interpolate_linear_avx2.cpp

}  // namespace railtab::lookup::detail
