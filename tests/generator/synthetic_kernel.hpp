// SPDX-License-Identifier: Apache-2.0
// A fast kernel with the layout of the contact kernel (plus a creep-like part) whose values are a
// fixed function of the grid indices, for testing the sweep machinery without the contact core.
#pragma once

#include <atomic>
#include <cmath>
#include <string>

#include "scene/scene.hpp"
#include "engine/sweep.hpp"
#include "table/table.hpp"

namespace railtab::testing {

constexpr const char* kSyntheticScene = R"(
[scene]
name = "synthetic"
[profiles]
wheel = "s1002"
rail = "uic60"
[grid]
y = {start = -0.005, stop = 0.005, count = 7}
roll = [-0.001, 0.001]
load = [50e3, 80e3]
xi = [-0.001, 0.0, 0.001]
phi = [0.0, 0.5]
)";

struct SyntheticControl {
  std::atomic<int> columns{0};            // columns computed so far
  int interrupt_after = -1;               // set *flag after this many columns (-1: never)
  std::atomic<bool>* flag = nullptr;
};

inline SweepKernel synthetic_kernel(const Scene& scene, SyntheticControl* control = nullptr) {
  SweepKernel k;
  auto outputs = [](const std::string& part) {
    std::vector<OutputInfo> out;
    for (const std::string& name : required_outputs(part)) {
      if (name != "status") out.push_back({name, "1", "synthetic " + name});
    }
    return out;
  };
  k.parts = {{"geometry", {}, outputs("geometry")},
             {"normal", {"load"}, outputs("normal")},
             {"creep", {"load", "xi", "eta", "phi"}, outputs("creep")}};
  k.points_per_column = scene.grids.load.size() * scene.grids.xi.size() * scene.grids.eta.size() * scene.grids.phi.size();
  k.models = {{"normal", "synthetic"}};
  k.equilibrium_roll = [](double y) { return -0.05 * y; };
  std::vector<std::size_t> cells = {2, 2 * scene.grids.load.size(), 2 * k.points_per_column};
  k.compute = [k_parts = k.parts, cells, control](const ColumnState& s, ColumnOutput& out) {
    for (std::size_t w = 0; w < 2; ++w) {
      for (std::size_t p = 0; p < k_parts.size(); ++p) {
        for (std::size_t c = 0; c < cells[p]; ++c) {
          for (std::size_t o = 0; o < k_parts[p].outputs.size(); ++o) {
            out.values(w, p, o)[c] = std::sin(1e3 * s.y + 7e2 * s.roll + 0.1 * static_cast<double>(c) +
                                              static_cast<double>(p) + 0.01 * static_cast<double>(o) +
                                              0.5 * static_cast<double>(w));
          }
          out.status(w, p)[c] = status::kConverged | (c % 2 ? status::kFlangeContact : 0u);
        }
      }
    }
    if (s.iy == 1 && s.iroll == 0) {  // one failing point, reported as data
      out.status(1, 1)[0] = status::kNotConverged;
      out.failure("synthetic failure");
    }
    if (control) {
      int n = ++control->columns;
      if (n == control->interrupt_after && control->flag) control->flag->store(true);
    }
  };
  return k;
}

}  // namespace railtab::testing
