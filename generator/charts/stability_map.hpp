// SPDX-License-Identifier: Apache-2.0
// Stability map of a scene: for every normal model (STRIPES with both negative-curvature
// treatments) and a fine y sweep of both wheels at the scene's default load, the union of the status
// flags the geometry and the normal layer raise, and the number of loaded patches. Written as CSV
// for a chart (`railtab chart-stability`): where each method falls back, clips, shifts, splits into
// two patches, or fails.
#pragma once

#include <filesystem>

#include "scene/scene.hpp"

namespace railtab {

struct StabilityMapOptions {
  double y_min = -10e-3;  // first wheelset lateral displacement [m]
  double y_max = 10e-3;   // last (included, up to rounding) [m]
  double y_step = 0.1e-3; // step [m]
};

// One row per (variant, wheel, y), variants outer, then wheel (left, right), then y ascending.
// Columns:
//   variant            model label: hertz, linder, kik-piotrowski, stripes-a/shift,
//                      stripes-a/clip-and-smooth, stripes-ab/shift, stripes-ab/clip-and-smooth
//   model              normal model (hertz, linder, kik-piotrowski, stripes-a, stripes-ab)
//   negative_curvature shift | clip-and-smooth (only STRIPES uses it)
//   wheel              left | right
//   y_m                wheelset lateral displacement [m]
//   roll_rad           roll used: kinematic equilibrium roll if the scene asks for it, else 0 [rad]
//   load_N             vertical wheel load: the middle value of the scene's load grid [N]
//   status             union of the geometry wheel/point flags and the normal result's flags
//                      (decimal StatusBits, bits as in src/core/status.hpp)
//   status_names       the same as names, ';'-separated ("none" when 0)
//   patches            loaded patches of the normal result
//   points             rigid contact points of the geometry
//   normal_force_N     sum of the patch normal forces [N]
//   iterations         load-control iterations
//   error              message when the core threw (then status holds kFailed), else empty
// Throws railtab::Error for an invalid range or an unwritable file.
void write_stability_map_csv(const Scene& scene, const std::filesystem::path& csv,
                             const StabilityMapOptions& options = {});

}  // namespace railtab
