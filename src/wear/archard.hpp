// SPDX-License-Identifier: Apache-2.0
// Archard wear over a contact patch from the FASTSIM element results (Enblom & Berg procedure):
// per element the depth removed from a wheel point crossing it is k p |s| dx / H (Archard with the
// local pressure p, the local slip per rolling distance |s| and the element length dx; the time
// in the element dx/V cancels V, which enters only through k's slip-velocity dependence). Summed
// along a strip this is the depth per pass of the wheel material at that strip's lateral position;
// each wheel point passes the contact once per revolution, and wear is smeared around the
// circumference (uniform-wear assumption).
//
// Depth direction: Archard removes material along the local surface normal n (the strip's contact
// normal), so depth_per_pass is a NORMAL depth. The wheel profile is z(u) over the lateral
// profile coordinate u, so profile evolution needs the RADIAL depth d_r = d_n / cos(beta), beta the
// slope of the wheel profile at the strip (the contact angle relative to the wheel axle), and the
// strip occupies |du| = width cos(beta) of the profile. cos(beta) is taken from the strips' own
// wheel_u versus arc length (|du/ds|, so wheelset roll is included); with a single strip from the
// contact angle. The worn cross-section d_r |du| = d_n width does not depend on beta.
#pragma once

#include <vector>

#include "core/status.hpp"
#include "tangential/fastsim.hpp"
#include "wear/kth_wear_map.hpp"

namespace railtab {

struct WearOptions {
  KthWearMap map;                          // Archard coefficients and hardness
  Lubrication lubrication = Lubrication::dry;  // scaling of k
};

// Wear at one strip, i.e. at one lateral position of the wheel profile.
struct StripWear {
  double wheel_u = 0.0;         // wheel-profile coordinate of the strip centre [m]
  double width_u = 0.0;         // extent of the strip along the wheel-profile coordinate [m]
  double depth_per_pass = 0.0;  // normal depth removed from a wheel point crossing the patch [m]
  double depth_rate = 0.0;      // radial depth of the wheel profile per metre rolled [m/m]
};

struct WearResult {
  double wear_rate = 0.0;       // wheel-profile cross-section removed per metre rolled [m2/m]
  double volume_rate = 0.0;     // wheel volume removed per metre rolled [m3/m]
  double max_depth_rate = 0.0;  // largest radial depth per metre rolled [m/m]
  double seizure_fraction = 0.0;  // share of the worn volume produced in the seizure region [-]
  StatusBits status = 0;        // kConverged, or kLiftOff for an unloaded patch
};

// Reused output buffers (they only grow).
struct WearDistribution {
  std::vector<StripWear> strips;     // one per FASTSIM strip, same order (m)
  std::vector<double> element_depth; // normal depth per pass removed in each element [m] (elements)
};

// Wear of the last FASTSIM solve held in `fastsim` (elements, pressure, slip, speed).
WearResult archard_wear(const FastsimWorkspace& fastsim, const WearOptions& options,
                        WearDistribution& distribution);

}  // namespace railtab
