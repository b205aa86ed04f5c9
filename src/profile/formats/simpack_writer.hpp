// SPDX-License-Identifier: Apache-2.0
// A profile as the text of a SIMPACK rail-wheel profile (.prw wheel, .prr rail), the format other
// vehicle-dynamics tools (SIMPACK, CONTACT, GENSYS importers) read. The counterpart of
// read_profile (profile/formats/profile_io.hpp); docs/profiles.md describes the format.
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <string_view>

#include "profile/curves/profile.hpp"

namespace railtab {

// The file text of a SIMPACK profile through the points (u [m] towards the field side, z [m] up;
// the profile frame of docs/conventions.md), ascending u. Written in SIMPACK's / CONTACT's frame
// (y = u, z = -z, in mm, `units.len.f = 1000`) with every processing option neutral (no shift,
// rotation, bounds, mirroring or inversion), so read_profile gives the points back (to rounding
// in the 16th digit). `comment` goes to the spline block's `comment` (quotes are replaced by
// spaces). Deterministic: no dates. Throws railtab::Error for fewer than 4 points, u and z of
// different lengths, a non-finite number or u not strictly increasing.
std::string simpack_profile_text(ProfileKind kind, std::span<const double> u, std::span<const double> z,
                                 std::string_view comment = {});

// Throws railtab::Error naming `file` unless its extension is .prw for a wheel or .prr for a rail
// (another tool decides the kind by it). The file itself is written by the caller, through the
// generator's safe output file (generator/table/output_file.hpp: write_text_file): src/ writes
// no file (docs/architecture.md, "File I/O").
void check_simpack_file_name(const std::filesystem::path& file, ProfileKind kind);

}  // namespace railtab
