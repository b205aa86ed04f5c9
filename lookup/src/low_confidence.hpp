// SPDX-License-Identifier: Apache-2.0
// The low_confidence status bit (docs/lookup.md, "Low confidence"): where a query's answer spans a
// change the table does not resolve. Two rules, both from the table's own values:
// - at load, per interpolation cell and slot (block_layout.cpp, and the creepage cells of the
//   one-sided values at jumps, jump_side.cpp): the slot holds a contact at some corners and none
//   at others (holds_contact, from the nodes' statuses). Linear interpolation then blends a loaded contact
//   with nothing: the onset, lift-off or slot hand-over lies somewhere inside the cell, and the
//   interpolated force is anywhere between 0 and the loaded corner's. Cells a located contact jump
//   cuts are interpolated one-sided (jump_side.hpp) and do not read the cell's own status;
// - per query (mark_unpaired_contact): the slot carries a normal force but its geometry holds no
//   rigid point: the loaded patch crossed the flange angle before (or after)
//   its rigid point did, so the slot's contact angle, radius and position are not the patch's;
//   or the slot holds a touching rigid point but no normal force: its patch is in another slot at
//   zero creepage, and may be back in this one at the query's creepage.
// A third, per query in a cell a jump cuts, is the one-sided path's (crossing_pieces,
// jump_piece.hpp): between a crossing jump's positions at the cell's two load nodes, one node has
// no segment on the query's side of every jump, so the slots' split of the force is blended.
#pragma once

#include <cstddef>

#include "railtab/lookup.hpp"

namespace railtab::lookup::detail {

struct Block;
struct TableData;

// The load-balance rule: at a grid node or a one-sided value at a jump (zero creepage), the slots'
// normal forces N_s and the contact angles the table serves with them, delta_s (the geometry
// part's, the rigid point's), carry the vertical wheel load Q only when sum_s N_s cos(delta_s) ~ Q
// (docs/conventions.md, "Load control in track axes"). Where they miss it by more than this
// fraction of Q, the loaded patch and its rigid point part ways (the patch lags a rigid point
// that jumped, e.g. up the flange, or sits in the other slot): every cell that uses the node, and
// every piece that uses the one-sided value, is low confidence. The default table's nodes stay
// within 12.1 % (two rigid points competing at the flange root); the one-sided values right of the
// flange's point jump miss it by 50 %.
inline constexpr double kLoadBalanceLimit = 0.2;

// Applies the load-balance rule to a loaded table (before narrow_exact_blocks: double records).
// Only for tables of format 2.1 and later (railtab generate's, whose normal parts are solved under
// load control) whose geometry block is over y alone and whose normal block over y (and load):
// the shape railtab generate writes with roll following the equilibrium or fixed.
void mark_unbalanced_load(TableData& d);

// Whether a node's (or a cell's) part status says the slot holds a contact: solved (converged or
// not) and neither lifted off nor failed. An empty slot has status 0 in every part; a creep point
// whose patch sits in the other slot at that creepage, `converged,lift_off` (docs/table-format.md).
inline bool holds_contact(StatusBits s) noexcept {
  return (s & (status::kConverged | status::kNotConverged)) != 0 && (s & (status::kLiftOff | status::kFailed)) == 0;
}

// Whether the nodes corner_node[0 .. n_corners-1] of a cell disagree about holding a contact in
// any of the block's n_parts parts (status(node, part) gives a node's part status).
template <class Status>
bool mixed_presence(Status status, int n_parts, const std::size_t* corner_node, int n_corners) noexcept {
  for (int p = 0; p < n_parts; ++p) {
    int present = 0;
    for (int c = 0; c < n_corners; ++c) present += holds_contact(status(corner_node[c], p));
    if (present > 0 && present < n_corners) return true;
  }
  return false;
}

// Per query, after the slot's values and part statuses are set (every path of table.cpp and
// fast_path.cpp), kLowConfidence in the geometry part's status of
// - a slot that serves a normal force while its geometry part holds no rigid point (not solved at
//   some node of its cell or piece: an empty slot has status 0);
// - in tables of format 2.1 and later (TableData::load_controlled: a touching rigid point carries
//   load there; synthetic test tables need not hold physical values), a slot whose geometry holds
//   a touching rigid point (separation 0 at every node of its cell or piece) while it serves no
//   normal force: its loaded patch sits in another slot, which the
//   first case flags at zero creepage. With creepage the patch may be back in this slot (the
//   coupled load moves its angle, and the hand-over with it; jumps are located at zero
//   creepage), where the table holds nothing, so the slot's "no contact" is not the model's either.
//   Example: left wheel of the exact table at y = 5.593 mm, creepage (-1.89e-3, 3.17e-3, -0.086):
//   tread slot 0 kN read, 90.6 kN in the model. Both cases fire together at the hand-over, so the
//   flagged queries (any slot) are the same; a query of one slot sees its own flag.
inline void mark_unpaired_contact(bool has_geometry_and_normal, bool load_controlled, Contact& c) noexcept {
  if (!has_geometry_and_normal) return;
  const bool point = (c.part_status[kGeometry] & (status::kConverged | status::kNotConverged)) != 0;
  if (c.value[kNormalForce] != 0.0 ? !point : load_controlled && point && c.value[kSeparation] == 0.0)
    c.part_status[kGeometry] |= status::kLowConfidence;
}

}  // namespace railtab::lookup::detail
