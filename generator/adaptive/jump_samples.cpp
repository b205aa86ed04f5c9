// SPDX-License-Identifier: Apache-2.0
// One-sided values at the contact jumps (jump_locator.hpp, add_jump_samples): the contact kernel
// (the sweep's own code path) at the two ends of every jump's final interval.

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "kernel/contact_kernel.hpp"
#include "adaptive/jump_locator.hpp"
#include "engine/parallel_for.hpp"
#include "engine/progress.hpp"

namespace railtab {
namespace {

// The kernel's outputs of one column (one y, one load, both wheels), laid out as the sweep's.
struct Column {
  std::vector<std::size_t> first_output{0};  // per part, plus the total
  std::vector<std::size_t> part_size;        // inner grid x slot, per part
  std::vector<std::vector<double>> values;   // [wheel * outputs + output]
  std::vector<std::vector<StatusBits>> status;  // [wheel * parts + part]
};

Column compute_column(const SweepKernel& kernel, const Scene& one, double y, std::size_t wheel) {
  Column c;
  for (const PartSpec& part : kernel.parts) {
    c.first_output.push_back(c.first_output.back() + part.outputs.size());
    std::size_t n = kSlots;
    for (const std::string& axis : part.inner_axes) {
      if (axis == "xi") n *= one.grids.xi.size();
      if (axis == "eta") n *= one.grids.eta.size();
      if (axis == "phi") n *= one.grids.phi.size();
      if (axis == "load") n *= one.grids.load.size();
      if (axis == "roll") n *= one.grids.roll.size();
    }
    c.part_size.push_back(n);
  }
  const std::size_t outputs = c.first_output.back(), parts = kernel.parts.size();
  std::vector<double*> value_ptr;
  std::vector<StatusBits*> status_ptr;
  for (std::size_t w = 0; w < 2; ++w)
    for (std::size_t p = 0; p < parts; ++p)
      for (std::size_t o = c.first_output[p]; o < c.first_output[p + 1]; ++o) c.values.emplace_back(c.part_size[p], 0.0);
  for (std::size_t w = 0; w < 2; ++w)
    for (std::size_t p = 0; p < parts; ++p) c.status.emplace_back(c.part_size[p], 0u);
  for (auto& v : c.values) value_ptr.push_back(v.data());
  for (auto& s : c.status) status_ptr.push_back(s.data());
  (void)outputs;
  ColumnOutput out(value_ptr, status_ptr, c.first_output, parts);
  ColumnState state;
  state.y = y;
  state.wheels = 1u << wheel;  // the other wheel's cells stay zero (not read)
  state.roll = one.equilibrium_roll ? kernel.equilibrium_roll(y) : one.grids.roll.front();
  state.yaw = fixed_yaw(one);
  kernel.compute(state, out);
  return c;
}

}  // namespace

void add_jump_samples(Table& table, const Scene& scene, const ContactJumps& jumps, int threads,
                      const StageProgress& progress, const std::string& root) {
  const TableGroup* list = table.group(root);
  if (!list) return;  // no jumps
  const std::size_t n_load = scene.grids.load.size();
  std::size_t count = 0;
  for (const auto& wheel : jumps.wheel)
    for (const auto& l : wheel) count = std::max(count, l.size());
  // Columns: [wheel][load][jump][side], computed in parallel (each independent, deterministic).
  std::vector<Scene> one(n_load, scene);
  std::vector<SweepKernel> kernels;
  for (std::size_t l = 0; l < n_load; ++l) {
    one[l].grids.load = {scene.grids.load[l]};
    one[l].grids.y = {scene.grids.y.front()};
    kernels.push_back(make_contact_kernel(one[l]));
  }
  const std::size_t tasks = 2 * n_load * count * 2;
  std::vector<Column> columns(tasks);
  std::size_t todo = 0;  // columns of real jumps (the rest is padding)
  for (const auto& wheel : jumps.wheel)
    for (const auto& l : wheel) todo += 2 * l.size();
  TaskProgress ticks(progress, todo);
  parallel_for_index(threads, tasks, [&](std::size_t t) {
    const std::size_t w = t / (n_load * count * 2), l = (t / (count * 2)) % n_load, j = (t / 2) % count,
                      side = t % 2;
    if (j >= jumps.wheel[w][l].size()) return;
    const ContactJump& jump = jumps.wheel[w][l][j];
    columns[t] = compute_column(kernels[l], one[l], side == 0 ? jump.left : jump.right, w);
    ticks.tick();
  });
  ticks.finish();
  const SweepKernel& kernel = kernels.front();
  const bool load_axis = table.axis("load") != nullptr;
  const char* names[2] = {"left", "right"};
  for (std::size_t w = 0; w < 2; ++w) {
    for (std::size_t p = 0; p < kernel.parts.size(); ++p) {
      const PartSpec& part = kernel.parts[p];
      TableGroup group{root + "/" + names[w] + "/" + part.name, {}};
      std::vector<std::string> axes;
      std::vector<std::size_t> shape;
      if (load_axis) axes.emplace_back("load"), shape.push_back(n_load);
      axes.emplace_back(kJumpDimension), shape.push_back(count);
      axes.emplace_back(kSideDimension), shape.push_back(2);
      for (const std::string& a : part.inner_axes) {
        if (a == "load") continue;
        const TableAxis* axis = table.axis(a);
        if (!axis) continue;  // fixed
        axes.push_back(a), shape.push_back(axis->values.size());
      }
      axes.emplace_back("slot"), shape.push_back(kSlots);
      std::size_t block = 0;  // values of one (load, jump, side)
      for (std::size_t t = 0; t < tasks && !block; ++t)
        if (!columns[t].part_size.empty()) block = columns[t].part_size[p];
      auto fill = [&](TableDataset& d, auto&& copy) {
        d.axes = axes;
        d.shape = shape;
        for (std::size_t l = 0; l < n_load; ++l)
          for (std::size_t j = 0; j < count; ++j)
            for (std::size_t side = 0; side < 2; ++side) {
              const Column& c = columns[((w * n_load + l) * count + j) * 2 + side];
              copy(c, ((l * count + j) * 2 + side) * block);
            }
      };
      const std::size_t outputs = kernel.parts.size();
      for (std::size_t o = 0; o < part.outputs.size(); ++o) {
        TableDataset d;
        d.name = part.outputs[o].name;
        d.units = part.outputs[o].units;
        d.description = part.outputs[o].description + " (one-sided value at the jump, side 0 left, 1 right)";
        d.values.assign(n_load * count * 2 * block, 0.0);
        fill(d, [&](const Column& c, std::size_t at) {
          if (c.values.empty()) return;  // padding
          const std::vector<double>& v = c.values[w * c.first_output.back() + c.first_output[p] + o];
          std::copy(v.begin(), v.end(), d.values.begin() + static_cast<std::ptrdiff_t>(at));
        });
        group.datasets.push_back(std::move(d));
      }
      TableDataset st;
      st.name = "status";
      st.units = "1";
      st.description = "status of the one-sided values (0 in the padding)";
      st.is_status = true;
      st.status.assign(n_load * count * 2 * block, 0u);
      fill(st, [&](const Column& c, std::size_t at) {
        if (c.status.empty()) return;
        const std::vector<StatusBits>& v = c.status[w * outputs + p];
        std::copy(v.begin(), v.end(), st.status.begin() + static_cast<std::ptrdiff_t>(at));
      });
      group.datasets.push_back(std::move(st));
      table.groups.push_back(std::move(group));
    }
  }
}

}  // namespace railtab
