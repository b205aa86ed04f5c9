// SPDX-License-Identifier: Apache-2.0
// The mirror that swaps the wheels: the symmetry check of a sweep and one column mirrored.
#include "engine/mirror.hpp"

#include <fmt/format.h>

#include "engine/sweep_plan.hpp"

namespace railtab {

namespace {

// values[i] == -values[n - 1 - i] for every i, bit for bit but for the sign of a zero.
bool symmetric(const std::vector<double>& values) {
  const std::size_t n = values.size();
  for (std::size_t i = 0; i < n; ++i)
    if (values[i] != -values[n - 1 - i]) return false;
  return true;
}

}  // namespace

std::string mirror_obstacle(const Scene& scene) {
  const SceneGrids& g = scene.grids;
  if (g.y.size() < 2) return "one y value";
  if (!symmetric(g.y)) return "the y grid is not symmetric about 0";
  if (!scene.equilibrium_roll && !symmetric(g.roll)) return "the roll grid is not symmetric about 0";
  // An even yaw axis holds only yaw >= 0: the mirror's -yaw is not a node of the table.
  if (g.yaw_even) return "the yaw axis keeps only yaw >= 0 (yaw_symmetry even)";
  if (!symmetric(g.yaw)) return "the yaw grid is not symmetric about 0";
  if (!symmetric(g.eta)) return "the eta grid is not symmetric about 0";
  if (!symmetric(g.phi)) return "the phi grid is not symmetric about 0";
  return {};
}

std::string mirror_obstacle(const Scene& scene, const SweepKernel& kernel) {
  if (!kernel.mirror_symmetric) return "the kernel's model is not mirror-symmetric";
  const std::string grids = mirror_obstacle(scene);
  if (!grids.empty()) return grids;
  for (const TableAxis& axis : kernel.own_axes)
    if ((axis.name == "eta" || axis.name == "phi") && !symmetric(axis.values))
      return fmt::format("the kernel's {} axis is not symmetric about 0", axis.name);
  for (const SweepKernel::PerYOutput& out : kernel.per_y) {
    const std::size_t n = out.values.size();
    for (std::size_t i = 0; i < n; ++i)
      if (out.values[i] != out.values[n - 1 - i]) return fmt::format("the root dataset {} differs at -y", out.info.name);
  }
  return {};
}

std::vector<std::vector<std::size_t>> mirror_cells(const Scene& scene, const SweepKernel& kernel) {
  std::vector<std::vector<std::size_t>> cells;
  for (const PartSpec& part : kernel.parts) {
    std::vector<std::size_t> shape;
    std::vector<char> reversed;
    for (const std::string& axis : part.inner_axes) {
      shape.push_back(grid_of(scene, axis).size());
      reversed.push_back(axis == "eta" || axis == "phi");
    }
    shape.push_back(kSlots);
    reversed.push_back(0);
    std::size_t total = 1;
    for (std::size_t n : shape) total *= n;
    std::vector<std::size_t> map(total);
    for (std::size_t c = 0; c < total; ++c) {
      // Decompose c in C order (last axis fastest), reverse the mirrored axes, compose again.
      std::size_t rest = c, image = 0, stride = 1;
      for (std::size_t a = shape.size(); a-- > 0;) {
        const std::size_t i = rest % shape[a];
        rest /= shape[a];
        image += (reversed[a] ? shape[a] - 1 - i : i) * stride;
        stride *= shape[a];
      }
      map[c] = image;
    }
    cells.push_back(std::move(map));
  }
  return cells;
}

void mirror_column(const SweepKernel& kernel, const std::vector<std::vector<std::size_t>>& cells,
                   const ColumnOutput& from, const ColumnOutput& to) {
  for (std::size_t wheel = 0; wheel < 2; ++wheel) {
    for (std::size_t p = 0; p < kernel.parts.size(); ++p) {
      const std::vector<std::size_t>& map = cells[p];
      for (std::size_t o = 0; o < kernel.parts[p].outputs.size(); ++o) {
        const double* src = from.values(wheel, p, o);
        double* dst = to.values(1 - wheel, p, o);
        const bool odd = kernel.parts[p].outputs[o].odd;
        for (std::size_t c = 0; c < map.size(); ++c) {
          const double v = src[c];
          dst[map[c]] = odd && v != 0.0 ? -v : v;
        }
      }
      const StatusBits* src = from.status(wheel, p);
      StatusBits* dst = to.status(1 - wheel, p);
      for (std::size_t c = 0; c < map.size(); ++c) dst[map[c]] = src[c];
    }
  }
}

}  // namespace railtab
