// SPDX-License-Identifier: Apache-2.0
// The exact model's linear creep coefficients on a solved patch (patch_linear_creep.hpp).
#include "halfspace/patch_linear_creep.hpp"

#include <algorithm>
#include <numbers>

#include "core/check.hpp"

namespace railtab::halfspace {

LinearCreep patch_linear_creep(const Grid& grid, const std::vector<double>& pressure, const Material& material,
                               const TangentialSolverOptions& options, Workspace& workspace, double track_sign) {
  TangentialSolution solution;
  const CreepForces forces = [&](const Creepage& c) -> std::array<double, 3> {
    solve_tangential(grid, pressure, RollingCreepage{c.xi, c.eta, c.phi}, kFullAdhesionFriction, material, options,
                     workspace, solution);
    RAILTAB_CHECK(solution.status & status::kConverged,
                  "patch_linear_creep: steady rolling did not converge at creepage ({}, {}, {})", c.xi, c.eta, c.phi);
    return {solution.fx, solution.fy, solution.mz};
  };
  // In the patch's axes (the same warm-started solves on both wheels), then in the contact frame:
  // fy, mz, eta and phi change sign with track_sign.
  LinearCreep out = linear_creep(forces, {1e-6, 1e-6, 1e-4});
  const double sign[3] = {1.0, track_sign, track_sign};
  for (int f = 0; f < 3; ++f)
    for (int q = 0; q < 3; ++q) out.slope[f][q] *= sign[f] * sign[q];
  return out;
}

std::array<double, 2> patch_equivalent_ellipse(const Grid& grid, const NormalSolution& normal) {
  int lo = grid.ny, hi = -1;
  for (int j = 0; j < grid.ny; ++j) {
    for (int i = 0; i < grid.nx; ++i) {
      if (!(normal.pressure[static_cast<std::size_t>(grid.index(i, j))] > 0.0)) continue;
      lo = std::min(lo, j);
      hi = std::max(hi, j);
    }
  }
  if (hi < 0 || !(normal.area_estimate > 0.0)) return {0.0, 0.0};
  const double b = 0.5 * (hi - lo + 0.5) * grid.dy;
  return {normal.area_estimate / (std::numbers::pi * b), b};
}

}  // namespace railtab::halfspace
