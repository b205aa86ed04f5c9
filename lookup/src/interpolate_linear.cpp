// SPDX-License-Identifier: Apache-2.0
// The multilinear interpolator's SSE2 kernels for every (dimension count, value count, value
// type), the choice between them and the AVX2 ones (interpolate_linear_avx2.cpp), and use_avx2.
#include <cstdlib>

#include "interpolate.hpp"
#include "interpolate_linear.hpp"

namespace railtab::lookup::detail {

bool use_avx2() noexcept {
  if (const char* env = std::getenv("RAILTAB_LOOKUP_NO_AVX2"); env && *env && *env != '0')
    return false;
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
}

// The kernel of the table for this CPU (AVX2 or SSE2) and value type (value_bytes 4: float).
LinearKernel linear_kernel_for(int n_dims, int n_values, int value_bytes) noexcept {
  if (use_avx2()) return linear_kernel_avx2(n_dims, n_values, value_bytes);
  return linear_kernel_in_table<false>(n_dims, n_values, value_bytes);
}

}  // namespace railtab::lookup::detail
