// SPDX-License-Identifier: Apache-2.0
// Linear creep coefficients: the slopes of a contact model's creep forces on the wheel (fx, fy, mz)
// against the creepages (xi, eta, phi) at zero creepage, in the signs of docs/conventions.md
// ("Creepages and creep forces": d fx / d xi = -G c^2 C11 < 0 on an ellipse). A model is measured
// in full adhesion (friction so large that no element slips): its forces are then linear in the
// creepage, and central differences give its slopes at vanishing creepage exactly, whatever the
// step. Beside them Kalker's linear theory on the patch's equivalent ellipse, the reference every
// linear vehicle model uses.
#pragma once

#include <array>
#include <functional>

#include "core/material.hpp"
#include "normal/normal_model.hpp"
#include "tangential/fastsim.hpp"
#include "tangential/fastsim_contact.hpp"

namespace railtab {

// slope[f][c] = d f / d c at zero creepage; f: 0 fx, 1 fy, 2 mz (on the wheel); c: 0 xi, 1 eta,
// 2 phi. Units: fx, fy per xi or eta [N], per phi [N per rad/m = N m]; mz per xi or eta [N m], per
// phi [N m2 per rad].
struct LinearCreep {
  double slope[3][3] = {};
};

// The creep forces (fx [N], fy [N], mz [N m]) of a model at a creepage.
using CreepForces = std::function<std::array<double, 3>(const Creepage&)>;

// Central differences of `forces` at +-step[c] about zero creepage, one creepage at a time
// (6 evaluations). step: xi, eta [-], phi [rad/m], each > 0.
LinearCreep linear_creep(const CreepForces& forces, const std::array<double, 3>& step);

// Kalker's linear theory on an ellipse with semi-axes a (rolling) and b (lateral) [m]:
// fx_xi = -G c^2 C11, fy_eta = -G c^2 C22, fy_phi = -G c^3 C23, mz_eta = +G c^3 C23 (Kalker's
// reciprocity), c^2 = a b; mz_phi (C33) is left 0: no trusted table of C33 is held
// (tangential/kalker_coefficients.hpp). The cross terms of a symmetric patch are 0.
LinearCreep kalker_linear_creep(double a, double b, const Material& material);

// The equivalent ellipse of a patch [m]: its own semi-axes where the model gives them (Hertz,
// Kik-Piotrowski), else the equal-area ellipse of its lateral extent: b = half the extent of its
// loaded strips (x_lead > x_trail), a = area / (pi b). {0, 0} for a patch without area.
std::array<double, 2> equivalent_ellipse(const ContactPatch& patch);

// FASTSIM (fastsim_contact: the elliptic one on a Hertz patch without strips, strip-wise
// otherwise) on one loaded patch, in full adhesion.
LinearCreep fastsim_linear_creep(const WheelContactGeometry& geometry, const ContactPatch& patch,
                                 const CreepConditions& conditions, const Material& material,
                                 const FastsimOptions& options, FastsimWorkspace& workspace);

// The friction coefficient of "full adhesion" above (no element reaches mu p at the steps used).
inline constexpr double kFullAdhesionFriction = 1e4;

}  // namespace railtab
