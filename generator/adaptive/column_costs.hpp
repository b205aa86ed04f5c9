// SPDX-License-Identifier: Apache-2.0
// The estimated cost of each y column of a scene, by which --shard splits the y grid
// (engine/shard_split.hpp): a flange column solves tread and flange patches, about 1.5 x a tread
// column's normal and creep work.
#pragma once

#include <vector>

#include "scene/scene.hpp"

namespace railtab {

// Estimated relative cost of each y column of the scene: loaded contact patches of both wheels at
// the middle load without creepage (at least 1). Deterministic; 1 for every y where the contact
// chain fails (the column is then cheap anyway).
std::vector<double> column_costs(const Scene& scene);

}  // namespace railtab
