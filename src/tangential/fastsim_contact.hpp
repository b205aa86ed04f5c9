// SPDX-License-Identifier: Apache-2.0
// FASTSIM on any contact patch of the normal layer, so callers (eval, the table sweep, benchmarks)
// need not know which normal model made it: a Hertz patch without strips is solved by the
// classical elliptic FASTSIM on its own ellipse, every other patch strip-wise.
#pragma once

#include "tangential/fastsim.hpp"

namespace railtab {

struct CreepConditions {
  double friction = 0.3;  // Coulomb coefficient mu [-]
  double speed = 20.0;    // rolling speed V [m/s]
  int ellipse_strips = 40;  // lateral strips of the elliptic FASTSIM (Hertz patches) [-]
};

// Creep forces on the wheel for one loaded patch of `geometry`. The element results stay in
// `workspace` (for archard_wear). An unloaded patch returns zeros with kLiftOff.
FastsimResult fastsim_contact(const WheelContactGeometry& geometry, const ContactPatch& patch,
                              const Creepage& creepage, const CreepConditions& conditions,
                              const Material& material, const FastsimOptions& options,
                              FastsimWorkspace& workspace);

}  // namespace railtab
