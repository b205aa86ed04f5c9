// SPDX-License-Identifier: Apache-2.0
// Per-thread state of the half-space solvers: the FFT buffers and the kernel spectra of the grid
// and material they were last made for (recomputed only when those change), and scratch fields.
// One Workspace per thread; the solvers never share one.
#pragma once

#include <memory>
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
  FftConvolver* fft = nullptr;  // sized for the grid of these spectra
};

class Workspace {
 public:
  // Normal-kernel spectrum for this grid and material (cached).
  const Spectrum& normal_kernel(const Grid& grid, const Material& material);
  // The same kernel in real space, valid after normal_kernel(): the influence at element offset
  // (di, dj), |di| < nx, |dj| < ny, at index (dj + ny - 1) * (2 nx - 1) + di + nx - 1 (for
  // updates of a few elements, cheaper than a convolution).
  const std::vector<double>& normal_kernel_offsets() const { return k_nn_offsets_; }
  // Tangential kernel spectra and the near window of A / dx, with an FFT sized for them (cached
  // for the last few grid sizes: the contact box changes by an element or so between the rounds
  // of a coupled solve and along a sweep, and a kernel costs as much as many solver steps).
  TangentialKernels tangential_kernels(const Grid& grid, const Material& material, int window);

  FftConvolver fft;  // the normal problem's (sized by normal_kernel)
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
  struct TangentialEntry {
    Key key;
    FftConvolver fft;
    Spectrum k_bxx, k_bxy, k_byy;
    NearKernel near, near_b;
    unsigned long last_use = 0;
  };
  static constexpr int kTangentialCache = 4;
  Key normal_key_;
  Spectrum k_nn_;
  std::vector<double> k_nn_offsets_;
  std::vector<std::unique_ptr<TangentialEntry>> tangential_;
  unsigned long uses_ = 0;
};

}  // namespace railtab::halfspace
