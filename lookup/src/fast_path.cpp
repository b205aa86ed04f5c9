// SPDX-License-Identifier: Apache-2.0
// The fused query of fast_path.hpp. Every value is computed with the same operations in the same
// order as the generic path: locate_state and interpolate_normalised_creep (table.cpp), the
// linear kernels (interpolate_linear.cpp, weighted_sum.hpp) and interpolate_scales (creep_map.cpp), so
// both paths give the same bytes (scripts/lookup_result_dump.cpp compares them; the test
// FastPath.SameBytesAsTheGenericPath runs both on the default table's shape). The derivative
// query (fast_derivatives) runs the same slot code with its gradients beside the values.
#include "fast_path.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <initializer_list>

#include "block_gradient.hpp"
#include "interpolate.hpp"
#include "jump_piece.hpp"
#include "low_confidence.hpp"
#include "part_spec.hpp"
#include "table_data.hpp"
#include "weighted_sum.hpp"

namespace railtab::lookup::detail {
namespace {

double state_var(const State& s, int var) noexcept {
  switch (var) {
    case kVarY: return s.y;
    case kVarRoll: return s.roll;
    case kVarLoad: return s.load;
    case kVarXi: return s.xi;
    case kVarEta: return s.eta;
    case kVarYaw: return s.yaw;
    default: return s.phi;
  }
}

template <int NV>
inline void store_values(const Block& b, const SumsSse2<NV, double>& sums, Contact& c) noexcept {
  if (b.first_output >= 0) {
    sums.store(c.value + b.first_output);
  } else {
    double v[NV];
    sums.store(v);
    for (int k = 0; k < NV; ++k) c.value[b.output_of[k]] = v[k];
  }
}

// The cell's part statuses of a block (query layout: after the values of the cell's first record)
// whose NP parts are consecutive from `first` (checked at load): one copy.
template <int NP>
inline void store_status_run(int first, const Block& b, RecordPtr cell_record, Contact& c) noexcept {
  std::memcpy(&c.part_status[first], cell_record + b.status_offset, NP * sizeof(StatusBits));
}

// Zeroes the parts the table does not hold (interpolate_slots does it first).
inline void zero_absent(const TableData& d, Contact& c) noexcept {
  for (int a = 0; a < d.n_absent; ++a) {
    const PartSpec& spec = kPartSpecs[d.absent_part[a]];
    for (int k = 0; k < spec.n_out; ++k) c.value[spec.first_output + k] = 0.0;
    c.part_status[d.absent_part[a]] = 0;
  }
}

// The slot's status from its part statuses and the query bits (as interpolate_slots).
inline void fold_status(const TableData& d, StatusBits q, Contact& c) noexcept {
  mark_unpaired_contact(true, d.load_controlled, c);  // the fast path's tables hold geometry and normal parts
  StatusBits any = 0, all = ~0u;
  for (int p = 0; p < kNumParts; ++p) {
    if (!d.has_part[p]) continue;
    any |= c.part_status[p];
    all &= c.part_status[p];
  }
  c.status = (any & ~status::kConverged) | (all & status::kConverged) | q;
  c.reserved = 0;
}

// What the derivative query adds to regular_slot: where the slot's derivatives go (rows by Output,
// zeroed here) and the variables held at the table's edge (their columns stay 0).
struct DerivativeSink {
  double (*d)[kNumVars] = nullptr;
  unsigned frozen = 0;  // bit var: clamped
};

// A row of derivatives over the state variables: y, load and the three creepages (roll 0: the
// fast path's tables do not tabulate it).
__attribute__((always_inline)) inline void set_row(double* row, double y, double load, double xi, double eta,
                                                   double phi) noexcept {
  static_assert(kVarY == 0 && kVarRoll == 1 && kVarLoad == 2 && kVarXi == 3 && kVarEta == 4 && kVarPhi == 5 &&
                kVarYaw == 6 && kNumVars == 7);
  row[0] = y, row[1] = 0.0, row[2] = load, row[3] = xi, row[4] = eta, row[5] = phi, row[6] = 0.0;  // no roll, yaw axis
}

// d value / d t of a bilinear cell over (y, load) for the value at f00 (lower y, lower load),
// f01 (lower y, upper load), f10, f11: along y and along load.
inline void bilinear_dt(double f00, double f01, double f10, double f11, double ty, double tl, double& dy,
                        double& dl) noexcept {
  dy = (1.0 - tl) * (f10 - f00) + tl * (f11 - f01);
  dl = (1.0 - ty) * (f01 - f00) + ty * (f11 - f10);
}

// The rows of the parts the table does not hold: 0 (the derivative query's zero_absent).
inline void zero_absent_rows(const TableData& d, double (*dd)[kNumVars]) noexcept {
  for (int a = 0; a < d.n_absent; ++a) {
    const PartSpec& spec = kPartSpecs[d.absent_part[a]];
    for (int k = 0; k < spec.n_out; ++k) set_row(dd[spec.first_output + k], 0.0, 0.0, 0.0, 0.0, 0.0);
  }
}

// Creepage axis q's rows: dxn = d xn / d var of its normalised creepage xn = creepage inv (through
// the scale's dinv row, and the creepage itself unless it is clamped), dv = d v / d var of its coordinate.
inline void creepage_rows(const CreepMap& map, int q, double creepage, double inv, double xn, const double* dinv,
                          bool clamped, double* dxn, double* dv) noexcept {
  set_row(dxn, creepage * dinv[kVarY], creepage * dinv[kVarLoad], 0.0, 0.0, 0.0);
  if (!clamped) dxn[kVarXi + q] = inv;
  coordinate_gradient(map, q, xn, inv, dxn, dinv, dv);
}

// The creep block's rows from its gradient g (y and load per SI unit, the v coordinates per unit
// v) chained through dv, then the forces in N and their derivatives (denormalise_creep on c.value
// and its gradient), the clamped variables' columns cleared. `block_values`: the creep block's
// values the gradient's chain reads, in record order (the double sum of its walk, as the generic
// derivatives read them; c.value may hold the float sum of float records).
inline void finish_creep_gradient(const TableData& d, const Block& cb, const BlockGradient& g, const double (*dv)[kNumVars],
                                  const double* xn, const double (*dxn)[kNumVars], double cos_angle, double sin_angle,
                                  unsigned frozen, const double* block_values, Contact& c,
                                  double (*dd)[kNumVars]) noexcept {
  const CreepMap& map = d.creep_map;
  chain_creep_coordinates(cb, g, dv, dd);
  double stored[kNumOutputs];  // the values denormalise_creep_gradient reads
  for (int o : {kContactAngle, kNormalForce, kFx, kFy, kMz}) stored[o] = c.value[o];
  for (int k = 0; k < cb.n_values; ++k) stored[cb.output_of[k]] = block_values[k];
  denormalise_creep(map, xn, cos_angle, sin_angle, c.value);
  denormalise_creep_gradient(map, xn, dxn, stored, cos_angle, sin_angle, dd);
  if (frozen)
    for (int var = 0; var < kNumVars; ++var)
      if (frozen >> var & 1u)
        for (int o = 0; o < kNumOutputs; ++o) dd[o][var] = 0.0;
}

// A yaw table's fused query keeps its yaw cell in the compact location array (fast_query locates
// y, load and yaw only) at this index, after load: the slot of kVarXi, which the fused query never
// locates (the creepage cells depend on the slot's scales).
constexpr int kYawLoc = kVarLoad + 1;

// One slot of a cell no jump cuts. NG, NN, NC: values per record of the geometry, normal and creep
// blocks; NP: parts of the creep block (creep, or creep and wear); TC: the creep block's value
// type (float for format 2.2, Block::value_bytes; the geometry and normal blocks hold doubles).
// kGrad: also the partial derivatives (into grad), derivatives.cpp's formulas on the cell, scales
// and creepage cells found here once; the values are the plain query's, the same code. kYaw: the
// blocks have a yaw dimension after y (geometry (y, yaw), normal and scales (y, yaw, load), creep
// (y, yaw, load, creepages)), its cell at loc[kYawLoc]; value queries only.
template <int NG, int NN, int NC, int NP, bool kAvx2, class TC, bool kGrad = false, bool kYaw = false>
void regular_slot(const TableData& d, int w, const AxisLoc* loc, const double* creepage, StatusBits q,
                  int s, Contact& c, const DerivativeSink* grad = nullptr) noexcept {
  static_assert(!(kGrad && kYaw), "a yaw table's derivative query takes the generic path");
  const FastPath& fp = d.fast;
  const Block& gb = d.block[w][fp.geometry];
  const Block& nb = d.block[w][fp.normal];
  const Block& cb = d.block[w][fp.creep];
  const CreepMap& map = d.creep_map;
  const std::size_t slot = static_cast<std::size_t>(s);
  zero_absent(d, c);
  const AxisLoc ly = loc[kVarY], ll = loc[kVarLoad];
  // The creep block's outer dimensions (y, load, or y, yaw, load): their cells and t and 1 - t, in
  // the generic kernels' order (first dimension first). The geometry block is over the first
  // kOuter - 1 of them, the normal block and the scales over all.
  constexpr int kOuter = kYaw ? 3 : 2;
  AxisLoc outer[kOuter];
  outer[0] = ly;
  if constexpr (kYaw) outer[1] = loc[kYawLoc];
  outer[kOuter - 1] = ll;
  double t2[kOuter], u2[kOuter];
  for (int k = 0; k < kOuter; ++k) t2[k] = outer[k].t, u2[k] = 1.0 - outer[k].t;
  // Every row of dd is written whole (no zeroing first: it costs as much as the rows): a block's
  // rows with their variables' columns, the others 0.
  double (*dd)[kNumVars] = nullptr;
  double iw_y = 0.0, iw_load = 0.0;
  bool empty = false;  // kGrad: the creep block is zero over the cell (FastPath::empty_creep)
  std::size_t empty_cell = slot;  // mixed radix over the outer cells (mark_empty_creep_cells)
  for (int k = 0; k < kOuter; ++k)
    empty_cell = empty_cell * static_cast<std::size_t>(cb.size[k] - 1) + static_cast<std::size_t>(outer[k].i);
  // The value query over an empty cell with one set of creep statuses: no creepage cell, no sum.
  const bool skip = !kGrad && fp.empty_creep[w][empty_cell] == 2;
  if constexpr (kGrad) {
    dd = grad->d;
    zero_absent_rows(d, dd);
    iw_y = inverse_width(d.axis[kVarY], ly);
    iw_load = inverse_width(d.axis[kVarLoad], ll);
    empty = fp.empty_creep[w][empty_cell] != 0;
  }

  // Geometry (y), first: its contact angle's sine and cosine (normal_from_share) are the longest
  // computation of the query, and depend on nothing else, so they overlap with what follows.
  RecordPtr g = gb.data.data() + slot * gb.slot_size;
  for (int k = 0; k < kOuter - 1; ++k) g += static_cast<std::size_t>(outer[k].i) * gb.stride[k];
  {
    SumsSse2<NG, double> sums;
    sums.zero();
    walk_corners_sse2<kOuter - 1, 0>(g, 1.0, t2, u2, gb.stride, sums);
    store_values(gb, sums, c);
    store_status_run<1>(kGeometry, gb, g, c);
  }
  if constexpr (kGrad)
    for (int k = 0; k < NG; ++k)
      set_row(dd[gb.output_of[k]], (record_value<double>(g + gb.stride[0], k) - record_value<double>(g, k)) * iw_y,
              0.0, 0.0, 0.0, 0.0);
  double cos_angle = 0.0, sin_angle = 0.0;
  if (map.vertical_share) {
    angle_cos_sin(c.value[kContactAngle], cos_angle, sin_angle);
  }

  // The slot's reciprocal scales at (y, load) (interpolate_scales, bilinear), the normalised
  // creepages and their cells (interpolate_normalised_creep): the creep records' address.
  double inv[3];
  double dinv[3][kNumVars], dxn[3][kNumVars], dv[3][kNumVars], iw_v[3];  // kGrad
  {
    const double* base = map.scale[w].data() + slot * map.nodes * 3;
    std::size_t origin = 0;
    for (int k = 0; k < kOuter; ++k) origin += static_cast<std::size_t>(outer[k].i) * map.stride[k];
    if constexpr (kYaw) {  // interpolate_node_values' corner loop, as the generic path
      const double* p = base + origin * 3;
      for (int k = 0; k < 3; ++k) inv[k] = 0.0;
      for (int corner = 0; corner < 8; ++corner) {
        double wc = 1.0;
        std::size_t node = 0;
        for (int dim = 0; dim < 3; ++dim) {
          const bool upper = (corner >> dim) & 1;
          wc *= upper ? t2[dim] : 1.0 - t2[dim];
          node += upper ? map.stride[dim] : 0;
        }
        const double* v = p + node * 3;
        for (int k = 0; k < 3; ++k) inv[k] += wc * v[k];
      }
    } else {
      bilinear_node_values(base + origin * 3, map.stride[0], map.stride[1], 3, ly.t, ll.t, inv);
    }
    if (kGrad && !empty) {
      const double* p00 = base + origin * 3;
      const double* p01 = p00 + map.stride[1] * 3;
      const double* p10 = p00 + map.stride[0] * 3;
      const double* p11 = p10 + map.stride[1] * 3;
      for (int k = 0; k < 3; ++k) {
        double dy, dl;
        bilinear_dt(p00[k], p01[k], p10[k], p11[k], ly.t, ll.t, dy, dl);
        set_row(dinv[k], dy * iw_y, dl * iw_load, 0.0, 0.0, 0.0);
      }
    }
  }
  constexpr int kDims = kOuter + 3;  // the creep block's
  double x[3], t5[kDims];
  std::size_t cell = 0;
  for (int k = 0; k < kOuter; ++k) t5[k] = t2[k], cell += static_cast<std::size_t>(outer[k].i) * cb.stride[k];
  for (int k = kOuter; k < kDims; ++k) t5[k] = 0.0;
  for (int k = 0; k < 3; ++k) {
    x[k] = creepage[k] * inv[k];
    if (skip) continue;
    AxisLoc l;
    d.axis[kVarXi + k].locate_fast(
        creep_coordinate_normalised(x[k] * map.kinv[k], map.lo_k[k] * inv[k], map.hi_k[k] * inv[k]), l);
    t5[kOuter + k] = l.t;
    cell += static_cast<std::size_t>(l.i) * cb.stride[kOuter + k];
    if (kGrad && !empty) {
      iw_v[k] = inverse_width(d.axis[kVarXi + k], l);
      creepage_rows(map, k, creepage[k], inv[k], x[k], dinv[k], grad->frozen >> (kVarXi + k) & 1u, dxn[k], dv[k]);
    }
  }
  RecordPtr cr = cb.data.data() + slot * cb.slot_size + cell;
  double u5[kDims];
  for (int k = 0; k < kDims; ++k) u5[k] = 1.0 - t5[k];

  // Normal (y, load).
  {
    RecordPtr n = nb.data.data() + slot * nb.slot_size;
    for (int k = 0; k < kOuter; ++k) n += static_cast<std::size_t>(outer[k].i) * nb.stride[k];
    SumsSse2<NN, double> sums;
    sums.zero();
    walk_corners_sse2<kOuter, 0>(n, 1.0, t2, u2, nb.stride, sums);
    store_values(nb, sums, c);
    store_status_run<1>(kNormal, nb, n, c);
    if constexpr (kGrad) {
      RecordPtr n01 = n + nb.stride[1], n10 = n + nb.stride[0], n11 = n10 + nb.stride[1];
      for (int k = 0; k < NN; ++k) {
        double dy, dl;
        bilinear_dt(record_value<double>(n, k), record_value<double>(n01, k), record_value<double>(n10, k),
                    record_value<double>(n11, k), ly.t, ll.t, dy, dl);
        set_row(dd[nb.output_of[k]], dy * iw_y, dl * iw_load, 0.0, 0.0, 0.0);
      }
    }
  }

  // Creep and wear (y, load, v_xi, v_eta, v_phi): 32 corners (64 with yaw).
  if (skip) {
    for (int k = 0; k < NC; ++k) c.value[cb.output_of[k]] = 0.0;
    std::memcpy(&c.part_status[kCreep], &fp.empty_status[w][2 * empty_cell], NP * sizeof(StatusBits));
  } else {
    double values[NC];
    if constexpr (kAvx2) corner_sum_avx2<kDims, NC, TC>(cr, t5, u5, cb.stride, values);
    else corner_sum_sse2<kDims, NC, TC>(cr, t5, u5, cb.stride, values);
    if (cb.first_output >= 0) std::memcpy(c.value + cb.first_output, values, sizeof values);
    else for (int k = 0; k < NC; ++k) c.value[cb.output_of[k]] = values[k];
    store_status_run<NP>(kCreep, cb, cr, c);
  }
  if (kGrad && empty) {
    for (int k = 0; k < NC; ++k) set_row(dd[cb.output_of[k]], 0.0, 0.0, 0.0, 0.0, 0.0);
    denormalise_creep(map, x, cos_angle, sin_angle, c.value);
  } else if constexpr (kGrad) {
    // d / d t of the cell's 5 fractions per unit of y, load and v, chained.
    double walked[NC], dt[NC][kMaxDims];  // walked: the values in double (the chain's, as the generic path's)
    multilinear_gradient<TC>(cr, 5, cb.stride, t5, NC, walked, dt);
    BlockGradient gc;
    for (int k = 0; k < NC; ++k)
      set_row(gc.d[k], dt[k][0] * iw_y, dt[k][1] * iw_load, dt[k][2] * iw_v[0], dt[k][3] * iw_v[1], dt[k][4] * iw_v[2]);
    finish_creep_gradient(d, cb, gc, dv, x, dxn, cos_angle, sin_angle, grad->frozen, walked, c, dd);
  } else {
    denormalise_creep(map, x, cos_angle, sin_angle, c.value);
  }
  fold_status(d, q, c);
}

// ---- Cells a located jump cuts (jump_side.hpp): the one-sided interpolation of
// interpolate_jump_cell fused for this shape, with the same ends, weights, products and sums in
// the same order. The pieces (jump_piece.hpp) are found once per query, then per slot each block
// reads only its own side's grid nodes and one-sided values at the jumps.

// The statuses of a block's NP parts folded over the records its pieces read.
template <int NP>
struct CutStatus {
  StatusBits any[NP] = {}, all[NP];
  CutStatus() noexcept {
    for (StatusBits& v : all) v = ~0u;
  }
  void fold(const Block& b, RecordPtr record) noexcept {
    StatusBits bits[NP];
    std::memcpy(bits, record + b.status_offset, sizeof bits);
    for (int p = 0; p < NP; ++p) {
      any[p] |= bits[p];
      all[p] &= bits[p];
    }
  }
  void store(const Block& b, Contact& c) const noexcept {
    for (int p = 0; p < NP; ++p)
      c.part_status[b.part[p]] = (any[p] & ~kEveryCorner) | (all[p] & kEveryCorner);
  }
};

// The ends of block b's pieces (both load nodes of the cell lc) with their weights, in the order
// load node, end a, end b, zero weights dropped, each moved to the creepage cell's first record
// `base`; folds the statuses of the sample ends and of the grid cell each piece carries.
template <int NP>
__attribute__((always_inline)) inline int cut_ends(const Block& b, const JumpSamples& js, const Piece* piece, int lc,
                                                   const double* weight, std::size_t slot, std::size_t base,
                                                   RecordPtr* end, double* end_w, CutStatus<NP>& st) noexcept {
  RecordPtr grid = b.data.data() + slot * b.slot_size + base;
  RecordPtr samples = js.data.data() + slot * js.slot_stride + base;
  const std::size_t load_step = js.load_dim >= 0 ? b.stride[js.load_dim] : 0;
  int n = 0;
  for (int k = 0; k < 2; ++k) {
    const Piece& p = piece[k];
    const std::size_t lnode = static_cast<std::size_t>(lc + k);
    auto slice = [&](const End& e) -> RecordPtr {
      if (e.sample)
        return samples + lnode * js.load_stride + static_cast<std::size_t>(e.index) * js.jump_stride +
               static_cast<std::size_t>(e.side) * js.side_stride;
      return grid + static_cast<std::size_t>(e.index) * b.stride[0] + lnode * load_step;
    };
    const RecordPtr ends[2] = {slice(p.a), slice(p.b)};
    const double ends_w[2] = {1.0 - p.t, p.t};
    for (int e = 0; e < 2; ++e) {
      const double we = weight[k] * ends_w[e];
      if (we == 0.0) continue;
      end[n] = ends[e];
      end_w[n++] = we;
    }
    if (p.a.sample) st.fold(b, ends[0]);
    if (p.b.sample) st.fold(b, ends[1]);
    if (p.cell >= 0)
      st.fold(b, grid + static_cast<std::size_t>(p.cell) * b.stride[0] + static_cast<std::size_t>(lc) * load_step);
  }
  return n;
}

// A block without creepage axes (geometry, normal) on a cut cell: its single corner weighs 1.0,
// so each record's weight is its end's (x 1.0 is exact). Its records hold doubles.
template <int NV>
__attribute__((always_inline)) inline void cut_block_0(const Block& b, const JumpSamples& js, const Piece* piece, int lc,
                                                       const double* weight, std::size_t slot, Contact& c) noexcept {
  RecordPtr end[4];
  double end_w[4];
  CutStatus<1> st;
  const int n = cut_ends<1>(b, js, piece, lc, weight, slot, 0, end, end_w, st);
  SumsSse2<NV, double> sums;
  sums.zero();
  for (int e = 0; e < n; ++e) sums.add(end_w[e], end[e]);
  store_values(b, sums, c);
  st.store(b, c);
}

// One slot of a cut cell (interpolate_jump_cell for this shape). kGrad: also the partial
// derivatives (into grad), each block's from jump_gradient (block_gradient.cpp) on the pieces and
// creepage cell found here, the scales' from one_sided_scales_gradient.
template <int NG, int NN, int NC, int NP, bool kAvx2, class TC, bool kGrad = false>
void cut_slot(const TableData& d, int w, const AxisLoc* loc, const double* creepage, const Piece (*pieces)[2],
              int s, Contact& c, const DerivativeSink* grad = nullptr) noexcept {
  const FastPath& fp = d.fast;
  const JumpWheel& j = d.jumps[w];
  const CreepMap& map = d.creep_map;
  const Block& cb = d.block[w][fp.creep];
  const JumpSamples& cs = j.samples[fp.creep];
  const std::size_t slot = static_cast<std::size_t>(s);
  const int lc = loc[kVarLoad].i;
  const double weight[2] = {1.0 - loc[kVarLoad].t, loc[kVarLoad].t};
  cut_block_0<NG>(d.block[w][fp.geometry], j.samples[fp.geometry], pieces[1], lc, weight, slot, c);
  double cos_angle = 0.0, sin_angle = 0.0;
  if (map.vertical_share) {
    angle_cos_sin(c.value[kContactAngle], cos_angle, sin_angle);
  }
  cut_block_0<NN>(d.block[w][fp.normal], j.samples[fp.normal], pieces[0], lc, weight, slot, c);

  // The slot's reciprocal scales on the query's side (one_sided_scales): list 0's pieces, ends at
  // grid nodes from CreepMap::scale, at jumps from JumpWheel::inv_scale.
  double inv[3];
  one_sided_node_values(map, j, map.scale[w].data() + slot * map.nodes * 3, slot_at_jump(j, j.inv_scale, 3, s), 3,
                        pieces[0], 2, lc, weight, inv);
  double dinv[3][kNumVars], dxn[3][kNumVars], dv[3][kNumVars];  // kGrad
  AxisLoc all[kNumVars];                                        // kGrad: jump_gradient's cells
  if constexpr (kGrad) {
    double same[3];
    one_sided_scales_gradient(d, w, loc, pieces, s, same, dinv);
    all[kVarY] = loc[kVarY];
    all[kVarLoad] = loc[kVarLoad];
  }
  // The creepage cell at the normalised coordinates (creep_cell_n<3>): corner bit q = upper node
  // along creepage axis q, weights 1.0 * f_xi * f_eta * f_phi built by doubling the list per axis.
  double xn[3], cw[8];
  std::size_t off[8], base = 0;
  cw[0] = 1.0;
  off[0] = 0;
  for (int q = 0; q < 3; ++q) {
    xn[q] = creepage[q] * inv[q];
    AxisLoc l;
    d.axis[kVarXi + q].locate_fast(
        creep_coordinate_normalised(xn[q] * map.kinv[q], map.lo_k[q] * inv[q], map.hi_k[q] * inv[q]), l);
    base += static_cast<std::size_t>(l.i) * cb.stride[2 + q];
    if constexpr (kGrad) {
      all[kVarXi + q] = l;
      creepage_rows(map, q, creepage[q], inv[q], xn[q], dinv[q], grad->frozen >> (kVarXi + q) & 1u, dxn[q], dv[q]);
    }
    const int half = 1 << q;
    for (int corner = 0; corner < half; ++corner) {
      cw[corner + half] = cw[corner] * l.t;
      cw[corner] *= 1.0 - l.t;
      off[corner + half] = off[corner] + cb.stride[2 + q];
    }
  }
  {
    RecordPtr end[4];
    double end_w[4];
    CutStatus<NP> st;
    const int n = cut_ends<NP>(cb, cs, pieces[0], lc, weight, slot, base, end, end_w, st);
    double values[NC];
    if constexpr (kAvx2) jump_sum_avx2<3, NC, TC>(end, end_w, n, cw, off, values);
    else jump_sum_sse2<3, NC, TC>(end, end_w, n, cw, off, values);
    if (cb.first_output >= 0) std::memcpy(c.value + cb.first_output, values, sizeof values);
    else for (int k = 0; k < NC; ++k) c.value[cb.output_of[k]] = values[k];
    st.store(cb, c);
  }
  if constexpr (kGrad) {
    double (*dd)[kNumVars] = grad->d;
    zero_absent_rows(d, dd);
    BlockGradient g;
    jump_gradient(d, w, fp.geometry, all, pieces, s, g);
    for (int k = 0; k < NG; ++k) set_row(dd[d.block[w][fp.geometry].output_of[k]], g.d[k][kVarY], g.d[k][kVarLoad], 0.0, 0.0, 0.0);
    jump_gradient(d, w, fp.normal, all, pieces, s, g);
    for (int k = 0; k < NN; ++k) set_row(dd[d.block[w][fp.normal].output_of[k]], g.d[k][kVarY], g.d[k][kVarLoad], 0.0, 0.0, 0.0);
    jump_gradient(d, w, fp.creep, all, pieces, s, g);
    double block_values[NC];  // the one-sided sum's, in double
    for (int k = 0; k < NC; ++k) block_values[k] = c.value[cb.output_of[k]];
    finish_creep_gradient(d, cb, g, dv, xn, dxn, cos_angle, sin_angle, grad->frozen, block_values, c, dd);
  } else {
    denormalise_creep(map, xn, cos_angle, sin_angle, c.value);
  }
}

// locate_state for this shape: y and load (and yaw, kYaw: into loc[kYawLoc], |yaw| when the table
// stores half a symmetric axis) on their axes, the creepages clamped to their physical ranges, the
// fixed variables compared with their values. Returns false when a variable is not finite; else q
// gets kOutOfRange as locate_state sets it, and `clamped` bit var for each variable held at the
// table's edge.
template <bool kYaw = false>
__attribute__((always_inline)) inline bool locate(const TableData& d, const State& state, AxisLoc* loc,
                                                  double* creepage, StatusBits& q, unsigned& clamped) noexcept {
  const double y = state.y, load = state.load;
  const double physical[3] = {state.xi, state.eta, state.phi};
  bool finite = std::isfinite(y) && std::isfinite(load) && std::isfinite(physical[0]) &&
                std::isfinite(physical[1]) && std::isfinite(physical[2]);
  if constexpr (kYaw) finite = finite && std::isfinite(state.yaw);
  for (int k = 0; k < d.n_fixed; ++k) finite = finite && std::isfinite(state_var(state, d.fixed_var[k]));
  if (!finite) return false;
  clamped = static_cast<unsigned>(d.axis[kVarY].locate_fast(y, loc[kVarY])) << kVarY;
  if constexpr (kYaw) {
    const double yaw = d.yaw_even ? std::abs(state.yaw) : state.yaw;  // table_variables
    clamped |= static_cast<unsigned>(d.axis[kVarYaw].locate_fast(yaw, loc[kYawLoc])) << kVarYaw;
  }
  clamped |= static_cast<unsigned>(d.axis[kVarLoad].locate_fast(load, loc[kVarLoad])) << kVarLoad;
  const CreepMap& map = d.creep_map;
  for (int c = 0; c < 3; ++c) {
    const double x = physical[c];
    clamped |= static_cast<unsigned>(x < map.lo[c] || x > map.hi[c]) << (kVarXi + c);
    creepage[c] = std::min(std::max(x, map.lo[c]), map.hi[c]);
  }
  bool out = clamped != 0;
  for (int k = 0; k < d.n_fixed; ++k) {
    const int var = d.fixed_var[k];
    out |= std::abs(state_var(state, var) - d.fixed_value[var]) > d.fixed_tolerance[var];
  }
  q = out ? status::kOutOfRange : 0u;
  return true;
}

inline bool cut_cell(const TableData& d, int w, const AxisLoc* loc) noexcept {
  return d.has_jumps && d.jumps[w].cut[static_cast<std::size_t>(loc[kVarY].i) * static_cast<std::size_t>(d.jumps[w].load_cells) +
                                       static_cast<std::size_t>(loc[kVarLoad].i)];  // jump_cell, with a load axis
}

template <int NG, int NN, int NC, int NP, bool kAvx2, class TC, bool kYaw = false>
bool fast_query(const TableData& d, int w, const State& state, int slot_begin, int slot_end, Contact* contact,
                StatusBits& q) noexcept {
  // Only y and load (and yaw, at kYawLoc) are located (kVarRoll between them stays zero): not the
  // whole kNumVars array, whose zeroing GCC emits as a `rep stos` on every query.
  static_assert(kVarY < kVarLoad && kVarRoll < kVarLoad && kYawLoc < kNumVars);
  AxisLoc loc[kYaw ? kYawLoc + 1 : kVarLoad + 1];
  double creepage[3];
  unsigned clamped;
  if (!locate<kYaw>(d, state, loc, creepage, q, clamped)) return false;
  if (!kYaw && cut_cell(d, w, loc)) {  // one-sided (jump_side.hpp), as interpolate_slots (a yaw table has no jumps)
    const int n = slot_end - slot_begin;
    for (int s = 0; s < n; ++s) zero_absent(d, contact[s]);
    if (d.fast.cut) {
      Piece pieces[2][2];
      query_pieces(d.jumps[w], d.axis[kVarY], loc, 2, pieces);
      for (int s = 0; s < n; ++s)
        cut_slot<NG, NN, NC, NP, kAvx2, TC>(d, w, loc, creepage, pieces, slot_begin + s, contact[s]);
    } else {  // the generic one-sided path reads every variable's AxisLoc
      AxisLoc all[kNumVars];
      all[kVarY] = loc[kVarY];
      all[kVarLoad] = loc[kVarLoad];
      interpolate_jump_cell(d, w, all, creepage, slot_begin, slot_end, contact);
    }
    for (int s = 0; s < n; ++s) fold_status(d, q, contact[s]);
    return true;
  }
  for (int s = slot_begin; s < slot_end; ++s)
    regular_slot<NG, NN, NC, NP, kAvx2, TC, false, kYaw>(d, w, loc, creepage, q, s, contact[s - slot_begin]);
  return true;
}

template <int NG, int NN, int NC, int NP, bool kAvx2, class TC>
bool fast_derivatives(const TableData& d, int w, const State& state, int slot_begin, int slot_end,
                      Contact* contact, double (*deriv)[kNumOutputs][kNumVariables], StatusBits& q) noexcept {
  AxisLoc loc[kVarLoad + 1];
  double creepage[3];
  unsigned clamped;
  StatusBits bits;
  if (!locate(d, state, loc, creepage, bits, clamped)) return false;
  const bool cut = cut_cell(d, w, loc);
  if (cut && !d.fast.cut) return false;
  q = bits;
  if (cut) {
    Piece pieces[2][2];
    query_pieces(d.jumps[w], d.axis[kVarY], loc, 2, pieces);
    for (int s = slot_begin; s < slot_end; ++s) {
      const DerivativeSink grad{deriv[s - slot_begin], clamped};
      Contact& c = contact[s - slot_begin];
      zero_absent(d, c);
      cut_slot<NG, NN, NC, NP, kAvx2, TC, true>(d, w, loc, creepage, pieces, s, c, &grad);
      fold_status(d, q, c);
    }
    return true;
  }
  for (int s = slot_begin; s < slot_end; ++s) {
    const DerivativeSink grad{deriv[s - slot_begin], clamped};
    regular_slot<NG, NN, NC, NP, kAvx2, TC, true>(d, w, loc, creepage, q, s, contact[s - slot_begin], &grad);
  }
  return true;
}

// The block holding `part` (-1: none).
int block_of(const TableData& d, int part) noexcept {
  for (int b = 0; b < d.n_blocks; ++b)
    for (int p = 0; p < d.block[0][b].n_parts; ++p)
      if (d.block[0][b].part[p] == part) return b;
  return -1;
}

bool block_over(const Block& b, std::initializer_list<int> vars) noexcept {
  if (b.n_dims != static_cast<int>(vars.size())) return false;
  int d = 0;
  for (int v : vars)
    if (b.var[d++] != v) return false;
  return true;
}

// A yaw table's fused query has no derivative query (derivatives.cpp takes the generic path).
template <int NG, int NN, int NC, int NP, bool kAvx2, class TC>
void pick(FastPath& fp, bool yaw) noexcept {
  if (yaw) {
    fp.query = &fast_query<NG, NN, NC, NP, kAvx2, TC, true>;
    return;
  }
  fp.query = &fast_query<NG, NN, NC, NP, kAvx2, TC>;
  fp.derivatives = &fast_derivatives<NG, NN, NC, NP, kAvx2, TC>;
}

template <int NG, int NN, int NC, class TC>
void pick(FastPath& fp, bool avx2, int np, bool yaw) noexcept {
  if (np == 2) avx2 ? pick<NG, NN, NC, 2, true, TC>(fp, yaw) : pick<NG, NN, NC, 2, false, TC>(fp, yaw);
  else avx2 ? pick<NG, NN, NC, 1, true, TC>(fp, yaw) : pick<NG, NN, NC, 1, false, TC>(fp, yaw);
}

template <int NG, int NN, int NC>
void pick(FastPath& fp, bool avx2, int np, bool single, bool yaw) noexcept {
  single ? pick<NG, NN, NC, float>(fp, avx2, np, yaw) : pick<NG, NN, NC, double>(fp, avx2, np, yaw);
}

// FastPath::empty_creep of the creep block, when its creepage dimensions come last (after its
// "outer" ones: y, load, and roll or yaw when tabulated): an outer node is empty when all its records
// over the creepage axes are zero; an outer cell when its 2^outer nodes are.
void mark_empty_creep_cells(TableData& d) {
  const int c = d.creep_block;
  if (c < 0) return;
  auto creepage = [](int var) { return var == kVarXi || var == kVarEta || var == kVarPhi; };
  const Block& b0 = d.block[0][c];
  int outer = 0;
  while (outer < b0.n_dims && !creepage(b0.var[outer])) ++outer;
  for (int k = outer; k < b0.n_dims; ++k)
    if (!creepage(b0.var[k])) return;
  if (outer == 0 || outer == b0.n_dims || b0.n_parts > 2) return;
  for (int w = 0; w < 2; ++w) {
    const Block& b = d.block[w][c];
    if (b.n_dims != b0.n_dims || b.n_parts != b0.n_parts) return;
    for (int k = 0; k < b.n_dims; ++k)
      if (b.var[k] != b0.var[k] || b.size[k] != b0.size[k]) return;
  }
  std::size_t nodes = 1, cells = 1, inner_cells = 1;  // per slot: outer nodes, outer cells; creepage cells
  for (int k = 0; k < outer; ++k) nodes *= static_cast<std::size_t>(b0.size[k]), cells *= static_cast<std::size_t>(b0.size[k] - 1);
  for (int k = outer; k < b0.n_dims; ++k) inner_cells *= static_cast<std::size_t>(b0.size[k] - 1);
  for (int w = 0; w < 2; ++w) {
    const Block& b = d.block[w][c];
    const std::size_t step = b.stride[outer - 1];  // bytes per outer node (its creepage records)
    const std::size_t inner = step / static_cast<std::size_t>(b.record);
    std::vector<unsigned char> node(static_cast<std::size_t>(d.n_slots) * nodes);
    for (std::size_t n = 0; n < node.size(); ++n) {
      RecordPtr r = b.data.data() + n * step;  // slot grids follow each other: n counts (slot, outer node)
      bool zero = true;
      for (std::size_t k = 0; k < inner && zero; ++k, r += b.record)
        for (int v = 0; v < b.n_values && zero; ++v)
          zero = (b.value_bytes == sizeof(float) ? record_value<float>(r, v) : record_value<double>(r, v)) == 0.0;
      node[n] = zero;
    }
    std::vector<unsigned char>& cell = d.fast.empty_creep[w];
    std::vector<StatusBits>& status = d.fast.empty_status[w];
    cell.assign(static_cast<std::size_t>(d.n_slots) * cells, 0);
    status.assign(2 * cell.size(), 0);
    for (std::size_t k = 0; k < cell.size(); ++k) {
      // The cell's first outer node (mixed radix over the outer cells, first dimension slowest).
      std::size_t rest = k % cells, first = 0, node_stride = 1;
      int idx[kMaxDims];
      for (int dim = outer - 1; dim >= 0; --dim) {
        idx[dim] = static_cast<int>(rest % static_cast<std::size_t>(b0.size[dim] - 1));
        rest /= static_cast<std::size_t>(b0.size[dim] - 1);
      }
      std::size_t strides[kMaxDims];
      for (int dim = outer - 1; dim >= 0; --dim) {
        strides[dim] = node_stride;
        first += static_cast<std::size_t>(idx[dim]) * node_stride;
        node_stride *= static_cast<std::size_t>(b0.size[dim]);
      }
      const std::size_t slot_nodes = (k / cells) * nodes;
      bool empty = true;
      for (unsigned corner = 0; corner < (1u << outer) && empty; ++corner) {
        std::size_t n = slot_nodes + first;
        for (int dim = 0; dim < outer; ++dim)
          if (corner >> dim & 1u) n += strides[dim];
        empty = node[n];
      }
      cell[k] = empty;
      if (!empty) continue;
      // The statuses the query would copy: those of each creepage cell's first record.
      RecordPtr base = b.data.data() + (slot_nodes + first) * b.stride[outer - 1];
      StatusBits first_bits[2] = {};
      std::memcpy(first_bits, base + b.status_offset, static_cast<std::size_t>(b.n_parts) * sizeof(StatusBits));
      bool uniform = true;
      for (std::size_t ic = 0; ic < inner_cells && uniform; ++ic) {
        std::size_t r = ic, at = 0;
        for (int dim = b.n_dims - 1; dim >= outer; --dim) {
          at += (r % static_cast<std::size_t>(b.size[dim] - 1)) * b.stride[dim];
          r /= static_cast<std::size_t>(b.size[dim] - 1);
        }
        StatusBits here[2] = {};
        std::memcpy(here, base + at + b.status_offset, static_cast<std::size_t>(b.n_parts) * sizeof(StatusBits));
        uniform = std::memcmp(here, first_bits, sizeof here) == 0;
      }
      if (!uniform) continue;
      cell[k] = 2;
      std::memcpy(&status[2 * k], first_bits, sizeof first_bits);
    }
  }
  d.fast.empty_outer = outer;
}

}  // namespace

void prepare_fast_path(TableData& d) {
  d.fast = FastPath{};
  // RAILTAB_LOOKUP_NO_FAST_PATH=1: the generic path for every table (to compare the two).
  if (const char* env = std::getenv("RAILTAB_LOOKUP_NO_FAST_PATH"); env && *env && *env != '0') return;
  const CreepMap& map = d.creep_map;
  if (d.method != Method::kLinear || !map.active) return;
  mark_empty_creep_cells(d);  // the generic linear query skips them too (table.cpp)
  if (d.n_blocks != 3) return;
  // A yaw axis adds a dimension after y to every block (table-format.md); such a table has no
  // jumps, so its fused query has no cut cells.
  const bool yaw = d.tabulated[kVarYaw];
  if (!(d.tabulated[kVarY] && d.tabulated[kVarLoad] && !d.tabulated[kVarRoll]) || (yaw && d.has_jumps)) return;
  const int outer = yaw ? 3 : 2;  // the creep block's dimensions before its creepages
  if (d.n_located != outer || d.n_clamped != 3 || !map.swept[0] || !map.swept[1] || !map.swept[2]) return;
  if (map.n_dims != outer || map.var[0] != kVarY || map.var[outer - 1] != kVarLoad || (yaw && map.var[1] != kVarYaw))
    return;
  if (!d.has_part[kGeometry] || !d.has_part[kNormal] || !d.has_part[kCreep]) return;
  const int g = block_of(d, kGeometry), n = block_of(d, kNormal), c = block_of(d, kCreep);
  if (g < 0 || n < 0 || c != d.creep_block || g == n || n == c || g == c) return;
  for (int w = 0; w < 2; ++w) {
    const Block& gb = d.block[w][g];
    const Block& nb = d.block[w][n];
    const Block& cb = d.block[w][c];
    if (yaw ? !block_over(gb, {kVarY, kVarYaw}) || !block_over(nb, {kVarY, kVarYaw, kVarLoad}) ||
                  !block_over(cb, {kVarY, kVarYaw, kVarLoad, kVarXi, kVarEta, kVarPhi})
            : !block_over(gb, {kVarY}) || !block_over(nb, {kVarY, kVarLoad}) ||
                  !block_over(cb, {kVarY, kVarLoad, kVarXi, kVarEta, kVarPhi}))
      return;
    if (gb.first_output != 0 || gb.n_values != kPartSpecs[kGeometry].n_out) return;  // the angle at value 0
    // Geometry and normal as doubles (format 2.2 stores them so); the creep block of both wheels
    // of one type (narrow_exact_blocks decides per block for both).
    if (gb.value_bytes != sizeof(double) || nb.value_bytes != sizeof(double) ||
        cb.value_bytes != d.block[0][c].value_bytes)
      return;
  }
  const Block& gb = d.block[0][g];
  const Block& nb = d.block[0][n];
  const Block& cb = d.block[0][c];
  for (int w = 1; w < 2; ++w)
    if (d.block[w][g].n_values != gb.n_values || d.block[w][n].n_values != nb.n_values ||
        d.block[w][c].n_values != cb.n_values)
      return;
  // Part statuses copied in one run per block: geometry alone, normal alone, creep (and wear).
  const int np = cb.n_parts;
  if (gb.n_parts != 1 || nb.n_parts != 1 || gb.part[0] != kGeometry || nb.part[0] != kNormal) return;
  if (!(cb.part[0] == kCreep && (np == 1 || (np == 2 && cb.part[1] == kWear)))) return;
  for (int w = 1; w < 2; ++w)
    if (d.block[w][c].n_parts != np) return;
  const bool avx2 = use_avx2(), single = cb.value_bytes == sizeof(float);
  // The shapes railtab generate writes: creep with its per-creepage normal force (load coupling)
  // and wear, or without either.
  if (gb.n_values == 7 && nb.n_values == 6) {
    if (cb.n_values == 6) pick<7, 6, 6>(d.fast, avx2, np, single, yaw);
    else if (cb.n_values == 5) pick<7, 6, 5>(d.fast, avx2, np, single, yaw);
    else if (cb.n_values == 4) pick<7, 6, 4>(d.fast, avx2, np, single, yaw);
  }
  if (!d.fast.query) return;
  d.fast.geometry = g;
  d.fast.normal = n;
  d.fast.creep = c;
  if (d.fast.empty_outer != outer) d.fast.query = nullptr, d.fast.derivatives = nullptr;  // always, by the shape
  // Cut cells fused too when the blocks and their one-sided values have the layout cut_slot reads
  // (blocks written in the order geometry, normal, creep, as interpolate_jump_cell writes them).
  if (!d.has_jumps || !(g < n && n < c)) return;
  for (int w = 0; w < 2; ++w) {
    const JumpWheel& j = d.jumps[w];
    const JumpSamples &gs = j.samples[g], &ns = j.samples[n], &cs = j.samples[c];
    if (!j.load_axis || gs.list != 1 || ns.list != 0 || cs.list != 0 || gs.load_dim >= 0 || ns.load_dim != 1 ||
        cs.load_dim != 1 || gs.n_inner != 0 || ns.n_inner != 0 || cs.n_inner != 3 || cs.inner0 != 2 ||
        j.inv_scale.empty())
      return;
  }
  d.fast.cut = true;
}

}  // namespace railtab::lookup::detail
