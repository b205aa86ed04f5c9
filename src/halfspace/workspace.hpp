// SPDX-License-Identifier: Apache-2.0
// Per-thread state of the half-space solvers: the FFT buffers and the kernel spectra of the grid
// and material they were last made for (recomputed only when those change), and scratch fields.
// One Workspace per thread; the solvers never share one.
#pragma once

#include <vector>

#include "core/material.hpp"
#include "halfspace/fft_convolution.hpp"
#include "halfspace/grid.hpp"

namespace railtab::halfspace {

// Kernels of the tangential problem (tangential_solver.hpp), A the tangential influence
// coefficients at element offset (di, dj) = field minus source:
//  - steady B(di, dj) = (A(di dx, dj dy) - A((di + 1) dx, dj dy)) / dx: the slip of element I is
//    w_I + sum_J B(I - J) p_J;
//  - A / dx: the change of the slip when tractions change with the previous displacements frozen
//    (only in the near window, for the optional Gauss-Seidel coupling of the solver).
struct NearKernel {  // a kernel on the window |di| <= w, |dj| <= w
  std::vector<double> xx, xy, yy;
  int w = 0;
  double at(const std::vector<double>& k, int di, int dj) const {
    return k[(dj + w) * (2 * w + 1) + (di + w)];
  }
};
struct TangentialKernels {
  const Spectrum *bxx, *bxy, *byy;  // steady kernel spectra
  const NearKernel* near;    // A / dx
  const NearKernel* near_b;  // B
};

class Workspace {
 public:
  // Normal-kernel spectrum for this grid and material (cached).
  const Spectrum& normal_kernel(const Grid& grid, const Material& material);
  // Tangential kernel spectra and the near window of A / dx (cached).
  TangentialKernels tangential_kernels(const Grid& grid, const Material& material, int window);

  FftConvolver fft;
  Spectrum field_a, field_b;                 // spectra of the current fields
  std::vector<double> u, g, t, r, p_old;     // normal-solver scratch (grid size)
  std::vector<double> sx, sy;                // tangential-solver scratch (grid size)

 private:
  struct Key {
    int nx = 0, ny = 0;
    double dx = 0, dy = 0, E = 0, nu = 0;
    int window = 0;
    bool operator==(const Key&) const = default;
  };
  static Key key_of(const Grid& g, const Material& m, int window) {
    return {g.nx, g.ny, g.dx, g.dy, m.youngs_modulus, m.poisson_ratio, window};
  }
  Key normal_key_, tangential_key_;
  Spectrum k_nn_, k_bxx_, k_bxy_, k_byy_;
  NearKernel near_, near_b_;
};

}  // namespace railtab::halfspace
