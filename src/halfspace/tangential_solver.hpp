// SPDX-License-Identifier: Apache-2.0
// Steady rolling with Coulomb friction on a grid (Kalker's exact theory, discretised as in
// CONTACT): traction p = (px, py) on the WHEEL per element, slip of the wheel relative to the rail
// per rolling distance
//   s_I = w_I + (u_I - u_I+) / dx,   u = A p (tangential influence coefficients, influence.hpp),
// I+ the point dx ahead of element I (the material moves towards -x through the patch, so what is
// at I now was at I+ one step earlier): the rolling-direction difference of the displacements.
// w is the rigid slip of docs/conventions.md: w_x = xi - phi y, w_y = eta + phi x, (x, y) from the
// patch's reference point (the grid origin). Conditions per element in contact (g = mu p_n):
//   adhesion |p| <= g, s = 0;   slip |p| = g, p = -g s / |s|.
// Outside the contact p = 0. Normal and tangential problems decouple (same material).
//
// Solver: the steady state is the fixed point of a local update Phi: with the exact slip
// s = w + B p of the current tractions (B the steady kernel applied by FFT, fft_convolution.hpp),
// every element takes the traction that satisfies its own conditions with the others frozen
// (the local problem of Kalker's ConvexGS/SteadyGS with the diagonal of B; in slip the magnitude
// equation is solved by Newton in |s|). Plain repetition of Phi (Jacobi, or Gauss-Seidel marching
// from the leading edge) diverges on fine grids: B is not symmetric and its off-diagonal tail
// feeds errors down the rolling direction. The fixed point is found instead by Anderson mixing
// (Walker & Ni, SIAM J. Numer. Anal. 49 (2011); a GMRES-like secant method on the history of
// the last `anderson_depth` updates), which converges on every case of the tests, at full slip
// and large spin too. A fixed point satisfies the discrete conditions exactly, whatever the
// inner update: converged means sum |Phi(p) - p| <= tolerance * sum |p|.
// The update couples each element with the one ahead of it (upwind, the default): the elements
// of a row are updated in order from the leading edge, and each element's slip includes the
// traction change just made at the element ahead, through B's coefficient there. B is the
// rolling-direction difference of the displacements, so that coefficient is about minus the
// diagonal: the Jacobi update leaves the dominant coupling a full step behind, and errors travel
// down the row one element per step (18-407 Anderson steps on blocks A and C); with it, a sweep
// carries them through the row at once (13-44 steps on the same cases, the same forces to within
// the tolerance: a fixed point satisfies the element conditions whatever the coupling).
// Optional (not the default): Gauss-Seidel coupling of all neighbours within `window` elements
// in the update, with the steady kernel B or (steady_sweep = false) with A / dx (the transient
// step with the previous displacements frozen, a convex problem); window = 1 does not converge
// at small creepage (1500 steps, TangentialSolver.SignsAsFastsim).
#pragma once

#include <vector>

#include "core/material.hpp"
#include "core/status.hpp"
#include "halfspace/grid.hpp"
#include "halfspace/workspace.hpp"

namespace railtab::halfspace {

struct TangentialSolverOptions {
  double tolerance = 1e-7;        // sum |Phi(p) - p| relative to sum |p| at the fixed point [-]
  int max_steps = 1500;           // updates Phi (accelerated) [-]
  int anderson_depth = 20;        // history of the Anderson mixing (40: fewer steps, each dearer) [-]
  double mixing = 0.5;            // Anderson's relaxation of the update (damping) [-]
  double inner_tolerance = 1e-9;  // Gauss-Seidel only: sum |dp| per sweep relative to sum |p| [-]
  int max_inner_sweeps = 1;       // sweeps per update [-]
  bool steady_sweep = true;       // couple with B (else A / dx, see above)
  bool restart_on_slip_change = false;  // clear the history when the slip set changes [-]
  int window = 0;                 // sweeps couple elements this far apart (-1: all) [elements]
  bool upwind = true;             // window 0: couple each element with the one ahead (above)
};

struct RollingCreepage {
  double xi = 0.0;   // [-]
  double eta = 0.0;  // [-]
  double phi = 0.0;  // [rad/m]
};

struct TangentialSolution {
  std::vector<double> traction_x, traction_y;  // on the wheel per element [Pa]; a solve with
                                               //   the same grid size starts from them
  std::vector<double> slip_x, slip_y;          // per rolling distance, wheel minus rail [-]
  std::vector<unsigned char> state;            // 0 exterior, 1 adhesion, 2 slip
  double fx = 0.0, fy = 0.0;                   // forces on the wheel [N]
  double mz = 0.0;                             // moment about n at the grid origin [N m]
  double slip_area = 0.0;                      // elements in slip times the element area [m2]
  double frictional_work = 0.0;                // -sum p . s dA, per rolling distance [J/m]
  int sweeps = 0;                              // rolling steps taken
  StatusBits status = 0;  // kConverged / kNotConverged; kFullSlip when every loaded element
                          //   slips; kInvalidInput for unusable input
};

// pressure: the normal solution on the same grid [Pa]; mu >= 0.
void solve_tangential(const Grid& grid, const std::vector<double>& pressure,
                      const RollingCreepage& creepage, double mu, const Material& material,
                      const TangentialSolverOptions& options, Workspace& workspace,
                      TangentialSolution& solution);

}  // namespace railtab::halfspace
