// SPDX-License-Identifier: Apache-2.0
// Size of a table before it is computed: grid points and bytes in memory, every product checked
// for overflow, compared with limits a flag can raise (--max-points, --max-bytes), and an
// estimate of the run time. Checked before anything proportional to the grid is allocated
// (docs/reliability.md, "Limits").
#pragma once

#include <cstdint>
#include <string>

#include "scene/scene.hpp"

namespace railtab {

struct SweepKernel;

inline constexpr std::uint64_t kDefaultMaxPoints = 20'000'000;       // about 30-70 min on 2 cores [-]
inline constexpr std::uint64_t kDefaultMaxBytes = 4ull << 30;        // table in memory [B]
// Run time of one grid point (both wheels) per thread, as a range [s]. The engine does not know the
// physics: the kernel states its cost (SweepKernel::point_cost; kernel/contact_kernel.hpp).
struct PointCost {
  double low = 0.0;
  double high = 0.0;
};
// The fast models, the range measured on the shipped scenes (docs/validation.md: 57 us for
// tables/default.toml; flange-heavy scenes up to ~200 us).
inline constexpr PointCost kFastPointCost{50e-6, 200e-6};
// The exact half-space model (normal_model = "halfspace", load coupling on): two coupled solves
// (both wheels) and the share of the contact jumps' one-sided values; measured 0.06 s CPU per point
// on tables/default_halfspace.toml (2026-11-26), up to twice that on flange-heavy grids.
inline constexpr PointCost kExactPointCost{0.04, 0.12};

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

// One line for the log: points, memory and the run time range with `threads` threads at `cost`
// per point.
std::string describe_table_size(std::uint64_t points, std::uint64_t bytes, int threads, PointCost cost);

}  // namespace railtab
