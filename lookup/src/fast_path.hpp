// SPDX-License-Identifier: Apache-2.0
// One fused query for the shape of table users get (tables/default.toml: linear method, y and
// load located, normalised creep coordinates over xi, eta and phi, blocks geometry (y), normal
// (y, load) and creep + wear (y, load, xi, eta, phi)): the cell search, the three blocks, the
// creep map and the law in one function without the generic per-variable and per-block loops,
// with the long-latency work (the sine and cosine of the contact angle, the creep records'
// loads) started early. A yaw axis (format 2.4) is the same shape with yaw after y in every block
// and in the creep scales (value queries; such a table has no jumps). Same operations in the same
// order as the generic path (table.cpp, interpolate_linear.cpp), so the same bytes; any other table
// takes the generic path. The derivative query of the yaw-free shape too (FastDerivatives).
#pragma once

#include <vector>

#include "railtab/lookup.hpp"

namespace railtab::lookup::detail {

struct TableData;

// Interpolates slots [slot_begin, slot_end) of wheel w (0 or 1) into contact[0 ..] and sets q to
// the query bits, as locate_state + interpolate_slots would. Returns false, writing nothing, when
// a variable is not finite (the caller takes the generic path, which flags it).
using FastQuery = bool (*)(const TableData& d, int w, const State& state, int slot_begin,
                           int slot_end, Contact* contact, StatusBits& q) noexcept;

// The same with the partial derivatives (Table::query_derivatives) of slots [slot_begin,
// slot_end): the values query() gives into contact[0 ..], and into deriv[slot - slot_begin] those
// of derivatives.cpp's generic path (the same formulas on
// the cell, scales and creepage cells the value pass found; the gradient of the creep cell from
// its corners read once more). Returns false, writing nothing, when a variable is not finite or
// a located jump cuts the cell and the cut cells are not fused (FastPath::cut: the generic path).
using FastDerivatives = bool (*)(const TableData& d, int w, const State& state, int slot_begin, int slot_end,
                                 Contact* contact, double (*deriv)[kNumOutputs][kNumVariables],
                                 StatusBits& q) noexcept;

struct FastPath {
  FastQuery query = nullptr;  // null: the table does not have the shape (generic path)
  FastDerivatives derivatives = nullptr;  // set with query (not for a yaw table)
  int geometry = -1, normal = -1, creep = -1;  // its blocks
  bool cut = false;  // cells a located jump cuts fused too (else interpolate_jump_cell)
  // Per wheel, [(slot * y cells + y cell) * load cells + load cell]: 1 when every creep record on
  // the cell's four (y, load) nodes is zero (no contact there: the generator writes an empty
  // slot's records as zeros). Made for any linear table with normalised creep coordinates whose
  // creep block ends in its creepage dimensions, over its empty_outer leading dimensions (y,
  // load, and roll or yaw when tabulated; the index is the same mixed radix): the generic query
  // (table.cpp) skips those cells as the fused one does. The creep block's interpolant is then 0 over the whole cell, so the
  // derivative query writes its rows as zeros without the gradient and the chain rule: exact, as
  // every term of the chain is a product with a zero derivative or with N = 0.
  std::vector<unsigned char> empty_creep[2];
  // The same cells, 2 when moreover every creepage cell over them carries the same part statuses
  // (empty_status[w][cell * 2 + p], parts p of the creep block): the value query then skips the
  // creepage cell search and the corner sum, writing the sum's zeros and those statuses (the
  // float sum of zero records is +0.0, so the same bytes). Mostly the flange slot without contact.
  std::vector<StatusBits> empty_status[2];
  int empty_outer = 0;  // leading dimensions of the creep block the cells are over (0: not made)
};

// Chooses d.fast for a loaded table (table_load.cpp, last step).
void prepare_fast_path(TableData& d);

}  // namespace railtab::lookup::detail
