// SPDX-License-Identifier: Apache-2.0
#include "halfspace/workspace.hpp"

#include "halfspace/influence.hpp"

namespace railtab::halfspace {

const Spectrum& Workspace::normal_kernel(const Grid& grid, const Material& material) {
  const Key key = key_of(grid, material, 0);
  fft.resize(grid.nx, grid.ny);
  if (!(key == normal_key_) || k_nn_.empty()) {
    const double hx = 0.5 * grid.dx, hy = 0.5 * grid.dy;
    fft.kernel_spectrum(
        [&](int di, int dj) { return normal_influence(di * grid.dx, dj * grid.dy, hx, hy, material); },
        k_nn_);
    normal_key_ = key;
  }
  return k_nn_;
}

TangentialKernels Workspace::tangential_kernels(const Grid& grid, const Material& material,
                                                int window) {
  const Key key = key_of(grid, material, window);
  fft.resize(grid.nx, grid.ny);
  if (!(key == tangential_key_) || k_bxx_.empty()) {
    const double hx = 0.5 * grid.dx, hy = 0.5 * grid.dy, dx = grid.dx;
    auto a = [&](int di, int dj) {
      const TangentialInfluence c = tangential_influence(di * dx, dj * grid.dy, hx, hy, material);
      return TangentialInfluence{c.xx / dx, c.xy / dx, c.yy / dx};
    };
    fft.kernel_spectrum([&](int di, int dj) { return a(di, dj).xx - a(di + 1, dj).xx; }, k_bxx_);
    fft.kernel_spectrum([&](int di, int dj) { return a(di, dj).xy - a(di + 1, dj).xy; }, k_bxy_);
    fft.kernel_spectrum([&](int di, int dj) { return a(di, dj).yy - a(di + 1, dj).yy; }, k_byy_);
    near_.w = near_b_.w = window;
    const int n = (2 * window + 1) * (2 * window + 1);
    for (NearKernel* nk : {&near_, &near_b_}) {
      nk->xx.assign(n, 0.0);
      nk->xy.assign(n, 0.0);
      nk->yy.assign(n, 0.0);
    }
    for (int dj = -window; dj <= window; ++dj)
      for (int di = -window; di <= window; ++di) {
        const TangentialInfluence c = a(di, dj);
        const int k = (dj + window) * (2 * window + 1) + (di + window);
        near_.xx[k] = c.xx;
        near_.xy[k] = c.xy;
        near_.yy[k] = c.yy;
        const TangentialInfluence t1 = a(di + 1, dj);
        near_b_.xx[k] = c.xx - t1.xx;
        near_b_.xy[k] = c.xy - t1.xy;
        near_b_.yy[k] = c.yy - t1.yy;
      }
    tangential_key_ = key;
  }
  return {&k_bxx_, &k_bxy_, &k_byy_, &near_, &near_b_};
}

}  // namespace railtab::halfspace
