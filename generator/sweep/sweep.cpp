// The sweep engine: a kernel over the (y, roll) grid in parallel, in a deterministic order.
#include "sweep/sweep.hpp"

#include <fmt/format.h>
#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/info.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/partitioner.h>
#include <oneapi/tbb/task_arena.h>
#include <oneapi/tbb/task_group.h>

#include <chrono>
#include <cmath>
#include <condition_variable>
#include <ctime>
#include <limits>
#include <memory>
#include <mutex>
#include <thread>

#include "core/check.hpp"
#include "sweep/checkpoint.hpp"
#include "table/version.hpp"

namespace railtab {

void ColumnOutput::failure(const std::string& message) {
  if (failures_++ == 0) first_failure_ = message;
}

std::pair<std::size_t, std::size_t> shard_range(std::size_t ny, int index, int count) {
  RAILTAB_CHECK(count >= 1 && index >= 1 && index <= count, "shard {}/{}: need 1 <= I <= N", index, count);
  RAILTAB_CHECK(static_cast<std::size_t>(count) <= ny, "shard {}/{}: the y grid has only {} values to split",
                index, count, ny);
  auto n = static_cast<std::size_t>(count), i = static_cast<std::size_t>(index);
  return {ny * (i - 1) / n, ny * i / n};
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
    {"load", "N", "vertical wheel load in track axes"},
    {"xi", "1", "longitudinal creepage, wheel relative to rail, per rolling distance"},
    {"eta", "1", "lateral creepage, wheel relative to rail, per rolling distance"},
    {"phi", "rad/m", "spin creepage, wheel relative to rail, per rolling distance"},
};

const std::vector<double>& grid_of(const Scene& scene, const std::string& name) {
  const SceneGrids& g = scene.grids;
  if (name == "y") return g.y;
  if (name == "roll") return g.roll;
  if (name == "load") return g.load;
  if (name == "xi") return g.xi;
  if (name == "eta") return g.eta;
  if (name == "phi") return g.phi;
  throw Error(fmt::format("sweep: unknown state axis '{}'", name));
}

// Sizes and offsets of one sweep.
struct Layout {
  std::size_t y_begin = 0, y_end = 0;   // shard's range of the full y grid
  std::size_t ny = 0;                   // y values in this table (shard) = blocks
  std::size_t nroll = 1;                // roll values swept per y (1 with equilibrium roll)
  bool y_tabulated = false;             // y is an axis of the file
  bool roll_tabulated = false;          // roll is an axis of the file
  std::vector<std::size_t> cells;       // per part: inner grid x slot elements of one column
  std::vector<std::size_t> first_output;  // per part: index of its first output, plus the total
};

bool tabulated(const Scene& scene, const std::string& axis) {
  if (axis == "roll" && scene.equilibrium_roll) return false;
  return grid_of(scene, axis).size() > 1;
}

Layout make_layout(const Scene& scene, const SweepKernel& kernel, const SweepOptions& options) {
  Layout l;
  std::tie(l.y_begin, l.y_end) = shard_range(scene.grids.y.size(), options.shard_index, options.shard_count);
  l.ny = l.y_end - l.y_begin;
  l.y_tabulated = scene.grids.y.size() > 1;
  l.roll_tabulated = tabulated(scene, "roll");
  l.nroll = scene.equilibrium_roll ? 1 : scene.grids.roll.size();
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
    } else if (grid_of(scene, axis.name).size() == 1) {
      fixed[axis.name] = grid_of(scene, axis.name).front();
    }
  }
  return fixed;
}

