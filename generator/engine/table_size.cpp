// SPDX-License-Identifier: Apache-2.0
// Table size before the sweep (table_size.hpp): checked products, limits, time estimate.
#include "engine/table_size.hpp"

#include <fmt/format.h>

#include "core/check.hpp"
#include "engine/sweep.hpp"

namespace railtab {
namespace {

std::string human_bytes(double b) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int u = 0;
  while (b >= 1024.0 && u < 6) {
    b /= 1024.0;
    ++u;
  }
  return fmt::format("{:.3g} {}", b, units[u]);
}

std::string human_seconds(double s) {
  if (s < 120.0) return fmt::format("{:.0f} s", s);
  if (s < 7200.0) return fmt::format("{:.0f} min", s / 60.0);
  if (s < 172800.0) return fmt::format("{:.1f} h", s / 3600.0);
  return fmt::format("{:.3g} days", s / 86400.0);
}

// "50-200 us", "40-120 ms": a cost range per point in the unit of its upper end.
std::string cost_range(double low, double high) {
  if (high < 1e-3) return fmt::format("{:.0f}-{:.0f} us", low * 1e6, high * 1e6);
  if (high < 1.0) return fmt::format("{:.0f}-{:.0f} ms", low * 1e3, high * 1e3);
  return fmt::format("{:.3g}-{:.3g} s", low, high);
}

std::uint64_t axis_count(const std::vector<double>& axis) { return axis.empty() ? 1 : axis.size(); }

}  // namespace

std::uint64_t checked_multiply(std::uint64_t a, std::uint64_t b, const std::string& what) {
  std::uint64_t product = 0;
  RAILTAB_CHECK(!__builtin_mul_overflow(a, b, &product), "{}: size overflows 64 bits ({} x {})", what, a, b);
  return product;
}

std::uint64_t table_points(const Scene& scene, std::uint64_t y_count) {
  const std::string what = fmt::format("scene '{}': table grid points", scene.name);
  std::uint64_t points = y_count;
  const SceneGrids& g = scene.grids;
  points = checked_multiply(points, scene.equilibrium_roll ? 1 : axis_count(g.roll), what);
  points = checked_multiply(points, axis_count(g.yaw), what);
  for (const std::vector<double>* axis : {&g.load, &g.xi, &g.eta, &g.phi}) {
    points = checked_multiply(points, axis_count(*axis), what);
  }
  return points;
}

std::uint64_t table_bytes(const Scene& scene, const SweepKernel& kernel, std::uint64_t y_count) {
  const std::string what = fmt::format("scene '{}': table bytes", scene.name);
  const SceneGrids& g = scene.grids;
  const std::uint64_t columns = checked_multiply(
      checked_multiply(y_count, scene.equilibrium_roll ? 1 : axis_count(g.roll), what), axis_count(g.yaw), what);
  std::uint64_t total = 0;
  for (const PartSpec& part : kernel.parts) {
    std::uint64_t cells = checked_multiply(columns, kSlots, what);
    for (const std::string& axis : part.inner_axes) {
      const std::vector<double>* grid = axis == "load" ? &g.load
                                        : axis == "xi" ? &g.xi
                                        : axis == "eta" ? &g.eta
                                        : axis == "phi" ? &g.phi
                                                        : nullptr;
      RAILTAB_CHECK(grid, "{}: unknown axis '{}'", what, axis);
      cells = checked_multiply(cells, axis_count(*grid), what);
    }
    const std::uint64_t per_cell = sizeof(double) * part.outputs.size() + sizeof(StatusBits);
    const std::uint64_t part_bytes = checked_multiply(checked_multiply(cells, per_cell, what), 2, what);  // 2 wheels
    RAILTAB_CHECK(!__builtin_add_overflow(total, part_bytes, &total), "{}: size overflows 64 bits", what);
  }
  return total;
}

void check_table_size(const Scene& scene, std::uint64_t points, std::uint64_t bytes, std::uint64_t max_points,
                      std::uint64_t max_bytes, PointCost cost) {
  const double low = cost.low, high = cost.high;
  RAILTAB_CHECK(points <= max_points,
                "scene '{}': the table has {} grid points ({:.3g}), above the limit of {} (--max-points); at "
                "{} per point per thread that is {} to {} on one thread. Coarsen the grid, split it "
                "with --shard, or raise --max-points",
                scene.name, points, static_cast<double>(points), max_points, cost_range(low, high),
                human_seconds(static_cast<double>(points) * low), human_seconds(static_cast<double>(points) * high));
  RAILTAB_CHECK(bytes <= max_bytes,
                "scene '{}': the table needs {} in memory ({} bytes), above the limit of {} (--max-bytes). Coarsen "
                "the grid, split it with --shard, or raise --max-bytes",
                scene.name, human_bytes(static_cast<double>(bytes)), bytes, human_bytes(static_cast<double>(max_bytes)));
}

std::uint64_t computed_points(const Scene& scene, std::size_t y_begin, std::size_t y_end, bool mirrored) {
  const std::vector<double>& y = scene.grids.y;
  RAILTAB_CHECK(y_begin < y_end && y_end <= y.size(), "computed_points: y range [{}, {}) of {} values", y_begin,
                y_end, y.size());
  std::uint64_t columns = 0;
  for (std::size_t i = y_begin; i < y_end; ++i) {
    const std::size_t image = y.size() - 1 - i;  // the mirror's column of -y (mirror.hpp: y symmetric)
    if (!mirrored || y[i] >= 0.0 || image < y_begin || image >= y_end) ++columns;
  }
  return table_points(scene, columns);
}

std::string describe_table_size(std::uint64_t points, std::uint64_t computed, std::uint64_t bytes, int threads,
                                PointCost cost) {
  const double per_thread = static_cast<double>(computed) / static_cast<double>(threads < 1 ? 1 : threads);
  const double low = cost.low, high = cost.high;
  const std::string mirrored =
      computed < points ? fmt::format(" ({} computed, the others their mirror images)", computed) : std::string();
  return fmt::format("table: {} grid points{}, {} in memory (the file is smaller: compressed); estimated time {} to "
                     "{} with {} thread{}\n",
                     points, mirrored, human_bytes(static_cast<double>(bytes)), human_seconds(per_thread * low),
                     human_seconds(per_thread * high), threads, threads == 1 ? "" : "s");
}

}  // namespace railtab
