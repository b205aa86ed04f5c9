// Per-thread state of the half-space solvers: the FFT buffers and the kernel spectra of the grid
// and material they were last made for (recomputed only when those change), and scratch fields.
// One Workspace per thread; the solvers never share one.
#pragma once

#include <vector>

#include "core/material.hpp"
#include "halfspace/fft_convolution.hpp"
#include "halfspace/grid.hpp"

namespace railtab::halfspace {

// The steady-rolling kernel of the tangential problem at element offset (di, dj):
// B(di, dj) = (A(di dx, dj dy) - A((di + 1) dx, dj dy)) / dx, A the tangential influence
// coefficients; the slip of element I is w_I + sum_J B(I - J) p_J (tangential_solver.hpp).
struct SteadyKernel {
  std::vector<double> xx, xy, yy;  // (2 wx + 1) * (2 wy + 1) values of the near window
  int wx = 0, wy = 0;              // window half-widths in elements
  double at(const std::vector<double>& k, int di, int dj) const {
    return k[(dj + wy) * (2 * wx + 1) + (di + wx)];
  }
};

class Workspace {
 public:
  // Normal-kernel spectrum for this grid and material (cached).
  const Spectrum& normal_kernel(const Grid& grid, const Material& material);
  // Steady-rolling kernel spectra (xx, xy, yy) and its near window (cached).
  void tangential_kernels(const Grid& grid, const Material& material, int window,
                          const Spectrum** xx, const Spectrum** xy, const Spectrum** yy,
                          const SteadyKernel** near);

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
  Spectrum k_nn_, k_xx_, k_xy_, k_yy_;
  SteadyKernel near_;
};

}  // namespace railtab::halfspace
