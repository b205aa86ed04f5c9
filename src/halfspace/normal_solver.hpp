// SPDX-License-Identifier: Apache-2.0
// Normal contact of two elastic half-spaces of the same material on a grid (potential contact
// area): find the pressure p >= 0 and the approach delta with
//   deformed gap  e = h + A p - delta >= 0,   p e = 0,
// h the undeformed gap [m] per element (any reference: delta is measured from it), A the normal
// influence coefficients (influence.hpp), applied by FFT (fft_convolution.hpp).
//
// Method: bound-constrained conjugate gradients, Polonsky & Keer, Wear 231 (1999) 206-219, as
// Vollebregt (JOTA 162 (2014) 977-1004) uses it in CONTACT: CG on the contact set with
// projection onto p >= 0 and restart when elements re-enter. Load control (the normal force is
// prescribed): the mean of the deformed gap over the contact set is removed from the residual and
// the pressure is rescaled to the load after each step; delta is that mean. Approach control: delta
// is prescribed. Stop when dA sum|p - p_old| <= tolerance * N.
#pragma once

#include <vector>

#include "core/material.hpp"
#include "core/status.hpp"
#include "halfspace/grid.hpp"
#include "halfspace/workspace.hpp"

namespace railtab::halfspace {

struct NormalSolverOptions {
  double tolerance = 1e-9;   // relative pressure change per iteration at convergence [-]
  int max_iterations = 800;  // [-]
};

struct NormalSolution {
  std::vector<double> pressure;  // per element [Pa]; a solve with the same grid size starts from it
  double normal_force = 0.0;     // [N]
  double approach = 0.0;         // delta, relative to the reference of h [m]
  double area = 0.0;             // elements with p > 0 times the element area (CONTACT's
                                 //   definition; overestimates by O(element size)) [m2]
  double area_estimate = 0.0;    // the same with the contact edge placed inside the boundary
                                 //   elements (p^2 extrapolated to zero, rows and columns averaged):
                                 //   the estimate of the continuum area [m2]
  double max_pressure = 0.0;     // [Pa]
  int iterations = 0;
  StatusBits status = 0;         // kConverged or kNotConverged; kAreaTooSmall when an element on
                                 // the grid's edge carries pressure; kLiftOff when p = 0
                                 // everywhere; kInvalidInput for unusable input (outputs 0)
};

// Load control: the normal force [N] is prescribed (> 0).
void solve_normal_for_force(const Grid& grid, const std::vector<double>& gap, double normal_force,
                            const Material& material, const NormalSolverOptions& options,
                            Workspace& workspace, NormalSolution& solution);

// Approach control: delta [m] is prescribed.
void solve_normal_for_approach(const Grid& grid, const std::vector<double>& gap, double approach,
                               const Material& material, const NormalSolverOptions& options,
                               Workspace& workspace, NormalSolution& solution);

}  // namespace railtab::halfspace
