// SPDX-License-Identifier: Apache-2.0
// The states of the speed-against-accuracy measurement (speed_accuracy.hpp explains which).
#pragma once

#include <filesystem>
#include <vector>

#include "speed_accuracy/speed_accuracy.hpp"

namespace railtab {

// CONTACT's block C states of the selection (dy_mm, creep_sets) with their reference values.
std::vector<SaState> read_contact_states(const std::filesystem::path& path, const SpeedAccuracyOptions& options);

// The same states at the target creepages and the scene's friction, without reference values.
std::vector<SaState> target_states(const SpeedAccuracyOptions& options, const Scene& scene);

}  // namespace railtab
