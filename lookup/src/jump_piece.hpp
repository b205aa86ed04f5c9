// SPDX-License-Identifier: Apache-2.0
// The y piece of a query in a jump cell (jump_side.hpp): which grid nodes or one-sided values at
// the jumps the query's side interpolates between, per load node of its cell. Shared by the
// generic one-sided path (jump_side.cpp) and the fused one of the default table's shape
// (fast_path.cpp), so both pick the same ends with the same fractions.
#pragma once

#include <algorithm>
#include <cstddef>
#include <limits>
#include <vector>

#include "creep_map.hpp"
#include "grid.hpp"
#include "jump_side.hpp"

namespace railtab::lookup::detail {

// One end of a y piece: a grid node of the block, or a one-sided value at a jump.
struct End {
  bool sample = false;
  int index = 0;   // grid node, or the jump's index in list 0
  int side = 0;    // sample: 0 left of the jump, 1 right
};

// The y piece of load node `node` (0 or 1 of the query's load cell) on the query's side of the
// jumps of `list`, and the grid cell whose status it carries (-1: the samples' only). The side
// comes from the jumps' positions interpolated in load when both nodes have the same number of
// them (else the node's own): the query lies in the segment between two jumps holding its y. At
// this node the segment's ends are the node's own jumps; the piece is the segment's grid cell
// holding y, or the part between a jump and the grid node next to it (one-sided value at the
// jump), or, with no grid node in the segment, between the two jumps' one-sided values.
struct Piece {
  End a, b;
  double t = 0.0;   // fraction from a to b, clamped to [0, 1]
  int cell = -1;    // y cell whose status the piece carries, -1: none
  bool spans = false;  // spans_jump: the answer blends two sides of a jump (low confidence)
};

// Jumps of `list` left of the query at load node `node` of its cell (0 or 1), counted without a
// branch per jump. The positions are sorted (the blend of two increasing lists with weights >= 0
// rounds to a non-decreasing one), so this is the first position above yq, as a search finds it.
// Only the jumps of the y cell's window (JumpWheel::window) are compared: those before it lie left
// of every query of the cell at both load nodes (so their blend too), those after it right.
// Blended positions do not depend on the node: callers count once for both.
inline std::size_t jumps_left(const JumpWheel& j, int list, const AxisLoc* loc, double yq, int node) noexcept {
  const int l = j.load_axis ? loc[kVarLoad].i : 0;
  const bool blend = j.load_axis && j.matched[list][static_cast<std::size_t>(l)];
  auto window = [&](int ln) -> const int* {
    return j.window[list].data() +
           (static_cast<std::size_t>(ln) * static_cast<std::size_t>(j.y_cells) + static_cast<std::size_t>(loc[kVarY].i)) * 2;
  };
  if (blend) {
    const double s = loc[kVarLoad].t;
    const std::vector<double>& lo_list = j.y[list][static_cast<std::size_t>(l)];
    const std::vector<double>& hi_list = j.y[list][static_cast<std::size_t>(l + 1)];
    const int* wa = window(l);
    const int* wb = window(l + 1);
    const std::size_t first = static_cast<std::size_t>(std::min(wa[0], wb[0]));
    const std::size_t last = static_cast<std::size_t>(std::max(wa[1], wb[1]));
    std::size_t m = first;
    for (std::size_t k = first; k < last; ++k) m += ((1.0 - s) * lo_list[k] + s * hi_list[k]) <= yq;
    return m;
  }
  const std::vector<double>& own = j.y[list][static_cast<std::size_t>(l + node)];
  const int* wn = window(l + node);
  std::size_t m = static_cast<std::size_t>(wn[0]);
  for (std::size_t k = m; k < static_cast<std::size_t>(wn[1]); ++k) m += own[k] <= yq;
  return m;
}

inline bool blended(const JumpWheel& j, int list, const AxisLoc* loc) noexcept {
  return j.load_axis && j.matched[list][static_cast<std::size_t>(loc[kVarLoad].i)];
}

// The piece of load node `node` with m jumps (jumps_left) left of the query.
inline Piece side_piece(const JumpWheel& j, const Axis& ya, int list, const AxisLoc* loc, double yq, int node,
                 std::size_t m) noexcept {
  const int l = j.load_axis ? loc[kVarLoad].i : 0;
  const std::size_t ln = static_cast<std::size_t>(l + node);
  const std::vector<double>& own = j.y[list][ln];
  const std::vector<int>& id = j.index[list][ln];
  const double* x = ya.nodes();
  const int n = ya.size();
  const bool has_lo = m > 0, has_hi = m < own.size();
  const double lo = has_lo ? own[m - 1] : -std::numeric_limits<double>::infinity();
  const double hi = has_hi ? own[m] : std::numeric_limits<double>::infinity();
  const int a = j.seg_first[list][ln][m];  // first node above lo
  const int b = j.seg_last[list][ln][m];   // last node below hi
  auto fraction = [](double v, double from, double to) { return std::clamp((v - from) / (to - from), 0.0, 1.0); };
  Piece p;
  if (b < a) {  // no grid node between the two jumps: their one-sided values
    p.a = End{true, id[m - 1], 1};
    p.b = End{true, id[m], 0};
    p.t = fraction(yq, lo, hi);
  } else if (has_lo && yq < x[a]) {  // between the lower jump and the segment's first node
    p.a = End{true, id[m - 1], 1};
    p.b = End{false, a, 0};
    p.t = fraction(yq, lo, x[a]);
    p.cell = a + 1 <= b ? a : -1;
  } else if (has_hi && yq > x[b]) {  // between the segment's last node and the upper jump
    p.a = End{false, b, 0};
    p.b = End{true, id[m], 0};
    p.t = fraction(yq, x[b], hi);
    p.cell = b - 1 >= a ? b - 1 : -1;
  } else if (b > a) {  // a grid cell of the segment
    const int c = std::clamp(loc[kVarY].i, a, b - 1);
    p.a = End{false, c, 0};
    p.b = End{false, c + 1, 0};
    p.t = fraction(yq, x[c], x[c + 1]);
    p.cell = c;
  } else {  // the segment's only node
    p.a = p.b = End{false, a, 0};
    p.cell = std::min(a, n - 2);
  }
  return p;
}

// Whether the query's answer blends two sides of a jump in a load cell whose nodes list different
// kinds of jumps (JumpWheel::partner; e.g. the tread-flange hand-over passing the flange root's
// point jump between two load nodes): a jump near the query's y cell (in either node's window)
// lies on one side of the query at its node and its partner, of the same kind, on the other; or
// it has no partner. The pieces pair the jumps by their order, which there pairs jumps of
// different kinds, so such a query reads one node's values from one side of the change and the
// other node's from the other: its slots' split and its angle are anywhere in between.
inline bool spans_jump(const JumpWheel& j, int list, const AxisLoc* loc, double yq) noexcept {
  const std::size_t l = static_cast<std::size_t>(loc[kVarLoad].i);
  const std::vector<int>& partner = j.partner[list][l];
  // On a load node (to the rounding of its located fraction) the query reads that node's sides.
  const double t = loc[kVarLoad].t;
  if (partner.empty() || t < 1e-9 || t > 1.0 - 1e-9) return false;
  const std::vector<double>* ys[2] = {&j.y[list][l], &j.y[list][l + 1]};
  for (std::size_t node = 0; node < 2; ++node) {
    const int* w = j.window[list].data() +
                   ((l + node) * static_cast<std::size_t>(j.y_cells) + static_cast<std::size_t>(loc[kVarY].i)) * 2;
    const std::size_t first = node == 0 ? 0 : ys[0]->size();
    for (int k = w[0]; k < w[1]; ++k) {
      const int p = partner[first + static_cast<std::size_t>(k)];
      if (p < 0 || (((*ys[node])[static_cast<std::size_t>(k)] <= yq) != ((*ys[1 - node])[static_cast<std::size_t>(p)] <= yq)))
        return true;
    }
  }
  return false;
}

// The pieces of both jump lists (0 every jump, 1 geometric only) at both load nodes of the
// query's cell (nodes: 2 with a load axis, else 1), shared by the blocks of a query.
inline void query_pieces(const JumpWheel& j, const Axis& ya, const AxisLoc* loc, int nodes, Piece pieces[2][2]) noexcept {
  const double* x = ya.nodes();
  const double yq = x[loc[kVarY].i] + loc[kVarY].t * (x[loc[kVarY].i + 1] - x[loc[kVarY].i]);
  std::size_t m0 = 0;
  for (int list = 0; list < 2; ++list)
    for (int k = 0; k < nodes; ++k) {
      const std::size_t m = k > 0 && blended(j, list, loc) ? m0 : jumps_left(j, list, loc, yq, k);
      if (k == 0) m0 = m;
      pieces[list][k] = side_piece(j, ya, list, loc, yq, k, m);
    }
  if (nodes == 2)
    for (int list = 0; list < 2; ++list)
      pieces[list][0].spans = pieces[list][1].spans = spans_jump(j, list, loc, yq);
}

// A field of `width` values per node of the normal part's grid g (creep_map.hpp: the creep scales,
// the linear creep coefficients) at the end e of a piece at absolute load node `load_node`:
// `grid` the slot's first node ([node * width + k]), `at_jump` the slot's one-sided values at
// the jumps ([((load node * jumps + jump) * 2 + side) * width + k], JumpWheel::inv_scale's layout).
inline const double* node_end_values(const NodeGrid& g, const JumpWheel& j, const double* grid, const double* at_jump,
                                     int width, std::size_t load_node, const End& e) noexcept {
  const std::size_t wd = static_cast<std::size_t>(width);
  if (e.sample)
    return at_jump + ((load_node * j.n_jumps + static_cast<std::size_t>(e.index)) * 2 + static_cast<std::size_t>(e.side)) * wd;
  const int ydim = g.dim_of(kVarY), ldim = g.dim_of(kVarLoad);
  const std::size_t node = static_cast<std::size_t>(e.index) * g.stride[ydim] + (ldim >= 0 ? load_node * g.stride[ldim] : 0);
  return grid + node * wd;
}

// The field on the query's side of a cut cell: list 0's pieces (the normal part's) at the cell's
// `nodes` load nodes from lc, blended with the load weights; grid and at_jump as node_end_values.
inline void one_sided_node_values(const NodeGrid& g, const JumpWheel& j, const double* grid, const double* at_jump,
                                  int width, const Piece* piece, int nodes, int lc, const double* weight,
                                  double* out) noexcept {
  for (int k = 0; k < width; ++k) out[k] = 0.0;
  for (int n = 0; n < nodes; ++n) {
    const std::size_t lnode = static_cast<std::size_t>(lc + n);
    const double* a = node_end_values(g, j, grid, at_jump, width, lnode, piece[n].a);
    const double* b = node_end_values(g, j, grid, at_jump, width, lnode, piece[n].b);
    const double t = piece[n].t;
    for (int k = 0; k < width; ++k) out[k] += weight[n] * ((1.0 - t) * a[k] + t * b[k]);
  }
}

// The slot's one-sided values at the jumps of a field laid out as JumpWheel::inv_scale.
inline const double* slot_at_jump(const JumpWheel& j, const std::vector<double>& at_jump, int width, int slot) noexcept {
  return at_jump.data() + static_cast<std::size_t>(slot) * j.n_load_nodes * j.n_jumps * 2 * static_cast<std::size_t>(width);
}

}  // namespace railtab::lookup::detail
