// SPDX-License-Identifier: Apache-2.0
// The multilinear interpolator's AVX2 kernels for every (dimension count, value count, value
// type): interpolate_linear.hpp.
#include "interpolate_linear.hpp"

namespace railtab::lookup::detail {

LinearKernel linear_kernel_avx2(int n_dims, int n_values, int value_bytes) noexcept {
  return linear_kernel_in_table<true>(n_dims, n_values, value_bytes);
}

}  // namespace railtab::lookup::detail
