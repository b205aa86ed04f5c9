// SPDX-License-Identifier: Apache-2.0
// One sweep laid out: sizes, the table skeleton, the run key, and one column computed into it.
#include "engine/sweep_plan.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "core/check.hpp"
#include "engine/checkpoint.hpp"
#include "engine/mirror.hpp"
#include "engine/shard_split.hpp"
#include "engine/table_size.hpp"
#include "table/version.hpp"

namespace railtab {

const std::vector<double>& grid_of(const Scene& scene, const std::string& name) {
  const SceneGrids& g = scene.grids;
  if (name == "y") return g.y;
  if (name == "roll") return g.roll;
  if (name == "yaw") return g.yaw;
  if (name == "load") return g.load;
  if (name == "xi") return g.xi;
  if (name == "eta") return g.eta;
  if (name == "phi") return g.phi;
  throw Error(fmt::format("sweep: unknown state axis '{}'", name));
}

namespace {

struct AxisInfo {
  const char* name;
  const char* units;
  const char* description;
};
constexpr AxisInfo kStateAxes[] = {
    {"y", "m", "wheelset lateral displacement, track frame, positive to the left"},
    {"roll", "rad", "wheelset roll relative to the track, right-hand about +x (left wheel up)"},
    {"yaw", "rad", "wheelset yaw (angle of attack) relative to the track, right-hand about +z"},
    {"load", "N", "vertical wheel load in track axes"},
    {"xi", "1", "longitudinal creepage, wheel relative to rail, per rolling distance"},
    {"eta", "1", "lateral creepage, wheel relative to rail, per rolling distance"},
    {"phi", "rad/m", "spin creepage, wheel relative to rail, per rolling distance"},
};


bool tabulated(const Scene& scene, const std::string& axis) {
  if (axis == "roll" && scene.equilibrium_roll) return false;
  return grid_of(scene, axis).size() > 1;
}

SweepLayout make_layout(const Scene& scene, const SweepKernel& kernel, const SweepOptions& options) {
  SweepLayout l;
  if (options.y_costs.empty()) {
    std::tie(l.y_begin, l.y_end) = shard_range(scene.grids.y.size(), options.shard_index, options.shard_count);
  } else {
    RAILTAB_CHECK(options.y_costs.size() == scene.grids.y.size(), "sweep: {} column costs for {} y values",
                  options.y_costs.size(), scene.grids.y.size());
    std::tie(l.y_begin, l.y_end) = weighted_shard_range(options.y_costs, options.shard_index, options.shard_count);
  }
  l.ny = l.y_end - l.y_begin;
  l.y_tabulated = scene.grids.y.size() > 1;
  l.roll_tabulated = tabulated(scene, "roll");
  l.nroll = scene.equilibrium_roll ? 1 : scene.grids.roll.size();
  l.yaw_tabulated = tabulated(scene, "yaw");
  l.nyaw = std::max<std::size_t>(1, scene.grids.yaw.size());
  l.columns = l.nroll * l.nyaw;
  l.first_output.push_back(0);
  for (const PartSpec& part : kernel.parts) {
    std::size_t cells = kSlots;
    for (const std::string& axis : part.inner_axes) cells *= grid_of(scene, axis).size();
    l.cells.push_back(cells);
    l.first_output.push_back(l.first_output.back() + part.outputs.size());
  }
  return l;
}

nlohmann::json fixed_axes(const Scene& scene) {
  nlohmann::json fixed = nlohmann::json::object();
  for (const AxisInfo& axis : kStateAxes) {
    if (std::string(axis.name) == "roll" && scene.equilibrium_roll) {
      fixed["roll"] = "equilibrium";  // per y in the root dataset /equilibrium_roll
    } else if (grid_of(scene, axis.name).size() == 1) {  // (a scene without yaw has no yaw at all)
      fixed[axis.name] = grid_of(scene, axis.name).front();
    }
  }
  return fixed;
}

// The table with every dataset allocated (zeros) and every attribute but `created`.
Table make_skeleton(const Scene& scene, const SweepKernel& kernel, const SweepLayout& l, const SweepOptions& options) {
  Table t;
  t.set_attribute("format_version", scene.grids.yaw.empty() ? kTableFormatVersion : kTableFormatVersionYaw);
  t.set_attribute("railtab_version", version_string());
  t.set_attribute("git_commit", git_commit());
  t.set_attribute("created", "");
  t.set_attribute("scene", scene.text);
  t.set_attribute("scene_name", scene.name);
  t.set_attribute("models", kernel.models.dump());
  t.set_attribute("fixed_axes", fixed_axes(scene).dump());
  // The yaw axis holds the non-negative half of a symmetric list: the lookup folds yaw to |yaw|.
  if (scene.grids.yaw_even) t.set_attribute("yaw_symmetry", "even");
  for (const auto& [name, text] : kernel.attributes) t.set_attribute(name, text);
  if (options.shard_count > 1) {
    // A shard is a valid table over its part of y; merge needs to know which part.
    t.set_attribute("shard", fmt::format("{}/{}", options.shard_index, options.shard_count));
    t.set_attribute("shard_y_begin", std::to_string(l.y_begin));
    t.set_attribute("shard_y_end", std::to_string(l.y_end));
    t.set_attribute("shard_y_total", std::to_string(scene.grids.y.size()));
  }

  for (const AxisInfo& info : kStateAxes) {
    std::string name = info.name;
    bool used = name == "y" ? l.y_tabulated : tabulated(scene, name);
    if (!used) continue;
    TableAxis axis{name, info.units, info.description, grid_of(scene, name), false};
    for (const TableAxis& own : kernel.own_axes) {
      if (own.name != name) continue;
      RAILTAB_CHECK(own.values.size() == axis.values.size(), "sweep: the kernel's axis {} has {} nodes for {} in the scene",
                    name, own.values.size(), axis.values.size());
      axis = own;
    }
    if (name == "y") {
      axis.values.assign(scene.grids.y.begin() + static_cast<std::ptrdiff_t>(l.y_begin),
                         scene.grids.y.begin() + static_cast<std::ptrdiff_t>(l.y_end));
    }
    t.axes.push_back(std::move(axis));
  }
  t.axes.push_back({"slot", "1", "contact slot: 0 = tread contact, 1 = flange contact", {0.0, 1.0}, true});

  std::vector<std::string> outer_axes;
  std::vector<std::size_t> outer_shape;
  if (l.y_tabulated) {
    outer_axes.push_back("y");
    outer_shape.push_back(l.ny);
  }
  if (l.roll_tabulated) {
    outer_axes.push_back("roll");
    outer_shape.push_back(l.nroll);
  }
  if (l.yaw_tabulated) {
    outer_axes.push_back("yaw");
    outer_shape.push_back(l.nyaw);
  }
  for (const char* wheel : {"left", "right"}) {
    for (const PartSpec& part : kernel.parts) {
      std::vector<std::string> axes = outer_axes;
      std::vector<std::size_t> shape = outer_shape;
      for (const std::string& axis : part.inner_axes) {
        if (!tabulated(scene, axis)) continue;
        axes.push_back(axis);
        shape.push_back(grid_of(scene, axis).size());
      }
      axes.push_back("slot");
      shape.push_back(kSlots);
      TableGroup group{std::string(wheel) + "/" + part.name, {}};
      for (const OutputInfo& out : part.outputs) {
        TableDataset d{out.name, out.units, out.description, axes, shape, {}, {}, false, 0};
        d.values.assign(d.size(), 0.0);
        group.datasets.push_back(std::move(d));
      }
      TableDataset status{"status", "1", "status bits per point and slot (src/core/status.hpp); 0 = no contact",
                          axes, shape, {}, {}, true, 0};
      status.status.assign(status.size(), 0u);
      group.datasets.push_back(std::move(status));
      t.groups.push_back(std::move(group));
    }
  }
  TableGroup root{"", {}};
  if (scene.equilibrium_roll) {
    TableDataset roll{"equilibrium_roll", "rad",
                      "kinematic equilibrium roll at each y, used for every output; NaN where the search failed",
                      {}, {}, {}, {}, false, 0};
    if (l.y_tabulated) {
      roll.axes = {"y"};
      roll.shape = {l.ny};
    }
    roll.values.assign(l.ny, 0.0);
    root.datasets.push_back(std::move(roll));
  }
  for (const SweepKernel::PerYOutput& out : kernel.per_y) {
    RAILTAB_CHECK(out.values.size() == scene.grids.y.size(), "sweep: root dataset {} has {} values for {} y nodes",
                  out.info.name, out.values.size(), scene.grids.y.size());
    TableDataset d{out.info.name, out.info.units, out.info.description, {}, {}, {}, {}, false, 0};
    if (l.y_tabulated) {
      d.axes = {"y"};
      d.shape = {l.ny};
    }
    d.values.assign(out.values.begin() + static_cast<std::ptrdiff_t>(l.y_begin),
                    out.values.begin() + static_cast<std::ptrdiff_t>(l.y_end));
    root.datasets.push_back(std::move(d));
  }
  if (!root.datasets.empty()) t.groups.push_back(std::move(root));
  return t;
}

}  // namespace

// Identity of a run for its checkpoint: anything that could change a stored byte.
std::uint64_t SweepPlan::run_key() const {
  const Table& t = table_;
  std::string id = fmt::format("{}|{}|{}|{}|{}|{}", *t.attribute("scene"), *t.attribute("models"),
                               *t.attribute("railtab_version"), *t.attribute("git_commit"),
                               t.attribute("shard") ? *t.attribute("shard") : "1/1", *t.attribute("format_version"));
  for (const TableGroup& g : t.groups) {
    for (const TableDataset& d : g.datasets) {
      id += "|" + g.path + "/" + d.name;
      for (std::size_t n : d.shape) id += fmt::format(",{}", n);
    }
  }
  return fnv1a(id);
}

SweepPlan::SweepPlan(const Scene& scene, const SweepKernel& kernel, const SweepOptions& options)
    : scene_(scene), kernel_(kernel) {
  RAILTAB_CHECK(!scene.equilibrium_roll || kernel.equilibrium_roll,
                "sweep: the scene asks for equilibrium roll but the kernel cannot compute it");
  RAILTAB_CHECK(kernel.compute, "sweep: kernel without compute function");
  layout_ = make_layout(scene, kernel, options);
  // Before any allocation (every engine makes its skeleton here): every size of the skeleton fits
  // once the totals do. make_layout only does arithmetic on the grid sizes.
  check_table_size(scene, table_points(scene, layout_.ny), table_bytes(scene, kernel, layout_.ny),
                   options.max_points, options.max_bytes, kernel.point_cost);
  table_ = make_skeleton(scene, kernel, layout_, options);
  TableGroup* root = table_.group("");
  TableDataset* roll_dataset = root ? root->find("equilibrium_roll") : nullptr;
  equilibrium_roll_ = roll_dataset ? roll_dataset->values.data() : nullptr;
  full_sweep_reason_ = options.mirror ? mirror_obstacle(scene, kernel) : "the full sweep was asked for";
  mirrored_ = full_sweep_reason_.empty();
  target_.assign(layout_.ny, kNoBlock);
  filled_.assign(layout_.ny, 0);
  if (!mirrored_) return;
  mirror_cells_ = mirror_cells(scene, kernel);
  const std::size_t ny = scene.grids.y.size();
  for (std::size_t b = 0; b < layout_.ny; ++b) {
    const std::size_t iy = layout_.y_begin + b, image = ny - 1 - iy;
    if (scene.grids.y[iy] > 0.0 && image >= layout_.y_begin && image < layout_.y_end) {
      target_[b] = image - layout_.y_begin;
      filled_[image - layout_.y_begin] = 1;
    }
  }
}

ColumnState SweepPlan::column_state(std::size_t iy, std::size_t column) const {
  ColumnState state;
  state.iy = iy;
  state.iroll = column / layout_.nyaw;
  state.iyaw = column % layout_.nyaw;
  state.y = scene_.grids.y[iy];
  state.yaw = scene_.grids.yaw.empty() ? 0.0 : scene_.grids.yaw[state.iyaw];
  if (!scene_.equilibrium_roll) state.roll = scene_.grids.roll[state.iroll];
  return state;
}

ColumnOutput SweepPlan::column_output(std::size_t block, std::size_t column) {
  const SweepLayout& l = layout_;
  const std::size_t parts = kernel_.parts.size();
  std::vector<double*> values;
  std::vector<StatusBits*> status;
  for (std::size_t wheel = 0; wheel < 2; ++wheel) {
    for (std::size_t p = 0; p < parts; ++p) {
      TableGroup& group = table_.groups[wheel * parts + p];
      std::size_t offset = (block * l.columns + column) * l.cells[p];
      for (std::size_t o = 0; o < kernel_.parts[p].outputs.size(); ++o) {
        values.push_back(group.datasets[o].values.data() + offset);
      }
      status.push_back(group.datasets.back().status.data() + offset);
    }
  }
  return ColumnOutput(std::move(values), std::move(status), l.first_output, parts);
}

// A column's outputs in `values` and `status` (sized here), laid out as ColumnOutput reads them.
ColumnOutput SweepPlan::aside_output(std::vector<double>& values, std::vector<StatusBits>& status) const {
  const SweepLayout& l = layout_;
  const std::size_t parts = kernel_.parts.size();
  std::size_t value_count = 0, cell_count = 0;
  for (std::size_t p = 0; p < parts; ++p) {
    value_count += l.cells[p] * kernel_.parts[p].outputs.size();
    cell_count += l.cells[p];
  }
  values.assign(2 * value_count, 0.0);
  status.assign(2 * cell_count, 0u);
  std::vector<double*> v;
  std::vector<StatusBits*> st;
  std::size_t next_value = 0, next_cell = 0;
  for (std::size_t wheel = 0; wheel < 2; ++wheel) {
    for (std::size_t p = 0; p < parts; ++p) {
      for (std::size_t o = 0; o < kernel_.parts[p].outputs.size(); ++o, next_value += l.cells[p])
        v.push_back(values.data() + next_value);
      st.push_back(status.data() + next_cell);
      next_cell += l.cells[p];
    }
  }
  return ColumnOutput(std::move(v), std::move(st), l.first_output, parts);
}

std::size_t SweepPlan::mirror_of(std::size_t column) const {
  const SweepLayout& l = layout_;
  return (l.nroll - 1 - column / l.nyaw) * l.nyaw + (l.nyaw - 1 - column % l.nyaw);
}

void SweepPlan::set_roll(std::size_t block, double roll) {
  if (equilibrium_roll_) equilibrium_roll_[block] = roll;
}

// The equilibrium roll of the mirror image: odd in y (a failed search's NaN stays as it is).
static double mirror_roll(double roll) { return std::isnan(roll) ? roll : -roll; }

void SweepPlan::fill_mirror(std::size_t from_block, std::size_t to_block) {
  for (std::size_t c = 0; c < layout_.columns; ++c)
    mirror_column(kernel_, mirror_cells_, column_output(from_block, c), column_output(to_block, mirror_of(c)));
  if (equilibrium_roll_) set_roll(to_block, mirror_roll(equilibrium_roll_[from_block]));
}

ColumnReport SweepPlan::compute_column(std::size_t block, std::size_t column) {
  const SweepLayout& l = layout_;
  const std::size_t iy = l.y_begin + block;
  // A scheduled block y < 0 of a mirrored sweep is a shard's whose block +y lies in another
  // shard: that column is computed aside and its mirror stored, so that every shard stores the
  // bytes the whole table would.
  const bool aside = mirrored_ && scene_.grids.y[iy] < 0.0;
  std::vector<double> aside_values;
  std::vector<StatusBits> aside_status;
  ColumnState state = aside ? column_state(scene_.grids.y.size() - 1 - iy, mirror_of(column)) : column_state(iy, column);
  ColumnOutput out = aside ? aside_output(aside_values, aside_status) : column_output(block, column);
  if (scene_.equilibrium_roll) {
    try {
      state.roll = kernel_.equilibrium_roll(state.y);
    } catch (const std::exception& e) {
      // The kernel then flags every point of the column (NaN input) as a failure.
      state.roll = std::numeric_limits<double>::quiet_NaN();
      out.failure(fmt::format("equilibrium roll at y = {} m: {}", state.y, e.what()));
    }
  }
  kernel_.compute(state, out);
  ColumnReport report{out.failures(), out.first_failure()};
  if (aside) {
    mirror_column(kernel_, mirror_cells_, out, column_output(block, column));
    set_roll(block, mirror_roll(state.roll));
    return report;
  }
  set_roll(block, state.roll);
  const std::size_t target = mirrored_ ? target_[block] : kNoBlock;
  if (target != kNoBlock) {
    mirror_column(kernel_, mirror_cells_, out, column_output(target, mirror_of(column)));
    set_roll(target, mirror_roll(state.roll));
    report.failures *= 2;  // the mirror column holds the same failed points
  }
  return report;
}

std::unique_ptr<Checkpoint> SweepPlan::resume(const std::filesystem::path& path, std::vector<char>& block_done,
                                              SweepSummary& summary) {
  const std::size_t ny = layout_.ny;
  block_done.assign(ny, 0);
  if (path.empty()) return nullptr;
  auto checkpoint = std::make_unique<Checkpoint>(path, run_key(), pack_block(table_, ny, 0).size());
  summary.checkpoint_discarded = checkpoint->discarded();
  for (Checkpoint::Record& r : checkpoint->take_records()) {
    if (r.block >= ny || block_done[r.block]) continue;
    unpack_block(table_, ny, r.block, r.bytes);
    const std::string altered = first_non_finite(table_, ny, r.block);
    RAILTAB_CHECK(altered.empty(),
                  "{}: the record of y block {} holds a non-finite value in {}, which the sweep never stores (the "
                  "checkpoint was altered): delete it, or run without --resume",
                  path.string(), r.block, altered);
    block_done[r.block] = 1;
    ++summary.blocks_done;
  }
  for (std::size_t b = 0; b < ny; ++b) {
    const std::size_t target = target_[b];
    if (target == kNoBlock || block_done[b] == block_done[target]) continue;
    if (block_done[b]) {
      fill_mirror(b, target);
      block_done[target] = 1;
      ++summary.blocks_done;
    } else {
      block_done[target] = 0;
      --summary.blocks_done;
    }
  }
  summary.points_resumed = summary.blocks_done * points_per_block();
  return checkpoint;
}

}  // namespace railtab
