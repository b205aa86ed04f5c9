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
  bool spans = false;  // crossing_pieces: no segment of a node puts the query on its side of every jump (low confidence)
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

// A patch hand-over between the slots (kind bits 6 and 7: the loaded patch leaves one slot and
// enters the other, no rigid point jumps) is located at zero creepage; under the load coupling the
// creepage moves it. Measured on the exact table (left wheel, 60 to 100 kN): the model's patch
// changes slot up to 6 um from the located jump's position interpolated in load (4.5 um left of it
// at 97.6 kN with spin -0.28 rad/m; 1.7 um right at 98.7 kN, xi -4e-3). Twice the largest seen.
inline constexpr std::uint32_t kPatchHandOver = 0xC0u;
inline constexpr double kHandOverCreepShift = 12e-6;  // m

// The pieces of a load cell whose nodes list different kinds of jumps (JumpWheel::partner; e.g.
// on the default scenes the tread-flange hand-over of the loaded patch, kind 192, passes the
// flange root's rigid-point jump, kind 3, between two load nodes). Pairing the jumps by their
// order there pairs jumps of different kinds, and a query would read one node's values from one
// side of a change and the other node's from the other (the patch's force split over both slots
// or counted from the wrong side of the rigid-point jump: the sum over the slots was off by up to
// 13 % of N on the exact table). So each jump is paired with the jump of the same kind (its
// geometric bits, or its whole kind without them: pairing_key, jump_side.hpp) and rank at the
// other node; its position interpolated in load between the two places the query on one side of
// it; and each node takes the segment of its own list that puts the query on that side of as
// many of its jumps as it can, geometric jumps (which change every part) first. Between the two
// positions of a crossing jump no segment of one node agrees with every side (the patch sits in
// one slot at one node and in the other at the other): that node's segment keeps the query's side
// of the geometric jumps, so the geometry and the sum over the slots stay right, and the answer is
// flagged low confidence (spans), as it is near a jump that one node lacks. On a load node (to the
// rounding of its located fraction) the query reads that node's own sides.
inline void crossing_pieces(const JumpWheel& j, const Axis& ya, int list, const AxisLoc* loc, double yq,
                            Piece pieces[2]) noexcept {
  const std::size_t l = static_cast<std::size_t>(loc[kVarLoad].i);
  const double s = loc[kVarLoad].t;
  const std::vector<int>& partner = j.partner[list][l];
  const std::vector<double>* ys[2] = {&j.y[list][l], &j.y[list][l + 1]};
  bool spans = false;
  std::size_t chosen[2];
  for (std::size_t node = 0; node < 2; ++node) {
    const std::vector<double>& own = *ys[node];
    const std::vector<double>& other = *ys[1 - node];
    const std::vector<std::uint32_t>& kind = j.kind[list][l + node];
    const std::size_t first = node == 0 ? 0 : ys[0]->size();
    const double own_weight = node == 0 ? 1.0 - s : s;
    // Whether jump k lies left of the query (at its position interpolated in load) and its weight.
    auto left = [&](std::size_t k) {
      const int p = partner[first + k];
      return (p < 0 ? own[k] : own_weight * own[k] + (1.0 - own_weight) * other[static_cast<std::size_t>(p)]) <= yq;
    };
    const long heavy = static_cast<long>(own.size()) + 1;  // more than all non-geometric jumps together
    auto weight = [&](std::size_t k) { return (kind[k] & kGeometricJumps) ? heavy : 1L; };
    // cost(m): the weights of the jumps that segment m (right of jumps 0 .. m-1) puts on the wrong
    // side of the query.
    const int* window = j.window[list].data() +
                        ((l + node) * static_cast<std::size_t>(j.y_cells) + static_cast<std::size_t>(loc[kVarY].i)) * 2;
    // Only the jumps of the cross window can lie on either side: those before it are left of the
    // query, those after it right, so the best segment lies in the window (cost(from): the window's
    // jumps left of the query).
    const int* cross = j.cross_window[list].data() +
                       ((l * 2 + node) * static_cast<std::size_t>(j.y_cells) + static_cast<std::size_t>(loc[kVarY].i)) * 2;
    const std::size_t from = static_cast<std::size_t>(cross[0]), to = static_cast<std::size_t>(cross[1]);
    long cost = 0;
    for (std::size_t k = from; k < to; ++k) {
      if (left(k)) cost += weight(k);
      // Near the query's y cell, a jump the other node lacks, or lists with other patch bits (a
      // patch appears at it at one load only), or one whose two positions straddle the query (a
      // patch hand-over's widened by kHandOverCreepShift): which slot holds the patch there moves
      // with the creepage too (the load coupling), so the slots' split is not resolved even where
      // both nodes agree on the sides.
      const int p = partner[first + k];
      if (static_cast<int>(k) >= window[0] && static_cast<int>(k) < window[1]) {
        const double margin = (kind[k] & kPatchHandOver) == kPatchHandOver && !(kind[k] & kGeometricJumps)
                                  ? kHandOverCreepShift : 0.0;
        const double y_other = p < 0 ? own[k] : other[static_cast<std::size_t>(p)];
        const bool same_kind = p >= 0 && j.kind[list][l + 1 - node][static_cast<std::size_t>(p)] == kind[k];
        if (!same_kind || (std::min(own[k], y_other) - margin <= yq && yq < std::max(own[k], y_other) + margin)) spans = true;
      }
    }
    long best = cost;
    std::size_t m_best = from;
    for (std::size_t m = from + 1; m <= to; ++m) {
      cost += left(m - 1) ? -weight(m - 1) : weight(m - 1);
      if (cost < best) best = cost, m_best = m;
    }
    chosen[node] = m_best;
    if (best > 0) spans = true;
  }
  if (s < 1e-9 || s > 1.0 - 1e-9) spans = false;  // on a load node: the other node weighs nothing
  for (int node = 0; node < 2; ++node) {
    pieces[node] = side_piece(j, ya, list, loc, yq, node, chosen[node]);
    pieces[node].spans = spans;
  }
}

// The pieces of both jump lists (0 every jump, 1 geometric only) at both load nodes of the
// query's cell (nodes: 2 with a load axis, else 1), shared by the blocks of a query.
inline void query_pieces(const JumpWheel& j, const Axis& ya, const AxisLoc* loc, int nodes, Piece pieces[2][2]) noexcept {
  const double* x = ya.nodes();
  const double yq = x[loc[kVarY].i] + loc[kVarY].t * (x[loc[kVarY].i + 1] - x[loc[kVarY].i]);
  std::size_t m0 = 0;
  for (int list = 0; list < 2; ++list) {
    if (nodes == 2 && !j.partner[list][static_cast<std::size_t>(loc[kVarLoad].i)].empty()) {
      crossing_pieces(j, ya, list, loc, yq, pieces[list]);
      continue;
    }
    for (int k = 0; k < nodes; ++k) {
      const std::size_t m = k > 0 && blended(j, list, loc) ? m0 : jumps_left(j, list, loc, yq, k);
      if (k == 0) m0 = m;
      pieces[list][k] = side_piece(j, ya, list, loc, yq, k, m);
    }
  }
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
