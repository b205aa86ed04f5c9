// SPDX-License-Identifier: Apache-2.0
// Per-thread FFT buffers and kernel spectra of the half-space solvers (workspace.hpp).
#include "halfspace/workspace.hpp"

#include "halfspace/influence.hpp"

namespace railtab::halfspace {

const Spectrum& Workspace::normal_kernel(const Grid& grid, const Material& material) {
  const Key key = key_of(grid, material, 0);
  fft.resize(grid.nx, grid.ny);
  if (!(key == normal_key_) || k_nn_.empty()) {
    const int ax = 2 * grid.nx - 1;
    normal_influence_table(grid.nx - 1, grid.ny - 1, grid.dx, grid.dy, material, k_nn_offsets_);
    fft.kernel_spectrum(
        [&](int di, int dj) {
          return k_nn_offsets_[static_cast<size_t>(dj + grid.ny - 1) * ax + (di + grid.nx - 1)];
        },
        k_nn_);
    normal_key_ = key;
  }
  return k_nn_;
}

TangentialKernels Workspace::tangential_kernels(const Grid& grid, const Material& material,
                                                int window) {
  const Key key = key_of(grid, material, window);
  ++uses_;
  for (auto& e : tangential_)
    if (e->key == key) {
      e->last_use = uses_;
      return {&e->k_bxx, &e->k_bxy, &e->k_byy, &e->near, &e->near_b, &e->fft};
    }
  // Not cached: a new entry, or the least recently used one replaced.
  TangentialEntry* entry = nullptr;
  if (static_cast<int>(tangential_.size()) < kTangentialCache) {
    tangential_.push_back(std::make_unique<TangentialEntry>());
    entry = tangential_.back().get();
  } else {
    entry = tangential_.front().get();
    for (auto& e : tangential_)
      if (e->last_use < entry->last_use) entry = e.get();
  }
  TangentialEntry& e = *entry;
  e.last_use = uses_;
  e.fft.resize(grid.nx, grid.ny);
  const double hx = 0.5 * grid.dx, hy = 0.5 * grid.dy, dx = grid.dx;
  auto a = [&](int di, int dj) {
    const TangentialInfluence c = tangential_influence(di * dx, dj * grid.dy, hx, hy, material);
    return TangentialInfluence{c.xx / dx, c.xy / dx, c.yy / dx};
  };
  // A / dx once per offset |di| <= nx, |dj| < ny (each is needed by three kernels, twice).
  const int ax = 2 * grid.nx + 1;
  std::vector<TangentialInfluence> table;
  tangential_influence_table(grid.nx, grid.ny - 1, grid.dx, grid.dy, material, table);
  for (TangentialInfluence& c : table) c = {c.xx / dx, c.xy / dx, c.yy / dx};
  auto at = [&](int di, int dj) -> const TangentialInfluence& {
    return table[static_cast<size_t>(dj + grid.ny - 1) * ax + (di + grid.nx)];
  };
  e.fft.kernel_spectrum([&](int di, int dj) { return at(di, dj).xx - at(di + 1, dj).xx; }, e.k_bxx);
  e.fft.kernel_spectrum([&](int di, int dj) { return at(di, dj).xy - at(di + 1, dj).xy; }, e.k_bxy);
  e.fft.kernel_spectrum([&](int di, int dj) { return at(di, dj).yy - at(di + 1, dj).yy; }, e.k_byy);
  e.near.w = e.near_b.w = window;
  const int n = (2 * window + 1) * (2 * window + 1);
  for (NearKernel* nk : {&e.near, &e.near_b}) {
    nk->xx.assign(n, 0.0);
    nk->xy.assign(n, 0.0);
    nk->yy.assign(n, 0.0);
  }
  for (int dj = -window; dj <= window; ++dj)
    for (int di = -window; di <= window; ++di) {
      const TangentialInfluence c = a(di, dj);
      const int k = (dj + window) * (2 * window + 1) + (di + window);
      e.near.xx[k] = c.xx;
      e.near.xy[k] = c.xy;
      e.near.yy[k] = c.yy;
      const TangentialInfluence t1 = a(di + 1, dj);
      e.near_b.xx[k] = c.xx - t1.xx;
      e.near_b.xy[k] = c.xy - t1.xy;
      e.near_b.yy[k] = c.yy - t1.yy;
    }
  e.key = key;
  return {&e.k_bxx, &e.k_bxy, &e.k_byy, &e.near, &e.near_b, &e.fft};
}

}  // namespace railtab::halfspace
