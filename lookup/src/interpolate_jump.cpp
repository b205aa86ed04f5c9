// SPDX-License-Identifier: Apache-2.0
// The one-sided sums of a jump cell (interpolate.hpp, jump_kernel_for): the kernels for every
// (creepage dimension count, value count, instruction set, value type).
#include <array>
#include <utility>

#include "interpolate.hpp"
#include "interpolate_common.hpp"
#include "weighted_sum.hpp"

namespace railtab::lookup::detail {

template <int NI, bool kAvx2, class T, int... V>
constexpr std::array<JumpKernel, sizeof...(V)> jump_kernels_for(
    std::integer_sequence<int, V...>) noexcept {
  if constexpr (kAvx2) return {&jump_sum_avx2<NI, V + 1, T>...};
  else return {&jump_sum_sse2<NI, V + 1, T>...};
}
template <bool kAvx2, class T, int... NI>
constexpr std::array<std::array<JumpKernel, kMaxValues<T>>, sizeof...(NI)> jump_table(
    std::integer_sequence<int, NI...>) noexcept {
  return {jump_kernels_for<NI, kAvx2, T>(std::make_integer_sequence<int, kMaxValues<T>>())...};
}
template <bool kAvx2, class T>
constexpr auto kJump = jump_table<kAvx2, T>(std::make_integer_sequence<int, kMaxJumpInner + 1>());

JumpKernel jump_kernel_for(int n_inner, int n_values, int value_bytes) noexcept {
  const bool avx2 = use_avx2();
  if (value_bytes == sizeof(float))
    return (avx2 ? kJump<true, float> : kJump<false, float>)[n_inner][n_values - 1];
  return (avx2 ? kJump<true, double> : kJump<false, double>)[n_inner][n_values - 1];
}

}  // namespace railtab::lookup::detail
