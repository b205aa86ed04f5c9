// SPDX-License-Identifier: Apache-2.0
// The error map stored in every table (format 2.3, docs/table-format.md "Error map"): the table
// against its own model at off-grid states (the lookup's interpolation of the written file
// against the model run directly), and that model against the exact half-space model, per
// region = y band x contact slot.
//
// Bands are groups of kCellsPerBand consecutive y cells (aligned to y nodes), so they do not
// depend on how a run is split. Every sample state is a fixed function of its index (an additive
// low-discrepancy sequence, no random generator), and every sample is computed on its own: the
// map is the same bytes for any thread count, for MPI (rank 0 computes it on the full table)
// and for shards (`railtab merge` computes it on the merged table with this same function).
#pragma once

#include <array>
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "scene/scene.hpp"
#include "table/merge.hpp"
#include "table/table.hpp"

namespace railtab {

inline constexpr const char* kErrorMapAttribute = "error_map_sampling";  // flat JSON text
inline constexpr const char* kBandDimension = "band";

inline constexpr std::size_t kCellsPerBand = 4;        // y cells per band
inline constexpr std::size_t kModelSamplesPerBand = 12;  // table vs model states per band
inline constexpr std::size_t kExactSamplesPerBand = 1;   // model vs exact states per band (the
                                                         //   first of the band's states)

// One off-grid state of the map: its band and y cell, the state, and the sequence index that
// fixes it.
struct ErrorSample {
  std::size_t band = 0, cell = 0;
  double y = 0.0, roll = 0.0, load = 0.0;
  double yaw = 0.0;  // 0 for a scene without yaw [rad]
  std::array<double, 3> creepage{};  // xi, eta [-], phi [rad/m]
};

// The states of the map of a table with y nodes `y_nodes` (the table's own y axis) over `scene`'s
// load, roll, yaw and creepage ranges. `sequence_offset` shifts the index sequence (0 for the stored
// map; tests use another offset for an independent sampling).
std::vector<ErrorSample> error_samples(const Scene& scene, const std::vector<double>& y_nodes,
                                       std::size_t samples_per_band = kModelSamplesPerBand,
                                       std::size_t sequence_offset = 0);

// What is compared at one sample and slot, both wheels pooled: fx, fy in % of mu N, mz in % of
// mu N c (c = sqrt(area / pi), the contact's radius), the normal force in % of itself, the
// contact angle in rad. N and area are the larger of the two sides' (so a contact that one side
// misses counts in full); a slot empty on both sides is not a sample; the contact angle counts
// only where both sides have the slot loaded.
inline constexpr std::size_t kErrorQuantities = 5;
inline constexpr const char* kErrorQuantityNames[kErrorQuantities] = {"fx", "fy", "mz", "normal_force",
                                                                       "contact_angle"};
inline constexpr const char* kErrorQuantityUnits[kErrorQuantities] = {"% of mu N", "% of mu N", "% of mu N c",
                                                                       "%", "rad"};

// Contact values of one slot of one wheel, as compared.
struct SlotValues {
  double fx = 0.0, fy = 0.0, mz = 0.0, normal_force = 0.0, area = 0.0, contact_angle = 0.0;
};
// The errors of `value` against `reference` (kErrorQuantities entries; NaN where a quantity does
// not count, see above), or an empty vector when the slot is empty on both sides.
std::vector<double> slot_errors(const SlotValues& value, const SlotValues& reference, double friction, double load);

// The model of `scene` run directly at `sample` (the contact kernel's code path: the same slots,
// sums and load control as the sweep, without the creep coefficients, which are not compared)
// with the normal model `model`: [wheel][slot], the wheels of
// `wheels` only (bit 0 left, bit 1 right; the others stay zero). `geometry` is
// make_geometry_solver(scene), made once.
using SampleValues = std::array<std::array<SlotValues, 2>, 2>;
SampleValues model_at(const Scene& scene, const ContactGeometrySolver& geometry, const ErrorSample& sample,
                      NormalModel model, unsigned wheels = 3u);

// The normal model of the table at y cell `cell` (the scene's, or with a model choice the one of
// the cell's lower node).
NormalModel model_of_cell(const Scene& scene, std::size_t cell);

// The error map of the table file `written` (made from `scene`) as the group kErrorMapGroup, and
// the text of the root attribute kErrorMapAttribute. Runs the samples on `threads` threads.
struct ErrorMap {
  std::vector<TableGroup> groups;
  std::string sampling;  // flat JSON
  double seconds = 0.0;        // wall time [s]
  double exact_seconds = 0.0;  // of which the exact model's states [s]
  std::size_t model_states = 0, exact_states = 0;
};
ErrorMap compute_error_map(const Scene& scene, const std::filesystem::path& written, int threads);

// Adds the map to `table` (replacing an older one).
void add_error_map(Table& table, ErrorMap map);

// The map of a merged table (railtab merge), from the scene text it carries (root attribute
// `scene`, profile files relative to the working directory) and its per-y model choice (root
// dataset normal_model_index): the single run's map, byte for byte. `written` is `table` on disk.
void add_error_map_of_merged(Table& table, const std::filesystem::path& written, int threads);
// The same as the finishing step of merge_table_files (what `railtab merge` passes).
MergeFinish error_map_merge_finish(int threads = 0);

}  // namespace railtab
