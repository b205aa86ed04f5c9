// SPDX-License-Identifier: Apache-2.0
// The cost of each y column estimated from the loaded contact patches the contact probe finds.
#include "adaptive/column_costs.hpp"

#include <algorithm>
#include <array>

#include "adaptive/contact_probe.hpp"

namespace railtab {

std::vector<double> column_costs(const Scene& scene) {
  std::vector<double> costs(scene.grids.y.size(), 1.0);
  const ContactProbe probe(scene);
  const std::vector<double> load{scene.grids.load[scene.grids.load.size() / 2]};
  const std::vector<std::array<double, 3>> no_creepage{{0.0, 0.0, 0.0}};
  for (std::size_t i = 0; i < costs.size(); ++i) {
    try {
      const auto wheels = probe.evaluate(scene.grids.y[i], load, no_creepage).front().front();
      double patches = 0.0;
      for (const ContactProbe::Wheel& wheel : wheels) {
        for (const ContactProbe::Slot& slot : wheel.slot) patches += slot.loaded ? 1.0 : 0.0;
      }
      costs[i] = std::max(patches, 1.0);
    } catch (const std::exception&) {
      // Left at 1: a failing column is flagged by the sweep, and it costs little.
    }
  }
  return costs;
}

}  // namespace railtab
