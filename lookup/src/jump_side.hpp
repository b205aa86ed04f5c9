// SPDX-License-Identifier: Apache-2.0
// Contact jumps along y (format 2.1, docs/lookup.md "Contact jumps"): the lookup never
// interpolates across a located jump. A query whose (y, load) cell a jump may cut takes the
// one-sided path: per load node of its cell, the y interpolation uses only grid nodes on the
// query's side of the jump (the cell of that side nearest the query, extrapolated linearly up to
// the jump), then the load nodes are blended as usual. Every other query pays one flag test.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "grid.hpp"
#include "railtab/lookup.hpp"
#include "records.hpp"

namespace railtab::lookup::detail {

struct TableData;
class Hdf5File;

// Jump kinds (docs/table-format.md, "Contact jumps"): bits 0-5 change the rigid contact points,
// so every part jumps; bits 6-9 change only the loaded patches (normal, creep, wear).
inline constexpr std::uint32_t kGeometricJumps = 0x3Fu;

// What pairs a jump with its partner at the other load node of a cell: its geometric bits when it
// has any, else its whole kind. A rigid-point jump keeps its geometric bits from one load to the
// next, but whether a loaded patch appears or leaves a slot at it (bits 6-9) may change with the
// load (on worn_miniprof.toml's right wheel the jump at -5.07 mm is kind 68 at 60 kN and 4 at 100 kN).
inline std::uint32_t pairing_key(std::uint32_t kind) noexcept {
  return (kind & kGeometricJumps) ? (kind & kGeometricJumps) : kind;
}

// JumpWheel::partner of one load cell from its two nodes' kind lists a and b: a's jumps then b's,
// each paired with the jump of the same pairing key and rank (the k-th jump of that key) at the
// other node, -1 where that has none.
inline std::vector<int> kind_partners(const std::vector<std::uint32_t>& a, const std::vector<std::uint32_t>& b) {
  std::vector<int> partner;
  auto pair_into = [&](const std::vector<std::uint32_t>& from, const std::vector<std::uint32_t>& to) {
    for (std::size_t k = 0; k < from.size(); ++k) {
      const std::uint32_t key = pairing_key(from[k]);
      std::size_t rank = 0;
      for (std::size_t i = 0; i < k; ++i) rank += pairing_key(from[i]) == key;
      int found = -1;
      for (std::size_t i = 0, seen = 0; i < to.size() && found < 0; ++i)
        if (pairing_key(to[i]) == key && seen++ == rank) found = static_cast<int>(i);
      partner.push_back(found);
    }
  };
  pair_into(a, b);
  pair_into(b, a);
  return partner;
}

// One block's one-sided values at the jumps (format 2.1, /jumps/<wheel>/<part>): per slot, load
// node, jump and side (0 left, 1 right of the jump) a slice over the block's creepage axes, in the
// block's query record layout (values, then the statuses of the creepage CELL the record starts,
// folded as the block's: every bit but converged and full_slip ORed, those ANDed), with the block's value
// type (doubles as read, floats after narrow_exact_blocks when the block's are).
// One jump cell's sum over one block (weighted_sum.hpp, jump_sum): the records at end[e] +
// corner_off[c] (bytes) weighted by end_w[e] x corner_w[c], into out[0 .. n_values-1].
using JumpKernel = void (*)(const RecordPtr* end, const double* end_w, int n_ends,
                            const double* corner_w, const std::size_t* corner_off,
                            double* out) noexcept;

struct JumpSamples {
  RecordBytes data;
  std::size_t slot_stride = 0, load_stride = 0, jump_stride = 0, side_stride = 0;  // bytes
  // The block's shape as the one-sided query walks it, fixed at load: jump list (0 every jump,
  // 1 geometric only), first creepage dimension, load dimension (-1: none), creepage dimensions,
  // and the sum kernel for (creepage dimensions, values per record).
  int list = 0, inner0 = 0, load_dim = -1, n_inner = 0;
  JumpKernel sum = nullptr;
};

// The jumps of one wheel, as the query path reads them.
struct JumpWheel {
  bool load_axis = false;   // load is tabulated: one jump list per load node
  int load_cells = 1;       // cells of the load axis (1 when load is not tabulated)
  // [0]: every jump (normal, creep, wear blocks and blocks holding them), [1]: geometric jumps
  // only (a block holding the geometry part alone). y[list][load node], sorted.
  std::vector<std::vector<double>> y[2];
  std::vector<std::vector<std::uint32_t>> kind[2];  // [list][load node]: each jump's kind bits
  std::vector<unsigned char> matched[2];  // [list][load cell]: same jump count at both nodes
  // [list][load cell]: empty where both nodes list the same kinds in the same order (each jump
  // then moves with load, and the blended positions place the query: no jump crosses another).
  // Else (two jumps of different kinds cross between the load nodes, or a node has a jump the
  // other lacks) node l's jumps then node l+1's: the index, in the other node's list, of the jump
  // of the same pairing key and rank, -1 where it has none (kind_partners; crossing_pieces,
  // jump_piece.hpp).
  std::vector<std::vector<int>> partner[2];
  std::vector<unsigned char> cut;         // [y cell * load_cells + load cell]: a jump may cut it
  // Per list and load node, for the segment right of m jumps (m = 0 .. jumps): its first grid
  // node above the jump m-1 and its last grid node below jump m (the binary searches of the
  // query, done at load).
  std::vector<std::vector<int>> seg_first[2], seg_last[2];
  std::vector<std::vector<int>> index[2];  // [list][load node][k]: the jump's index in list 0
  // The jumps a query in y cell c can find either side of it (jumps_left, jump_piece.hpp), per list:
  // window[list][(load node * y_cells + c) * 2] jumps of the node lie left of the cell's first
  // node by more than a rounding margin (so left of every query in it, blended in load or not),
  // and those from window[..+ 1] on right of its last node by as much; only the ones between are
  // compared with the query (usually 0-2 of them instead of the whole list).
  std::vector<int> window[2];
  // The same for a load cell whose nodes list different kinds (partner not empty), with each jump
  // at both its positions (its own and its partner's): cross_window[list][((load cell * 2 + node)
  // * y_cells + c) * 2], crossing_pieces compares only the jumps between.
  std::vector<int> cross_window[2];
  int y_cells = 0;
  JumpSamples samples[kNumParts];          // per block of the wheel
  // Normalised creep coordinates (creep_map.hpp): the one-sided reciprocal creepage scales at the
  // jumps (the normal part's creep_scale_* at both ends of each jump, as the grid's in
  // CreepMap::scale), [(((slot * load nodes + load node) * jumps + jump) * 2 + side) * 3 + k].
  std::vector<double> inv_scale;
  std::size_t n_load_nodes = 1, n_jumps = 0;
};

// Reads /jumps (left_y, left_kind, right_y, right_kind) when the file has it, checks it and
// fills d.jumps; a table without it keeps d.has_jumps false (interpolation as before 2.1).
void read_jumps(const Hdf5File& f, TableData& d);

// Whether the query's (y, load) cell may be cut by a jump of wheel w (d.has_jumps must be true).
bool jump_cell(const TableData& d, int w, const AxisLoc* loc) noexcept;

// Cubic methods in a cell no jump cuts: marks the y and load stencil nodes that lie beyond a jump
// (a neighbouring cell of the stencil is cut) in loc[kVarY / kVarLoad].cut_stencil, so the cubic
// slopes come from the cell's side only (one-sided, as at a table edge) and never blend across.
void cubic_stencil_limits(const TableData& d, int w, AxisLoc* loc) noexcept;

// The one-sided interpolation of every block of wheel w, slots [slot_begin, slot_end), into
// contact[0 ..]: values and part statuses, as the block kernels write them (linear in every
// method: a cubic stencil would reach across the jump).
// With normalised creep coordinates (d.creep_map.active) `creepage` holds the query's physical
// creepages (locate_state): the creep block's v cell and the law use the slot's scales taken from
// the query's side of the jumps too (one-sided, as the normal part's values).
void interpolate_jump_cell(const TableData& d, int w, const AxisLoc* loc, const double* creepage,
                           int slot_begin, int slot_end, Contact* contact) noexcept;

}  // namespace railtab::lookup::detail
