// SPDX-License-Identifier: Apache-2.0
// One-sided values at the contact jumps (jump_locator.hpp, add_jump_samples): the contact kernel
// (the sweep's own code path) at the two ends of every jump's final interval.

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "kernel/contact_kernel.hpp"
#include "adaptive/jump_locator.hpp"
#include "engine/mirror.hpp"
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

// A column of zeros laid out as the sweep's (the other wheel's cells stay zero: not read).
Column empty_column(const SweepKernel& kernel, const Scene& one) {
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
  const std::size_t parts = kernel.parts.size();
  for (std::size_t w = 0; w < 2; ++w)
    for (std::size_t p = 0; p < parts; ++p)
      for (std::size_t o = c.first_output[p]; o < c.first_output[p + 1]; ++o) c.values.emplace_back(c.part_size[p], 0.0);
  for (std::size_t w = 0; w < 2; ++w)
    for (std::size_t p = 0; p < parts; ++p) c.status.emplace_back(c.part_size[p], 0u);
  return c;
}

// Where the kernel writes into `c` (laid out by empty_column).
ColumnOutput output_of(Column& c) {
  std::vector<double*> value_ptr;
  std::vector<StatusBits*> status_ptr;
  for (auto& v : c.values) value_ptr.push_back(v.data());
  for (auto& s : c.status) status_ptr.push_back(s.data());
  return ColumnOutput(value_ptr, status_ptr, c.first_output, c.status.size() / 2);
}

Column compute_column(const SweepKernel& kernel, const Scene& one, double y, std::size_t wheel) {
  Column c = empty_column(kernel, one);
  ColumnOutput out = output_of(c);
  ColumnState state;
  state.y = y;
  state.wheels = 1u << wheel;  // the other wheel's cells stay zero (not read)
  state.roll = one.equilibrium_roll ? kernel.equilibrium_roll(y) : one.grids.roll.front();
  state.yaw = fixed_yaw(one);
  kernel.compute(state, out);
  return c;
}

// The column at y node `iy` of load `l` of one wheel, copied from the sweep's datasets in `table`
// into `c` (laid out by empty_column): the sweep computed it with the same kernel code for that
// wheel, load and y, so the bytes are those compute_column would give. False (c unusable) when
// the table does not hold that node in the expected layout (a shard's table, an axis more).
bool column_from_table(const Table& table, const SweepKernel& kernel, std::size_t iy, std::size_t l,
                       std::size_t n_load, std::size_t wheel, Column& c) {
  const std::string name = wheel == 0 ? "left/" : "right/";
  const bool load_axis = table.axis("load") != nullptr;
  for (std::size_t p = 0; p < kernel.parts.size(); ++p) {
    const PartSpec& part = kernel.parts[p];
    const TableGroup* group = table.group(name + part.name);
    if (!group) return false;
    const bool per_load =
        load_axis && std::find(part.inner_axes.begin(), part.inner_axes.end(), "load") != part.inner_axes.end();
    const std::size_t block = c.part_size[p], per_y = block * (per_load ? n_load : 1);
    const std::size_t at = iy * per_y + (per_load ? l : 0) * block;
    auto fits = [&](const TableDataset* d, std::size_t size) {
      return d && !d->shape.empty() && d->axes.front() == "y" && iy < d->shape.front() && size == d->shape.front() * per_y;
    };
    for (std::size_t o = 0; o < part.outputs.size(); ++o) {
      const TableDataset* d = group->find(part.outputs[o].name);
      if (!fits(d, d ? d->values.size() : 0)) return false;
      std::vector<double>& v = c.values[wheel * c.first_output.back() + c.first_output[p] + o];
      std::copy_n(d->values.begin() + static_cast<std::ptrdiff_t>(at), block, v.begin());
    }
    const TableDataset* st = group->find("status");
    if (!fits(st, st ? st->status.size() : 0)) return false;
    std::vector<StatusBits>& v = c.status[wheel * kernel.parts.size() + p];
    std::copy_n(st->status.begin() + static_cast<std::ptrdiff_t>(at), block, v.begin());
  }
  return true;
}

}  // namespace

