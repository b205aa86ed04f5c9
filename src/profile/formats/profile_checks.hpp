// SPDX-License-Identifier: Apache-2.0
// Plausibility of a profile read from a file (docs/profiles.md "Plausibility checks"): units,
// orientation and extent checked against what a wheel or rail can be, before a wrong file turns
// into a table of confident nonsense.
#pragma once

#include <string>

#include "profile/curves/profile.hpp"

namespace railtab {

// Throws railtab::Error "<what>: problem" naming the check that failed and the likely cause.
void check_plausible_profile(const Profile& profile, const std::string& what);

// The cant a rail head appears to have: the angle beta [rad] (counter-clockwise in the profile
// frame, the sense in which the track inclines its rails) by which the head must be turned back
// so that it is mirror-symmetric about a vertical line, and the remaining asymmetry [m] (largest
// spread of the midpoints of horizontal chords 1 to 12 mm below the top). A new rail head gives
// an asymmetry of micrometres; a worn one tenths of millimetres or more, and its beta means little.
struct ApparentCant {
  double beta;                 // [rad]
  double asymmetry;            // after turning back by beta [m]
  double asymmetry_as_given;   // without turning (beta = 0) [m]; 0 for a circle, whose axis is any
};
ApparentCant apparent_cant(const Profile& rail);

}  // namespace railtab
