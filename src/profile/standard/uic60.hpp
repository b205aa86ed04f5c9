// SPDX-License-Identifier: Apache-2.0
// The UIC60 / 60E1 rail head (EN 13674-1) from its arcs, in the rail profile frame of
// docs/conventions.md: u [m] from the head centreline, z [m] up, z = 0 at the top (z <= 0).
#pragma once

#include "profile/curves/profile.hpp"

namespace railtab {

// Nominal 60E1 head geometry [m]. The arcs are tangent to each other; the construction below
// reproduces the Manchester benchmark rail to 3e-5 mm (FACTS 5.2 centres to their 4-5 digits).
struct Uic60Geometry {
  double crown_radius = 0.300;     // R300 crown, centred on the centreline [m]
  double shoulder_radius = 0.080;  // R80, tangent to the crown [m]
  double corner_radius = 0.013;    // R13 gauge corner, tangent to R80 and to the side face [m]
  double crown_end = 0.0105;       // |u| where the crown meets R80 [m]
  double side_start = 0.036;       // |u| where R13 meets the side face (head width 72 mm) [m]
  double side_inclination = 0.05;  // side face 1:20, widening downwards [-]
  double side_depth = 0.030;       // the profile's side faces end this far below the top [m]
};

// The UIC60 head, name "UIC60", symmetric about u = 0, range |u| <= the u where the side face
// reaches side_depth below the top (36.787 mm for the default 30 mm). Allocation-free eval.
ProfilePtr make_uic60_profile();

}  // namespace railtab
