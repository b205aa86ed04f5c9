// SPDX-License-Identifier: Apache-2.0
// Reading measured or published profiles from files: the only file I/O in src/ (docs/profiles.md
// gives the formats and how each maps to the profile frames of docs/conventions.md).
#pragma once

#include <filesystem>

#include "profile/curves/profile.hpp"

namespace railtab {

// How a file's axes are to be taken where the format leaves it open (MiniProf): automatic
// (docs/profiles.md "MiniProf": flange tip down and on the track side, rail top up, gauge face
// on the track side), as in the file (no), or mirrored (yes).
enum class AxisMirror { automatic, no, yes };

struct ProfileReadOptions {
  double smoothing_length = 0.0;             // L_filt [m]: 0 interpolates (the default), > 0 smooths
  AxisMirror mirror_y = AxisMirror::automatic;  // MiniProf lateral axis
  AxisMirror mirror_z = AxisMirror::automatic;  // MiniProf vertical axis
  bool check_plausibility = true;            // width, height, flange side, rail top (profile_checks.hpp)
  // Added to the lateral coordinate after reading [m]: a wheel measured from its flange back
  // (CONTACT's FBPOS = 0, e.g. testbank worn_high_mileage.prw) needs -0.070 to put u = 0 on the
  // running circle that railtab's wheel frame requires (docs/profiles.md "Plausibility checks").
  double lateral_shift = 0.0;
};

// Reads a wheel or rail profile: a SplineProfile (profile/curves/spline_profile.hpp) when the points are
// a function z(u), a ParametricProfile (overhangs, undercuts, vertical faces) otherwise; named
// after the file stem. Formats (docs/profiles.md):
// - SIMPACK rail-wheel profiles (extension .prw / .prr, or any file with a `header.begin` or
//   `spline.begin` block): header `type` must match `kind`; the spline-block options shift.y/z,
//   rotate, bound.y/z, point.dist.min, mirror.y/z, inversion, units.len.f, units.ang.f are applied
//   in SIMPACK's order; the point block holds "y z [weight]" (weights ignored). `!` comments.
// - MiniProf (.whl wheel, .ban rail, or a file with a MINIPROF banner / ColumnDef= key): old
//   style, keyed header and plain forms, X Y in mm; axes oriented automatically unless mirror_y /
//   mirror_z say otherwise; wheels placed with the flange back at u = -70 mm, z = 0 at u = 0.
// - Anything else: two columns "lateral vertical" in mm, CONTACT's convention (lateral towards
//   the field side, vertical positive downwards); `#`, `%` and `!` start comments; commas or
//   white space separate the columns; blank lines are fine.
// All map to u = lateral [m], z = -vertical [m]; files running towards the track are reversed.
// Only regular files up to limits::kMaxProfileFileBytes are read (profile_limits.hpp).
// Throws railtab::Error naming the file (and the line) for an unreadable, non-regular or oversized
// file, a malformed or non-finite number, a wrong column count, a cut last line, fewer than 4 or
// more than limits::kMaxProfilePoints points, a coordinate beyond limits::kMaxProfileCoordinate,
// duplicate points, and (check_plausibility) a profile that cannot be a wheel or rail.
ProfilePtr read_profile(const std::filesystem::path& file, ProfileKind kind,
                        const ProfileReadOptions& options);
// The same with the default options and the given smoothing length L_filt [m].
ProfilePtr read_profile(const std::filesystem::path& file, ProfileKind kind,
                        double smoothing_length = 0.0);

}  // namespace railtab
