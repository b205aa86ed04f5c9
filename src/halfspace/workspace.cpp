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

void Workspace::tangential_kernels(const Grid& grid, const Material& material, int window,
                                   const Spectrum** xx, const Spectrum** xy, const Spectrum** yy,
                                   const SteadyKernel** near) {
  const Key key = key_of(grid, material, window);
  fft.resize(grid.nx, grid.ny);
  if (!(key == tangential_key_) || k_xx_.empty()) {
    const double hx = 0.5 * grid.dx, hy = 0.5 * grid.dy, dx = grid.dx;
    auto steady = [&](int di, int dj) {
      const TangentialInfluence a = tangential_influence(di * dx, dj * grid.dy, hx, hy, material);
      const TangentialInfluence b =
          tangential_influence((di + 1) * dx, dj * grid.dy, hx, hy, material);
      return TangentialInfluence{(a.xx - b.xx) / dx, (a.xy - b.xy) / dx, (a.yy - b.yy) / dx};
    };
    fft.kernel_spectrum([&](int di, int dj) { return steady(di, dj).xx; }, k_xx_);
    fft.kernel_spectrum([&](int di, int dj) { return steady(di, dj).xy; }, k_xy_);
    fft.kernel_spectrum([&](int di, int dj) { return steady(di, dj).yy; }, k_yy_);
    near_.wx = near_.wy = window;
    const int n = (2 * window + 1) * (2 * window + 1);
    near_.xx.assign(n, 0.0);
    near_.xy.assign(n, 0.0);
    near_.yy.assign(n, 0.0);
    for (int dj = -window; dj <= window; ++dj)
      for (int di = -window; di <= window; ++di) {
        const TangentialInfluence b = steady(di, dj);
        const int k = (dj + window) * (2 * window + 1) + (di + window);
        near_.xx[k] = b.xx;
        near_.xy[k] = b.xy;
        near_.yy[k] = b.yy;
      }
    tangential_key_ = key;
  }
  *xx = &k_xx_;
  *xy = &k_xy_;
  *yy = &k_yy_;
  *near = &near_;
}

}  // namespace railtab::halfspace
