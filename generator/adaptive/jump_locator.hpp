// SPDX-License-Identifier: Apache-2.0
// Contact jumps along y (docs/table-format.md, "Contact jumps"): per wheel and load node, the y
// where the contact configuration changes discontinuously, located by bisection on the contact
// chain (ContactProbe, zero creepage, roll as the table's) to a tolerance, so the lookup never
// interpolates across one (docs/lookup.md, "Contact jumps").
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "scene/scene.hpp"
#include "engine/sweep.hpp"
#include "table/table.hpp"

namespace railtab {

// Kind bits of one jump (several may be set; slot 0 tread, slot 1 flange). Geometric kinds change
// the rigid contact points, so every part jumps; the others change only the loaded patches
// (normal, creep, wear parts).
namespace jump_kind {
constexpr std::uint32_t kPointSlot0 = 1u << 0;      // a rigid contact point appears/vanishes in slot 0
constexpr std::uint32_t kPointSlot1 = 1u << 1;      //   ... in slot 1 (flange onset of the geometry)
constexpr std::uint32_t kSwitchSlot0 = 1u << 2;     // two points compete for slot 0 / the kept one switches
constexpr std::uint32_t kSwitchSlot1 = 1u << 3;
constexpr std::uint32_t kPointMoveSlot0 = 1u << 4;  // the rigid point of slot 0 jumps (rolling radius step)
constexpr std::uint32_t kPointMoveSlot1 = 1u << 5;
constexpr std::uint32_t kPatchSlot0 = 1u << 6;      // a loaded patch appears/vanishes in slot 0 (lift-off)
constexpr std::uint32_t kPatchSlot1 = 1u << 7;      //   ... in slot 1 (flange onset under load)
constexpr std::uint32_t kPatchMoveSlot0 = 1u << 8;  // the loaded patch of slot 0 jumps (rolling radius step)
constexpr std::uint32_t kPatchMoveSlot1 = 1u << 9;
constexpr std::uint32_t kGeometric = 0x3Fu;          // bits 0-5
constexpr std::uint32_t kAll = 0x3FFu;
}  // namespace jump_kind

struct JumpLocatorOptions {
  double tolerance = 1e-6;      // width of the final bisection interval [m]
  double radius_step = 5e-5;    // a rolling-radius change this large across `tolerance` is a jump [m]
  bool mirror = true;           // on a mirror-symmetric scene (engine/mirror.hpp) the right wheel's
                                //   jumps and one-sided values are the mirror images of the left
                                //   wheel's; false: both computed (the reference of the mirror's tests)
};

struct ContactJump {
  double y = 0.0;               // midpoint of the final interval [m]; grid nodes lie outside it
  std::uint32_t kind = 0;       // jump_kind bits
  double left = 0.0, right = 0.0;  // the final interval's ends (right - left <= tolerance) [m]
};

// jumps[wheel][load node] sorted by y (wheel 0 left, 1 right; one load entry when load is fixed).
struct ContactJumps {
  std::vector<std::vector<ContactJump>> wheel[2];
  std::size_t evaluations = 0;  // configuration evaluations spent (one wheel and load each) [-]
};

// Progress of a stage (tasks done of all; called from the workers, serialised, at most every
// 0.25 s and once at the end); empty = none.
using StageProgress = std::function<void(const SweepProgress&)>;

// Every jump inside the y grid of `scene` (between its first and last node), per wheel and load
// node; with `cells`, only those in y cells [first, last) (cell i lies between nodes i and i + 1:
// a shard's cells, joined by merge). Deterministic, and each cell's jumps do not depend on the
// others; `threads` as the sweep's (0 = all cores). Scenes with a roll axis are not
// supported (returns no jumps: the caller writes none). Each step evaluates the contact
// configuration of one wheel at one load (ContactProbe::configuration: geometry and normal
// contact, no creep forces; for the exact model the exact normal problem only in states with
// two or more candidate patches). progress counts the y nodes and the cells evaluated. With
// options.mirror on a mirror-symmetric scene (engine/mirror.hpp) the right wheel's jumps in a cell
// whose mirror cell is among `cells` are the left wheel's there, mirrored (the same bisection
// steps negated, so the same numbers).
struct CellRange {
  std::size_t first = 0;                                      // first y cell [-]
  std::size_t last = std::numeric_limits<std::size_t>::max();  // one past the last (clamped to the grid) [-]
};
ContactJumps locate_jumps(const Scene& scene, const JumpLocatorOptions& options = {}, int threads = 0,
                          const StageProgress& progress = {}, CellRange cells = {});

// Adds the group `root` (datasets left_y, left_kind, right_y, right_kind over (load, jump) or
// (jump)) and the one-sided values (add_jump_samples) to `table`. Nothing is added when the scene
// has a roll axis or no jump was found. `root` is kJumpGroup for a table, kShardJumpGroup for a
// shard (its jumps may lie in the cell after its last y node, outside its own y axis; merge joins
// them into kJumpGroup). threads and progress: those of add_jump_samples.
void add_jumps(Table& table, const Scene& scene, const ContactJumps& jumps, const JumpLocatorOptions& options = {},
               int threads = 0, const StageProgress& progress = {}, const std::string& root = kJumpGroup);

// One-sided values: every output of every part of the contact kernel at the ends of each jump's
// final interval (side 0 = left end, 1 = right end), added as groups <root>/<wheel>/<part> with
// datasets over ([load,] jump, side, the part's creepage axes, slot). add_jumps calls it. Each
// column is computed for the jump's wheel only (ColumnState::wheels); an end that lies on a y node
// of `table` is copied from the sweep's column there, and an end two jumps share is computed once
// (the same bytes either way); progress counts the columns computed or copied.
// With `mirror` on a mirror-symmetric scene, a right-wheel end whose mirror -y is a left-wheel
// end at the same load is that column's mirror image (engine/mirror.hpp), not computed again.
void add_jump_samples(Table& table, const Scene& scene, const ContactJumps& jumps, int threads = 0,
                      const StageProgress& progress = {}, const std::string& root = kJumpGroup, bool mirror = true);

// The names of the jump-list and side dimensions: plain dimensions, not axes (no coordinate).
inline constexpr const char* kJumpDimension = "jump";
inline constexpr const char* kSideDimension = "side";

}  // namespace railtab