// The table with every dataset allocated (zeros) and every attribute but `created`.
Table make_skeleton(const Scene& scene, const SweepKernel& kernel, const Layout& l, const SweepOptions& options) {
  Table t;
  t.set_attribute("format_version", kTableFormatVersion);
  t.set_attribute("railtab_version", version_string());
  t.set_attribute("git_commit", git_commit());
  t.set_attribute("created", "");
  t.set_attribute("scene", scene.text);
  t.set_attribute("scene_name", scene.name);
  t.set_attribute("models", kernel.models.dump());
  t.set_attribute("fixed_axes", fixed_axes(scene).dump());
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

// Identity of a run for its checkpoint: anything that could change a stored byte.
std::uint64_t run_key(const Table& t) {
  std::string id = fmt::format("{}|{}|{}|{}|{}|{}", *t.attribute("scene"), *t.attribute("models"),
                               *t.attribute("railtab_version"), *t.attribute("git_commit"),
                               t.attribute("shard") ? *t.attribute("shard") : "1/1", kTableFormatVersion);
  for (const TableGroup& g : t.groups) {
    for (const TableDataset& d : g.datasets) {
      id += "|" + g.path + "/" + d.name;
      for (std::size_t n : d.shape) id += fmt::format(",{}", n);
    }
  }
  return fnv1a(id);
}

}  // namespace

