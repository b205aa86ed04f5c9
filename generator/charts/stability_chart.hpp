// SPDX-License-Identifier: Apache-2.0
// The stability map chart: which status flags each normal model raises across y, per wheel.
#pragma once

#include <filesystem>

#include "charts/stability_map.hpp"

namespace railtab {

// Writes DIR/stability_map.csv (write_stability_map_csv), DIR/stability_map_flags.csv (one row
// per raised flag: y_mm, row, flag) and DIR/stability_map.png. Throws railtab::Error on failure.
void draw_stability_chart(const Scene& scene, const std::filesystem::path& out_dir,
                          const StabilityMapOptions& options = {});

}  // namespace railtab
