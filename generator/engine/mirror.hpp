// SPDX-License-Identifier: Apache-2.0
// The mirror that swaps the wheels, (y, roll, yaw, eta, phi) -> (-y, -roll, -yaw, -eta, -phi)
// (docs/conventions.md, side frame): whether a sweep may fill its columns y < 0 from those at -y,
// and one column mirrored into another.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "engine/sweep.hpp"
#include "scene/scene.hpp"

namespace railtab {

// Empty when the scene's grids are mapped onto themselves by the mirror: y (at least 2 values), a
// roll list (or the equilibrium roll), yaw, eta and phi each exactly symmetric about 0, bit for
// bit; a fixed roll or yaw is 0. Otherwise why not, for the log.
std::string mirror_obstacle(const Scene& scene);
// The same for a sweep of `kernel` over `scene`: also a kernel without a side of its own
// (SweepKernel::mirror_symmetric), its own eta and phi axes symmetric and its per-y datasets even.
std::string mirror_obstacle(const Scene& scene, const SweepKernel& kernel);

// For each part, the cell of the mirror image of every cell of one column (inner axes in C order,
// slot fastest): the eta and phi nodes reversed, every other index kept.
std::vector<std::vector<std::size_t>> mirror_cells(const Scene& scene, const SweepKernel& kernel);

// Write the mirror image of column `from` into column `to`: the wheels swapped, the cells moved by
// `cells` (mirror_cells), the `odd` outputs negated (a zero keeps its bits, as a computed or empty
// zero would), every status copied.
void mirror_column(const SweepKernel& kernel, const std::vector<std::vector<std::size_t>>& cells,
                   const ColumnOutput& from, const ColumnOutput& to);

}  // namespace railtab
