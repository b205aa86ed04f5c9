// SPDX-License-Identifier: Apache-2.0
// KTH wear map (Jendel, Wear 253 (2002) 89-99; used by Enblom & Berg, Wear 265 (2008) 1532-1541):
// Archard's dimensionless wear coefficient k as a function of the local contact pressure p and
// the local slip velocity v, for dry wheel-rail contact, scaled down for natural contamination or
// lubrication.
//
//   p >= 0.8 H                     -> k4 (seizure)
//   p <  0.8 H and v < 0.2 m/s     -> k1 (mild)
//   p <  0.8 H and 0.2 <= v <= 0.7 -> k2 (severe)
//   p <  0.8 H and v > 0.7 m/s     -> k3 (mild, oxidative)
//
// The thresholds 0.2 and 0.7 m/s and the seizure level (about 2.2 GPa) are confirmed by Enblom &
// Berg; the k values and H are NOT verified against Jendel (2002): the defaults are the midpoints of
// the ranges quoted in the literature, (1-10), (30-40), (1-10), (300-400) x 1e-4, and H = 2.75 GPa
// makes 0.8 H equal the 2.2 GPa seizure level. All are inputs: the map is used with calibration.
#pragma once

#include <string_view>

namespace railtab {

enum class Lubrication {
  dry,         // the map as measured (factor 1)
  natural,     // natural contamination: moisture, dirt (k / 5.5, Enblom & Berg)
  lubricated,  // flange lubrication (k / 11)
};
const char* to_string(Lubrication lubrication);
Lubrication parse_lubrication(std::string_view name);  // throws railtab::Error naming the value

enum class KthRegion { mild, severe, oxidative, seizure };  // k1, k2, k3, k4
const char* to_string(KthRegion region);

struct KthWearMap {
  double k1 = 5.5e-4;               // mild wear, low slip velocity [-] (unverified midpoint)
  double k2 = 35e-4;                // severe wear, intermediate slip velocity [-] (unverified)
  double k3 = 5.5e-4;               // mild oxidative wear, high slip velocity [-] (unverified)
  double k4 = 350e-4;               // seizure, high pressure [-] (unverified)
  double hardness = 2.75e9;         // H of the worn material [Pa] (unverified)
  double seizure_ratio = 0.8;       // pressure / H at the seizure boundary [-]
  double velocity_severe = 0.2;     // slip velocity where severe wear starts [m/s]
  double velocity_oxidative = 0.7;  // slip velocity above which wear is mild again [m/s]
  double factor_natural = 5.5;      // divisor of k for natural contamination [-]
  double factor_lubricated = 11.0;  // divisor of k for lubricated contact [-]
};

// Throws railtab::Error for negative or non-finite entries or inverted thresholds.
void validate(const KthWearMap& map);

// Region of the map; pressure [Pa] and slip velocity [m/s] are taken by magnitude.
KthRegion kth_region(const KthWearMap& map, double pressure, double slip_velocity);

// k for the region, divided by the lubrication factor [-].
double kth_wear_coefficient(const KthWearMap& map, double pressure, double slip_velocity,
                            Lubrication lubrication = Lubrication::dry);

}  // namespace railtab
