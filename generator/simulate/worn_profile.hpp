// SPDX-License-Identifier: Apache-2.0
// Profile evolution: a wheel profile worn by a radial depth distribution becomes the next wear
// step's wheel profile, written as a two-column profile file (docs/profiles.md) that a scene can
// name, so every step of a run can be reproduced with `railtab generate` and `railtab eval`.
#pragma once

#include <filesystem>
#include <vector>

#include "profile/curves/profile.hpp"

namespace railtab {

// Smooths `depth` (radial depth on the uniformly spaced bin centres `u` [m]) with smooth_depth,
// removes it from `wheel` (rolling radius r(u) - depth(u), i.e. z + depth; depth linear between
// bin centres, 0 beyond the bins), and writes the profile at `step` spacing over the wheel's
// range to `file` (lateral and vertical in mm, CONTACT orientation), and the same points as a
// SIMPACK wheel profile beside it (`file` with the extension .prw, profile/formats/simpack_writer.hpp).
// Written to temporary names and renamed. Throws railtab::Error naming the file for I/O errors or non-finite input.
void write_worn_profile(const Profile& wheel, const std::vector<double>& u,
                        const std::vector<double>& depth, double smoothing_length,
                        const std::filesystem::path& file, double step = 0.0002);

// The smoothing of write_worn_profile, on its own (for charts and tests): a triangular kernel of
// base `smoothing_length` [m] (0, or less than two bins: none), area-conserving also at the grid
// ends (worn_profile.cpp says why this kernel). `u` must be uniformly spaced.
std::vector<double> smooth_depth(const std::vector<double>& u, const std::vector<double>& depth,
                                 double smoothing_length);

}  // namespace railtab
