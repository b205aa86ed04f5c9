// SPDX-License-Identifier: Apache-2.0
// Internal to the profile readers: MiniProf wheel (.whl) and rail (.ban) files, in their three
// forms (docs/profiles.md "MiniProf"): old style (a "MINIPROF" banner, free header lines, data
// after the first blank line), keyed header (Key=Value lines, ColumnDef=...), plain columns.
#pragma once

#include <vector>

#include "profile/formats/parse_util.hpp"
#include "profile/curves/profile.hpp"
#include "profile/formats/profile_io.hpp"

namespace railtab::detail {

using Mirror = AxisMirror;

struct MiniProfOptions {
  Mirror mirror_y = Mirror::automatic;
  Mirror mirror_z = Mirror::automatic;
};

// Points in metres, y towards the field side, z DOWN (the frame of FilePoint), oriented and,
// for a wheel, placed (flange back at u = -70 mm, z = 0 at u = 0). Throws Error file:line.
std::vector<FilePoint> read_miniprof(const std::vector<std::string>& lines, const fs::path& file,
                                     ProfileKind kind, const MiniProfOptions& options);

// True when the first lines look like a MiniProf file (banner or keyed header).
bool looks_like_miniprof(const std::vector<std::string>& lines);

}  // namespace railtab::detail