void add_jump_samples(Table& table, const Scene& scene, const ContactJumps& jumps, int threads,
                      const StageProgress& progress, const std::string& root, bool mirror) {
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
  auto y_of = [&](std::size_t t) {
    const ContactJump& jump = jumps.wheel[t / (n_load * count * 2)][(t / (count * 2)) % n_load][(t / 2) % count];
    return t % 2 == 0 ? jump.left : jump.right;
  };
  auto real = [&](std::size_t t) { return (t / 2) % count < jumps.wheel[t / (n_load * count * 2)][(t / (count * 2)) % n_load].size(); };
  // Jumps a bisection step apart share an end (one's right is the next one's left, in the same
  // (wheel, load)): that column is computed once, by the first task that has it (a column is a
  // function of its wheel, load and y only, so the bytes are those of computing it twice).
  std::vector<std::size_t> source(tasks);
  std::vector<std::size_t> unique;  // tasks that compute their column
  for (std::size_t t = 0; t < tasks; ++t) {
    source[t] = t;
    if (!real(t)) continue;
    const std::size_t group = t / (count * 2);  // (wheel, load)
    for (std::size_t u = group * count * 2; u < t && source[t] == t; ++u)
      if (real(u) && y_of(u) == y_of(t)) source[t] = u;
  }
  // The mirror (engine/mirror.hpp): a right-wheel end whose -y is a left-wheel end at the same
  // load is that column's mirror image (task index of the left end's column, or `tasks`).
  std::vector<std::size_t> image(tasks, tasks);
  if (mirror && mirror_obstacle(scene, kernels.front()).empty()) {
    for (std::size_t t = n_load * count * 2; t < tasks; ++t) {
      if (!real(t) || source[t] != t) continue;
      const std::size_t left = ((t / (count * 2)) % n_load) * count * 2;
      for (std::size_t u = left; u < left + count * 2 && image[t] == tasks; ++u)
        if (real(u) && y_of(u) == -y_of(t)) image[t] = source[u];
    }
  }
  for (std::size_t t = 0; t < tasks; ++t)
    if (real(t) && source[t] == t && image[t] == tasks) unique.push_back(t);
  std::vector<Column> columns(tasks);
  TaskProgress ticks(progress, unique.size());
  // An end at a y node (a jump within one bisection step of the node) is the sweep's column there.
  const TableAxis* y_axis = table.axis("y");
  parallel_for_index(threads, unique.size(), [&](std::size_t k) {
    const std::size_t t = unique[k], w = t / (n_load * count * 2), l = (t / (count * 2)) % n_load;
    const double y = y_of(t);
    const auto node = y_axis ? std::find(y_axis->values.begin(), y_axis->values.end(), y) : std::vector<double>::const_iterator{};
    bool copied = false;
    if (y_axis && node != y_axis->values.end()) {
      columns[t] = empty_column(kernels[l], one[l]);
      copied = column_from_table(table, kernels[l], static_cast<std::size_t>(node - y_axis->values.begin()), l, n_load, w,
                                 columns[t]);
    }
    if (!copied) columns[t] = compute_column(kernels[l], one[l], y, w);
    ticks.tick();
  });
  ticks.finish();
  const SweepKernel& kernel = kernels.front();
  const std::vector<std::vector<std::size_t>> cells = mirror_cells(one.front(), kernel);
  for (std::size_t t = 0; t < tasks; ++t) {
    if (image[t] == tasks) continue;
    columns[t] = empty_column(kernel, one.front());
    mirror_column(kernel, cells, output_of(columns[image[t]]), output_of(columns[t]));
  }
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
              const Column& c = columns[source[((w * n_load + l) * count + j) * 2 + side]];
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
