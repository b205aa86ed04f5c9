// SPDX-License-Identifier: Apache-2.0
// The S1002 wheel profile (UIC 510-2 / EN 13715) from its piecewise analytic definition
// (/work/shared/FACTS.md section 5.1), in the wheel profile frame of docs/conventions.md:
//   u = S [m] (flange at negative u, flange back face at u = -0.070 m), z = -F(S) [m].
#pragma once

#include <array>

#include "profile/curves/profile.hpp"

namespace railtab {

// Range of the built-in S1002: the field side ends at S = +60 mm. The back of the flange is
// the R20.5 arc centred at S = -49.5 mm, vertical (infinite slope) at the back face S = -70 mm,
// so the range stops at S = -69 mm (slope 3.1, as in the standard's own domain note), where
// z(u) still has finite derivatives.
inline constexpr double kS1002UMin = -0.069;  // lowest u of the built-in profile [m]
inline constexpr double kS1002UMax = 0.060;   // highest u of the built-in profile [m]

// The seven joints between the sections A..H, in descending u [m]: +32.15796 (A|B), -26 (B|C),
// -35 (C|D), -38.426669071 (D|E), -39.764473993 (E|F), -49.662510381 (F|G), -62.764705882 (G|H)
// mm. Curvature jumps at most of them (see FACTS 5.1); geometry sweeps may want to know.
std::array<double, 7> s1002_joints();

// The S1002 wheel, name "S1002", range [kS1002UMin, kS1002UMax]. Allocation-free eval.
ProfilePtr make_s1002_profile();

}  // namespace railtab
