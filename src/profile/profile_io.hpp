// Reading measured or published profiles from files: the only file I/O in src/ (docs/profiles.md
// gives the formats and how each maps to the profile frames of docs/conventions.md).
#pragma once

#include <filesystem>

#include "profile/profile.hpp"

namespace railtab {

// Reads a wheel or rail profile and returns a SplineProfile (profile/spline_profile.hpp) through
// its points, named after the file stem.
// - SIMPACK rail-wheel profiles (extension .prw / .prr, or any file with a `header.begin` or
//   `spline.begin` block): header `type` must match `kind`; the spline-block options shift.y/z,
//   rotate, bound.y/z, point.dist.min, mirror.y/z, inversion, units.len.f, units.ang.f are applied
//   in SIMPACK's order; the point block holds "y z [weight]" (weights ignored). `!` comments.
// - Anything else: two columns "lateral vertical" in mm, CONTACT's convention (lateral towards
//   the field side, vertical positive downwards); `#`, `%` and `!` start comments; commas or
//   white space separate the columns; blank lines are fine.
// Both map to u = lateral [m], z = -vertical [m]; descending files are reversed.
// smoothing_length [m]: 0 interpolates the points, > 0 is CONTACT's filter length L_filt.
// Throws railtab::Error naming the file (and the line) for an unreadable file, a malformed or
// non-finite number, a wrong column count, fewer than 4 points, a lateral coordinate that is not
// monotonic after orientation, or duplicate points.
ProfilePtr read_profile(const std::filesystem::path& file, ProfileKind kind,
                        double smoothing_length = 0.0);

}  // namespace railtab