SweepResult run_sweep(const Scene& scene, const SweepKernel& kernel, const SweepOptions& options) {
  RAILTAB_CHECK(!scene.equilibrium_roll || kernel.equilibrium_roll,
                "sweep: the scene asks for equilibrium roll but the kernel cannot compute it");
  RAILTAB_CHECK(kernel.compute, "sweep: kernel without compute function");
  {
    // Before any allocation: every size of the layout below fits once the totals do.
    const auto [y_begin, y_end] = shard_range(scene.grids.y.size(), options.shard_index, options.shard_count);
    check_table_size(scene.name, table_points(scene, y_end - y_begin), table_bytes(scene, kernel, y_end - y_begin),
                     options.max_points, options.max_bytes);
  }
  const Layout l = make_layout(scene, kernel, options);
  SweepResult result;
  result.table = make_skeleton(scene, kernel, l, options);
  Table& table = result.table;
  SweepSummary& summary = result.summary;
  const std::size_t parts = kernel.parts.size();
  const std::size_t points_per_block = l.nroll * kernel.points_per_column;
  summary.blocks_total = l.ny;
  summary.points_total = l.ny * points_per_block;

  // Resume: blocks already in the checkpoint are loaded, not computed.
  std::vector<char> block_done(l.ny, 0);
  std::unique_ptr<Checkpoint> checkpoint;
  if (!options.checkpoint.empty()) {
    checkpoint = std::make_unique<Checkpoint>(options.checkpoint, run_key(table), pack_block(table, l.ny, 0).size());
    summary.checkpoint_discarded = checkpoint->discarded();
    for (Checkpoint::Record& r : checkpoint->take_records()) {
      if (r.block >= l.ny || block_done[r.block]) continue;
      unpack_block(table, l.ny, r.block, r.bytes);
      block_done[r.block] = 1;
      ++summary.blocks_done;
    }
  }
  summary.points_resumed = summary.blocks_done * points_per_block;

  struct Task {
    std::size_t block;  // local y index
    std::size_t iroll;
  };
  std::vector<Task> tasks;
  for (std::size_t b = 0; b < l.ny; ++b) {
    if (block_done[b]) continue;
    for (std::size_t r = 0; r < l.nroll; ++r) tasks.push_back({b, r});
  }
  const std::size_t points_todo = tasks.size() * kernel.points_per_column;
  summary.threads = options.threads > 0 ? options.threads : tbb::info::default_concurrency();

  TableGroup* root = table.group("");
  TableDataset* roll_dataset = root ? root->find("equilibrium_roll") : nullptr;
  double* equilibrium_roll = roll_dataset ? roll_dataset->values.data() : nullptr;

  std::atomic<std::size_t> points_done{0};
  std::vector<std::atomic<std::size_t>> remaining(l.ny);
  for (auto& r : remaining) r.store(l.nroll);
  std::mutex mutex;                      // guards the fields below
  std::condition_variable wake;
  std::vector<std::size_t> finished_blocks;  // complete, not yet checkpointed
  bool worker_finished = false;
  std::exception_ptr fatal;
  std::size_t first_failure_task = std::numeric_limits<std::size_t>::max();

  auto interrupted = [&] { return options.interrupt && options.interrupt->load(std::memory_order_relaxed); };

  auto run_task = [&](std::size_t task_index) {
    const Task& task = tasks[task_index];
    ColumnState state;
    state.iy = l.y_begin + task.block;
    state.iroll = task.iroll;
    state.y = scene.grids.y[state.iy];
    std::vector<double*> values;
    std::vector<StatusBits*> status;
    for (std::size_t wheel = 0; wheel < 2; ++wheel) {
      for (std::size_t p = 0; p < parts; ++p) {
        TableGroup& group = table.groups[wheel * parts + p];
        std::size_t offset = (task.block * l.nroll + task.iroll) * l.cells[p];
        for (std::size_t o = 0; o < kernel.parts[p].outputs.size(); ++o) {
          values.push_back(group.datasets[o].values.data() + offset);
        }
        status.push_back(group.datasets.back().status.data() + offset);
      }
    }
    ColumnOutput out(std::move(values), std::move(status), l.first_output, parts);
    if (scene.equilibrium_roll) {
      try {
        state.roll = kernel.equilibrium_roll(state.y);
      } catch (const std::exception& e) {
        // The kernel then flags every point of the column (NaN input) as a failure.
        state.roll = std::numeric_limits<double>::quiet_NaN();
        out.failure(fmt::format("equilibrium roll at y = {} m: {}", state.y, e.what()));
      }
      equilibrium_roll[task.block] = state.roll;
    } else {
      state.roll = scene.grids.roll[task.iroll];
    }
    kernel.compute(state, out);
    points_done.fetch_add(kernel.points_per_column, std::memory_order_relaxed);
    bool block_complete = remaining[task.block].fetch_sub(1) == 1;
    if (out.failures() > 0 || block_complete) {
      std::lock_guard lock(mutex);
      summary.failures += out.failures();
      if (out.failures() > 0 && task_index < first_failure_task) {
        first_failure_task = task_index;  // lowest column: the same message for any thread count
        summary.first_failure = out.first_failure();
      }
      if (block_complete) finished_blocks.push_back(task.block);
    }
    if (block_complete) wake.notify_one();
  };

  tbb::task_group_context context;
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  std::thread worker([&] {
    try {
      tbb::task_arena arena(summary.threads);  // caps the threads of this sweep only
      arena.execute([&] {
        tbb::parallel_for(
            tbb::blocked_range<std::size_t>(0, tasks.size(), 1),
            [&](const tbb::blocked_range<std::size_t>& range) {
              for (std::size_t i = range.begin(); i != range.end(); ++i) {
                if (interrupted()) {
                  context.cancel_group_execution();
                  return;
                }
                run_task(i);
              }
            },
            tbb::simple_partitioner(), context);
      });
    } catch (...) {
      std::lock_guard lock(mutex);
      fatal = std::current_exception();
    }
    {
      std::lock_guard lock(mutex);
      worker_finished = true;
    }
    wake.notify_one();
  });

  // This thread alone writes the checkpoint and reports progress.
  try {
    double last_report = -1.0;
    std::unique_lock lock(mutex);
    while (true) {
      wake.wait_for(lock, std::chrono::duration<double>(options.progress_interval),
                    [&] { return worker_finished || !finished_blocks.empty(); });
      std::vector<std::size_t> blocks;
      blocks.swap(finished_blocks);
      bool finished = worker_finished;
      lock.unlock();
      for (std::size_t b : blocks) {
        if (checkpoint) checkpoint->append(b, pack_block(table, l.ny, b));
        ++summary.blocks_done;
      }
      if (interrupted()) context.cancel_group_execution();
      double now = elapsed();
      if (options.progress && (finished || now - last_report >= options.progress_interval)) {
        options.progress({points_done.load(), points_todo, now});
        last_report = now;
      }
      lock.lock();
      if (finished && finished_blocks.empty()) break;
    }
  } catch (...) {
    context.cancel_group_execution();
    worker.join();
    throw;
  }
  worker.join();
  if (fatal) std::rethrow_exception(fatal);

  summary.seconds = elapsed();
  summary.points_computed = points_done.load();
  summary.interrupted = summary.blocks_done < summary.blocks_total;
  RAILTAB_CHECK(summary.interrupted || interrupted() || summary.points_computed == points_todo,
                "sweep: {} of {} points computed", summary.points_computed, points_todo);
  table.set_attribute("created", utc_timestamp());
  return result;
}

}  // namespace railtab
