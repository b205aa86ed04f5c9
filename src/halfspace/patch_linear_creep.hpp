// SPDX-License-Identifier: Apache-2.0
// Linear creep coefficients of the exact half-space model (tangential/linear_creep.hpp): its own
// steady rolling solution on a solved patch in full adhesion, i.e. at vanishing creepage; and the
// equivalent ellipse of such a patch.
#pragma once

#include <array>

#include "halfspace/grid.hpp"
#include "halfspace/normal_solver.hpp"
#include "halfspace/tangential_solver.hpp"
#include "halfspace/workspace.hpp"
#include "tangential/linear_creep.hpp"

namespace railtab::halfspace {

// Slopes of (fx, fy, mz at the grid origin) against (xi, eta, phi) of steady rolling on `grid`
// under `pressure` (a normal solution on that grid) with friction kFullAdhesionFriction: no element
// slips, the forces are linear in the creepage. Throws railtab::Error when a solve does not converge.
// track_sign: the patch's (wheel_rail.hpp): creepages and forces in the contact frame.
LinearCreep patch_linear_creep(const Grid& grid, const std::vector<double>& pressure, const Material& material,
                               const TangentialSolverOptions& options, Workspace& workspace,
                               double track_sign = 1.0);

// Equivalent ellipse {a, b} [m] of a normal solution on a grid: equal area (the solution's
// area_estimate, the contact edge placed inside the boundary elements) and equal lateral extent (the
// rows of loaded elements, p > 0, the outermost counting half, as area_estimate does):
// b = (hi - lo + 1/2) dy / 2, a = area / (pi b). {0, 0} without a loaded element.
std::array<double, 2> patch_equivalent_ellipse(const Grid& grid, const NormalSolution& normal);

}  // namespace railtab::halfspace
