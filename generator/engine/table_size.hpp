// SPDX-License-Identifier: Apache-2.0
// Size of a table before it is computed: grid points and bytes in memory, every product checked
// for overflow, compared with limits a flag can raise (--max-points, --max-bytes), and an
// estimate of the run time. Checked before anything proportional to the grid is allocated
// (docs/reliability.md, "Limits").
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "scene/scene.hpp"

namespace railtab {

struct SweepKernel;

inline constexpr std::uint64_t kDefaultMaxPoints = 20'000'000;       // fast models: 17-100 min on 2 cores [-]
inline constexpr std::uint64_t kDefaultMaxBytes = 4ull << 30;        // table in memory [B]
// Run time of one grid point (both wheels) per thread, as a range [s]. The engine does not know the
// physics: the kernel states its cost (SweepKernel::point_cost; kernel/contact_kernel.hpp).
struct PointCost {
  double low = 0.0;
  double high = 0.0;
};
// The fast models, per computed point: the whole run of tables/default_stripes.toml (the sweep, the
// one-sided values at its contact jumps and the error map, whose reference is the exact model)
// took user 2.9 s CPU for 9135 computed points, 0.31 ms each (docs/reliability.md, "Limits").
inline constexpr PointCost kFastPointCost{100e-6, 600e-6};
// The exact half-space model (normal_model = "halfspace", load coupling on), per COMPUTED point
// (a mirrored sweep computes the columns y >= 0 only): the sweep's coupled solves of both wheels
// and the share of the contact jumps' one-sided values and of the error map. Measured on
// tables/default.toml (docs/validation/exact-tables.md, "Generation cost"): the sweep
// 15.7 ms per computed point per thread, the whole run 22 ms CPU per computed point; the upper end
// allows a machine twice as slow or a grid denser in flange-onset jumps. At element size
// kExactPointCostElementSize; the kernel scales it by the elements per patch
// (contact_point_cost: 0.4 mm elements cost 0.56 times as much, measured 11 ms CPU per point).
inline constexpr PointCost kExactPointCost{0.015, 0.045};
inline constexpr double kExactPointCostElementSize = 0.3e-3;  // [m]

// a * b, or railtab::Error naming `what` when the product does not fit in 64 bits.
std::uint64_t checked_multiply(std::uint64_t a, std::uint64_t b, const std::string& what);

// Grid points of the table of `scene` with `y_count` y values (a shard's share): y x roll x load
// x xi x eta x phi (roll counts 1 with equilibrium roll). Throws railtab::Error on overflow.
std::uint64_t table_points(const Scene& scene, std::uint64_t y_count);

// Bytes of the in-memory table `kernel` makes for `scene` with `y_count` y values: every
// float64 output and uint32 status dataset of both wheels. Throws railtab::Error on overflow.
std::uint64_t table_bytes(const Scene& scene, const SweepKernel& kernel, std::uint64_t y_count);

// Throws railtab::Error when `points` exceeds `max_points` or `bytes` exceeds `max_bytes`,
// saying the size, the limit, the run time at `cost` per point and the flag that raises the limit.
void check_table_size(const Scene& scene, std::uint64_t points, std::uint64_t bytes, std::uint64_t max_points,
                      std::uint64_t max_bytes, PointCost cost);

// Grid points the sweep computes of the y range [y_begin, y_end) (y_begin < y_end <= the y count):
// all of table_points, or with the mirror (`mirrored`: engine/mirror.hpp) those of the columns
// y >= 0 and of the columns y < 0 whose mirror image -y lies outside the range (a shard's).
std::uint64_t computed_points(const Scene& scene, std::size_t y_begin, std::size_t y_end, bool mirrored);

// One line for the log: points (of which `computed` are solved, the rest mirror images), memory
// and the run time range of the computed points with `threads` threads at `cost` per point.
std::string describe_table_size(std::uint64_t points, std::uint64_t computed, std::uint64_t bytes, int threads,
                                PointCost cost);

}  // namespace railtab
