// SPDX-License-Identifier: Apache-2.0
// Contact jumps in the lookup (jump_side.hpp): reading /jumps at load and the one-sided query.
#include "jump_side.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "hdf5_file.hpp"
#include "interpolate.hpp"
#include "jump_piece.hpp"
#include "low_confidence.hpp"
#include "part_spec.hpp"
#include "table_data.hpp"

namespace railtab::lookup::detail {
namespace {

constexpr hsize_t kMaxJumps = 4096;  // entries of one jump list, at most (limit checked at load)

// Whether the jumps of one list may cut y cell [x0, x1] within load cell l (nodes l, l+1): a jump
// of either node inside it, or a jump whose interpolated position sweeps across it (the jumps
// paired as the query pairs them: in order where both nodes list the same kinds, else by
// kind_partners, JumpWheel::partner).
bool cuts(const JumpWheel& j, int list, int l, double x0, double x1) {
  const auto& ys = j.y[list];
  const int nodes = j.load_axis ? 2 : 1;
  for (int k = 0; k < nodes; ++k)
    for (double y : ys[static_cast<std::size_t>(l + k)])
      if (y >= x0 && y <= x1) return true;
  if (!j.load_axis) return false;
  const std::size_t lo = static_cast<std::size_t>(l);
  const auto& a = ys[lo];
  const auto& b = ys[lo + 1];
  const std::vector<int>& partner = j.partner[list][lo];
  for (std::size_t i = 0; i < a.size(); ++i) {
    const int p = partner.empty() ? static_cast<int>(i) : partner[i];  // empty: the same kinds in order
    if (p < 0) continue;
    const double other = b[static_cast<std::size_t>(p)];
    if (std::min(a[i], other) <= x1 && std::max(a[i], other) >= x0) return true;
  }
  return false;
}

// First creepage dimension of a block: after y and (when tabulated) load.
int first_inner(const Block& b) {
  int d = 0;
  while (d < b.n_dims && (b.var[d] == kVarY || b.var[d] == kVarLoad || b.var[d] == kVarRoll || b.var[d] == kVarYaw)) ++d;
  return d;
}

int load_dim(const Block& b) {
  for (int d = 0; d < b.n_dims; ++d)
    if (b.var[d] == kVarLoad) return d;
  return -1;
}

// The one-sided values of block b of wheel w, into the block's query record layout (double values:
// the blocks are narrowed after, narrow_exact_blocks).
void read_samples(const Hdf5File& f, TableData& d, int w, int bi, std::size_t n_load, std::size_t count) {
  const Block& b = d.block[w][bi];
  JumpSamples& js = d.jumps[w].samples[bi];
  const int inner0 = first_inner(b);
  std::size_t inner = 1;
  std::vector<hsize_t> shape;
  if (d.jumps[w].load_axis) shape.push_back(n_load);
  shape.push_back(count);
  shape.push_back(2);
  for (int k = inner0; k < b.n_dims; ++k) {
    shape.push_back(static_cast<hsize_t>(b.size[k]));
    inner *= static_cast<std::size_t>(b.size[k]);
  }
  const std::size_t ns = static_cast<std::size_t>(d.n_slots);
  shape.push_back(ns);
  const std::size_t rec = static_cast<std::size_t>(b.record);
  js.list = b.n_parts == 1 && b.part[0] == kGeometry ? 1 : 0;  // geometry alone: geometric jumps
  js.inner0 = inner0;
  js.load_dim = load_dim(b);
  js.n_inner = b.n_dims - inner0;
  if (js.n_inner > kMaxJumpInner) f.fail("a block with jumps has more than 3 creepage axes");
  js.sum = jump_kernel_for(js.n_inner, b.n_values, b.value_bytes);
  js.side_stride = inner * rec;
  js.jump_stride = 2 * js.side_stride;
  js.load_stride = count * js.jump_stride;
  js.slot_stride = n_load * js.load_stride;
  js.data.assign(ns * js.slot_stride, 0);
  const std::size_t slices = n_load * count * 2;
  std::vector<StatusBits> node_status(ns * slices * inner * static_cast<std::size_t>(b.n_parts), 0u);
  const std::string group = std::string("/jumps/") + (w == 0 ? "left" : "right") + "/";
  // The block's values in its own order (Block::output_of): a part's outputs, then (creep part with
  // load coupling) its per-creepage normal_force; a normalised creep part stores fx, fy, mz as
  // <name>_normalised (as read_part reads the grid).
  const bool normalised_creep = f.has_attribute("/", "creep_map");
  int offset = 0;
  for (int p = 0; p < b.n_parts; ++p) {
    const PartSpec& spec = kPartSpecs[b.part[p]];
    const std::string part = group + spec.name;
    int n_values = spec.n_out;
    if (b.part[p] == kCreep && offset + n_values < b.n_values && b.output_of[offset + n_values] == kNormalForce)
      ++n_values;
    for (int o = 0; o < n_values; ++o) {
      const int out = b.output_of[offset + o];
      const std::string name = part + "/" + output_name(static_cast<Output>(out)) +
                               (normalised_creep && out >= kFx && out <= kMz ? "_normalised" : "");
      const auto v = f.read_doubles(name, shape, "the jump list and the table's axes");
      if (d.checksums_verified && !v.checksummed) f.fail("dataset " + name + " has no checksum");
      for (std::size_t k = 0; k < v.values.size(); ++k) {
        if (!std::isfinite(v.values[k])) f.fail("dataset " + name + " holds a non-finite value");
        const std::size_t s = k % ns, node = (k / ns) % inner, slice = k / (ns * inner);
        std::memcpy(js.data.data() + s * js.slot_stride + slice * js.side_stride + node * rec +
                        static_cast<std::size_t>(offset + o) * sizeof(double),
                    &v.values[k], sizeof(double));
      }
    }
    offset += n_values;
    const auto st = f.read_uint32(part + "/status", shape, "the jump list and the table's axes");
    if (d.checksums_verified && !st.checksummed) f.fail("dataset " + part + "/status has no checksum");
    for (std::size_t k = 0; k < st.values.size(); ++k) {
      const std::size_t s = k % ns, node = (k / ns) % inner, slice = k / (ns * inner);
      node_status[((s * slices + slice) * inner + node) * static_cast<std::size_t>(b.n_parts) +
                  static_cast<std::size_t>(p)] = st.values[k];
    }
  }
  // Cell statuses over the creepage axes, as prepare_query_layout folds the block's (with its
  // low_confidence rule: a slot present at some corners of the creepage cell, absent at others).
  const int n_inner = b.n_dims - inner0;
  for (std::size_t s = 0; s < ns; ++s)
    for (std::size_t slice = 0; slice < slices; ++slice)
      for (std::size_t node = 0; node < inner; ++node) {
        int idx[kNumVars] = {};
        std::size_t rest = node;
        for (int k = n_inner - 1; k >= 0; --k) {
          const std::size_t n = static_cast<std::size_t>(b.size[inner0 + k]);
          idx[k] = static_cast<int>(rest % n);
          rest /= n;
        }
        std::size_t corner_node[1 << kMaxJumpInner];
        for (int corner = 0; corner < (1 << n_inner); ++corner) {
          std::size_t other = 0;
          for (int k = 0; k < n_inner; ++k) {
            const int n = b.size[inner0 + k];
            const int i = std::min(idx[k] + ((corner >> k) & 1), n - 1);
            other = other * static_cast<std::size_t>(n) + static_cast<std::size_t>(i);
          }
          corner_node[corner] = other;
        }
        auto part_status = [&](std::size_t k, int p) {
          return node_status[((s * slices + slice) * inner + k) * static_cast<std::size_t>(b.n_parts) +
                             static_cast<std::size_t>(p)];
        };
        const bool mixed = mixed_presence(part_status, b.n_parts, corner_node, 1 << n_inner);
        for (int p = 0; p < b.n_parts; ++p) {
          StatusBits any = 0, all = ~0u;
          for (int corner = 0; corner < (1 << n_inner); ++corner) {
            std::size_t other = 0;
            for (int k = 0; k < n_inner; ++k) {
              const int n = b.size[inner0 + k];
              const int i = std::min(idx[k] + ((corner >> k) & 1), n - 1);
              other = other * static_cast<std::size_t>(n) + static_cast<std::size_t>(i);
            }
            const StatusBits bits = node_status[((s * slices + slice) * inner + other) *
                                                    static_cast<std::size_t>(b.n_parts) +
                                                static_cast<std::size_t>(p)];
            any |= bits;
            all &= bits;
          }
          const StatusBits cell = (any & ~kEveryCorner) | (all & kEveryCorner) |
                                  (mixed ? status::kLowConfidence : 0u);
          unsigned char* record = js.data.data() + s * js.slot_stride + slice * js.side_stride + node * rec;
          std::memcpy(record + b.status_offset + static_cast<std::size_t>(p) * sizeof(StatusBits), &cell, sizeof cell);
        }
      }
}

// The normal part's one-sided creepage scales (normalised creep coordinates): finite and > 0 at
// every jump (the padding is not read by the query and holds 0).
void read_scales(const Hdf5File& f, TableData& d, int w, std::size_t n_load, std::size_t count) {
  JumpWheel& j = d.jumps[w];
  const std::size_t ns = static_cast<std::size_t>(d.n_slots);
  std::vector<hsize_t> shape;
  if (j.load_axis) shape.push_back(n_load);
  shape.push_back(count);
  shape.push_back(2);
  shape.push_back(ns);
  j.inv_scale.assign(ns * n_load * count * 2 * 3, 0.0);
  static const char* const names[3] = {"creep_scale_xi", "creep_scale_eta", "creep_scale_phi"};
  for (int k = 0; k < 3; ++k) {
    const std::string name = std::string("/jumps/") + (w == 0 ? "left" : "right") + "/normal/" + names[k];
    if (!f.exists(name)) f.fail("missing dataset " + name + " (root attribute creep_map and group /jumps need it)");
    const auto v = f.read_doubles(name, shape, "the jump list and the table's axes");
    if (d.checksums_verified && !v.checksummed) f.fail("dataset " + name + " has no checksum");
    for (std::size_t i = 0; i < v.values.size(); ++i) {
      const std::size_t s = i % ns, slice = i / ns, l = slice / (count * 2), jump = (slice / 2) % count;
      if (jump >= j.y[0][l].size()) continue;  // padding
      const double x = v.values[i];
      if (!(std::isfinite(x) && x > 0.0 && std::isfinite(1.0 / x)))
        f.fail("dataset " + name + " holds a scale that is not finite and > 0 at flat index " + std::to_string(i));
      j.inv_scale[((s * n_load * count * 2) + slice) * 3 + static_cast<std::size_t>(k)] = 1.0 / x;
    }
  }
}

void read_wheel(const Hdf5File& f, TableData& d, int w) {
  const std::string name = std::string("/jumps/") + (w == 0 ? "left" : "right");
  const std::vector<hsize_t> shape = f.dataset_shape(name + "_y");
  JumpWheel& j = d.jumps[w];
  j.load_axis = d.tabulated[kVarLoad];
  const hsize_t n_load = j.load_axis ? static_cast<hsize_t>(d.axis[kVarLoad].size()) : 1;
  const std::size_t rank = j.load_axis ? 2 : 1;
  if (shape.size() != rank || (rank == 2 && shape[0] != n_load) || shape.back() > kMaxJumps)
    f.fail("dataset " + name + "_y must have shape [" + (rank == 2 ? std::to_string(n_load) + ", " : "") +
           "jumps] with at most " + std::to_string(kMaxJumps) + " jumps");
  const auto y = f.read_doubles(name + "_y", shape, name + "_y's own jump count");
  const auto kind = f.read_uint32(name + "_kind", shape, name + "_y");
  if (d.checksums_verified && !(y.checksummed && kind.checksummed))
    f.fail("dataset " + name + "_y or _kind has no checksum but the table's other datasets have one");
  const std::size_t count = static_cast<std::size_t>(shape.back());
  const Axis& ya = d.axis[kVarY];
  for (int list = 0; list < 2; ++list) {
    j.y[list].assign(static_cast<std::size_t>(n_load), {});
    j.index[list].assign(static_cast<std::size_t>(n_load), {});
    j.kind[list].assign(static_cast<std::size_t>(n_load), {});
  }
  for (std::size_t l = 0; l < n_load; ++l) {
    bool ended = false;
    double last = -std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < count; ++k) {
      const double v = y.values[l * count + k];
      const std::uint32_t bits = kind.values[l * count + k];
      if (std::isnan(v)) {
        if (bits != 0) f.fail(name + "_kind is not 0 where " + name + "_y is NaN (no jump)");
        ended = true;
        continue;
      }
      if (ended || !(v > last) || !(v > ya.nodes()[0]) || !(v < ya.nodes()[ya.size() - 1]) || bits == 0)
        f.fail(name + "_y: jumps must be finite, strictly increasing, inside the y axis, before the NaN "
               "padding, with a nonzero kind");
      last = v;
      j.y[0][l].push_back(v);
      j.index[0][l].push_back(static_cast<int>(k));
      j.kind[0][l].push_back(bits);
      if (bits & kGeometricJumps) {
        j.y[1][l].push_back(v);
        j.index[1][l].push_back(static_cast<int>(k));
        j.kind[1][l].push_back(bits);
      }
    }
  }
  j.load_cells = j.load_axis ? static_cast<int>(n_load) - 1 : 1;
  for (int list = 0; list < 2; ++list) {
    j.matched[list].assign(static_cast<std::size_t>(j.load_cells), 0);
    j.partner[list].assign(static_cast<std::size_t>(j.load_cells), {});
    if (j.load_axis)
      for (int l = 0; l < j.load_cells; ++l) {
        const std::size_t lo = static_cast<std::size_t>(l);
        j.matched[list][lo] = j.y[list][lo].size() == j.y[list][lo + 1].size();
        if (j.kind[list][lo] != j.kind[list][lo + 1]) j.partner[list][lo] = kind_partners(j.kind[list][lo], j.kind[list][lo + 1]);
      }
  }
  const int y_cells = ya.size() - 1;
  j.cut.assign(static_cast<std::size_t>(y_cells) * static_cast<std::size_t>(j.load_cells), 0);
  for (int i = 0; i < y_cells; ++i)
    for (int l = 0; l < j.load_cells; ++l)
      j.cut[static_cast<std::size_t>(i) * static_cast<std::size_t>(j.load_cells) + static_cast<std::size_t>(l)] =
          cuts(j, 0, l, ya.nodes()[i], ya.nodes()[i + 1]) || cuts(j, 1, l, ya.nodes()[i], ya.nodes()[i + 1]);
  const double inf = std::numeric_limits<double>::infinity();
  const double* x = ya.nodes();
  for (int list = 0; list < 2; ++list) {
    j.seg_first[list].assign(static_cast<std::size_t>(n_load), {});
    j.seg_last[list].assign(static_cast<std::size_t>(n_load), {});
    for (std::size_t l = 0; l < n_load; ++l) {
      const std::vector<double>& own = j.y[list][l];
      for (std::size_t m = 0; m <= own.size(); ++m) {
        const double lo = m > 0 ? own[m - 1] : -inf, hi = m < own.size() ? own[m] : inf;
        j.seg_first[list][l].push_back(static_cast<int>(std::upper_bound(x, x + ya.size(), lo) - x));
        j.seg_last[list][l].push_back(static_cast<int>(std::lower_bound(x, x + ya.size(), hi) - x) - 1);
      }
    }
  }
  // Rounding margin of the windows: the blended jump positions and the query's y (x[c] + t (x[c+1]
  // - x[c]), t in [0, 1]) are within a few ulps of the nodes' range; 1e-9 of the axis is far more.
  const double margin = 1e-9 * (x[ya.size() - 1] - x[0]);
  j.y_cells = y_cells;
  for (int list = 0; list < 2; ++list) {
    j.window[list].assign(n_load * static_cast<std::size_t>(y_cells) * 2, 0);
    for (std::size_t l = 0; l < n_load; ++l) {
      const std::vector<double>& own = j.y[list][l];
      for (int c = 0; c < y_cells; ++c) {
        const std::size_t at = (l * static_cast<std::size_t>(y_cells) + static_cast<std::size_t>(c)) * 2;
        j.window[list][at] =
            static_cast<int>(std::lower_bound(own.begin(), own.end(), x[c] - margin) - own.begin());
        j.window[list][at + 1] =
            static_cast<int>(std::upper_bound(own.begin(), own.end(), x[c + 1] + margin) - own.begin());
      }
    }
  }
  // The crossing windows (JumpWheel::cross_window): per load cell with partners, node and y cell,
  // the jumps before the window lie, at both their positions, left of the cell by the margin (so
  // left of every query in it), those from its end on right of it.
  for (int list = 0; list < 2; ++list) {
    j.cross_window[list].assign(static_cast<std::size_t>(j.load_cells) * 2 * static_cast<std::size_t>(y_cells) * 2, 0);
    for (int l = 0; l < j.load_cells && j.load_axis; ++l) {
      const std::vector<int>& partner = j.partner[list][static_cast<std::size_t>(l)];
      if (partner.empty()) continue;
      for (std::size_t node = 0; node < 2; ++node) {
        const std::vector<double>& own = j.y[list][static_cast<std::size_t>(l) + node];
        const std::vector<double>& other = j.y[list][static_cast<std::size_t>(l) + 1 - node];
        const std::size_t first = node == 0 ? 0 : j.y[list][static_cast<std::size_t>(l)].size();
        auto lo = [&](std::size_t k) {
          const int p = partner[first + k];
          return p < 0 ? own[k] : std::min(own[k], other[static_cast<std::size_t>(p)]);
        };
        auto hi = [&](std::size_t k) {
          const int p = partner[first + k];
          return p < 0 ? own[k] : std::max(own[k], other[static_cast<std::size_t>(p)]);
        };
        for (int c = 0; c < y_cells; ++c) {
          std::size_t a = 0, b = own.size();
          while (a < b && hi(a) < x[c] - margin) ++a;
          while (b > a && lo(b - 1) > x[c + 1] + margin) --b;
          const std::size_t at = ((static_cast<std::size_t>(l) * 2 + node) * static_cast<std::size_t>(y_cells) +
                                  static_cast<std::size_t>(c)) * 2;
          j.cross_window[list][at] = static_cast<int>(a);
          j.cross_window[list][at + 1] = static_cast<int>(b);
        }
      }
    }
  }
  for (int b = 0; b < d.n_blocks; ++b) read_samples(f, d, w, b, static_cast<std::size_t>(n_load), count);
  j.n_load_nodes = static_cast<std::size_t>(n_load);
  j.n_jumps = count;
  if (d.creep_map.active) read_scales(f, d, w, static_cast<std::size_t>(n_load), count);
}

}  // namespace

void read_jumps(const Hdf5File& f, TableData& d) {
  if (!f.exists("/jumps")) return;  // before 2.1, or a table without jumps
  if (!d.tabulated[kVarY] || d.tabulated[kVarRoll] || d.tabulated[kVarYaw])
    f.fail("group /jumps needs a y axis and no roll or yaw axis (jumps are located per load node)");
  for (int w = 0; w < 2; ++w) read_wheel(f, d, w);
  d.has_jumps = true;
}

bool jump_cell(const TableData& d, int w, const AxisLoc* loc) noexcept {
  const JumpWheel& j = d.jumps[w];
  const std::size_t l = j.load_axis ? static_cast<std::size_t>(loc[kVarLoad].i) : 0;
  return j.cut[static_cast<std::size_t>(loc[kVarY].i) * static_cast<std::size_t>(j.load_cells) + l] != 0;
}

void cubic_stencil_limits(const TableData& d, int w, AxisLoc* loc) noexcept {
  const JumpWheel& j = d.jumps[w];
  const int y_cells = static_cast<int>(j.cut.size()) / j.load_cells;
  const int iy = loc[kVarY].i, il = j.load_axis ? loc[kVarLoad].i : 0;
  // Cut flag of (y cell, load cell); cells outside the table are not cut (the edge limits them).
  auto cut = [&](int y, int l) {
    return y >= 0 && y < y_cells && l >= 0 && l < j.load_cells &&
           j.cut[static_cast<std::size_t>(y) * static_cast<std::size_t>(j.load_cells) + static_cast<std::size_t>(l)] != 0;
  };
  // A stencil node beyond cell c along one axis is dropped when c is cut at any cell of the
  // other axis's stencil (conservative: the corners of the tensor stencil stay on one side).
  unsigned char y_bits = 0, load_bits = 0;
  for (int l = il - 1; l <= il + 1; ++l) {
    if (cut(iy - 1, l)) y_bits |= 1;
    if (cut(iy + 1, l)) y_bits |= 2;
  }
  if (j.load_axis)
    for (int y = iy - 1; y <= iy + 1; ++y) {
      if (cut(y, il - 1)) load_bits |= 1;
      if (cut(y, il + 1)) load_bits |= 2;
    }
  loc[kVarY].cut_stencil = y_bits;
  if (j.load_axis) loc[kVarLoad].cut_stencil = load_bits;
}

namespace {

// The corners of the query's cell over the creepage axes of block b (weights and record offsets
// from the cell's first record), and that first record's offset within a slice.
struct CreepCell {
  std::size_t base = 0;
  double w[1 << kMaxJumpInner];
  std::size_t off[1 << kMaxJumpInner];
};

template <int NI>
void creep_cell_n(const Block& b, int inner0, const AxisLoc* loc, CreepCell& c) noexcept {
  c.base = 0;
#pragma GCC unroll 4
  for (int k = 0; k < NI; ++k) c.base += static_cast<std::size_t>(loc[b.var[inner0 + k]].i) * b.stride[inner0 + k];
  // Corner bit q = upper node along creepage axis q; the weight is the product of the axes'
  // factors in axis order, 1.0 * f_0 * f_1 * .., built by doubling the corner list per axis.
  c.w[0] = 1.0;
  c.off[0] = 0;
#pragma GCC unroll 4
  for (int q = 0; q < NI; ++q) {
    const AxisLoc& l = loc[b.var[inner0 + q]];
    const int half = 1 << q;
#pragma GCC unroll 4
    for (int corner = 0; corner < half; ++corner) {
      c.w[corner + half] = c.w[corner] * l.t;
      c.w[corner] *= 1.0 - l.t;
      c.off[corner + half] = c.off[corner] + b.stride[inner0 + q];
    }
  }
}

// The block's creepage dimensions (b.n_dims - inner0, at most kMaxJumpInner) fixed at compile time.
void creep_cell(const Block& b, int inner0, const AxisLoc* loc, CreepCell& c) noexcept {
  switch (b.n_dims - inner0) {
    case 0: creep_cell_n<0>(b, inner0, loc, c); break;
    case 1: creep_cell_n<1>(b, inner0, loc, c); break;
    case 2: creep_cell_n<2>(b, inner0, loc, c); break;
    default: creep_cell_n<3>(b, inner0, loc, c); break;
  }
}

// The slot's reciprocal creepage scales on the query's side (normalised creep coordinates): the
// pieces of list 0 (the normal part's), ends at grid nodes from CreepMap::scale, at jumps from
// JumpWheel::inv_scale, blended in load as the values.
void one_sided_scales(const TableData& d, int w, const Piece* piece, int nodes, int lc, const double* weight,
                      int slot, double inv[3]) noexcept {
  const CreepMap& map = d.creep_map;
  const JumpWheel& j = d.jumps[w];
  one_sided_node_values(map, j, map.scale[w].data() + static_cast<std::size_t>(slot) * map.nodes * 3,
                        slot_at_jump(j, j.inv_scale, 3, slot), 3, piece, nodes, lc, weight, inv);
}

}  // namespace

void interpolate_jump_cell(const TableData& d, int w, const AxisLoc* loc, const double* creepage, int slot_begin,
                           int slot_end, Contact* contact) noexcept {
  const JumpWheel& j = d.jumps[w];
  const int nodes = j.load_axis ? 2 : 1;
  const int lc = j.load_axis ? loc[kVarLoad].i : 0;
  const double weight[2] = {j.load_axis ? 1.0 - loc[kVarLoad].t : 1.0, j.load_axis ? loc[kVarLoad].t : 0.0};
  const int n = slot_end - slot_begin;
  // The pieces of both jump lists at both load nodes, shared by the blocks.
  Piece pieces[2][2];
  query_pieces(j, d.axis[kVarY], loc, nodes, pieces);
  const CreepMap& map = d.creep_map;
  double cos_angle[kMaxSlots] = {}, sin_angle[kMaxSlots] = {};  // of each slot's contact angle
  bool have_angle = false;
  for (int bi = 0; bi < d.n_blocks; ++bi) {
    const Block& b = d.block[w][bi];
    const JumpSamples& js = j.samples[bi];
    const int list = js.list, inner0 = js.inner0, ld = js.load_dim;
    // The creepage cell per slot: the query's own creepages, or (normalised creep block) its v
    // coordinates at the slot's one-sided scales.
    const bool normalised = map.active && bi == d.creep_block;
    CreepCell cell[kMaxSlots];
    double xn[kMaxSlots][3];  // normalised creepages xi', eta', psi' (set and read only when normalised)
    for (int s = 0; s < n; ++s) {
      if (!normalised) {
        if (s == 0) creep_cell(b, inner0, loc, cell[0]);
        else cell[s] = cell[0];
        continue;
      }
      double inv[3];
      one_sided_scales(d, w, pieces[0], nodes, lc, weight, slot_begin + s, inv);
      AxisLoc slot_loc[kNumVars];
      for (int var = 0; var < kNumVars; ++var) slot_loc[var] = loc[var];
      for (int k = 0; k < 3; ++k) {
        xn[s][k] = creepage[k] * inv[k];
        if (map.swept[k])
          d.axis[kVarXi + k].locate_fast(creep_coordinate_normalised(xn[s][k] * map.kinv[k], map.lo_k[k] * inv[k],
                                                                     map.hi_k[k] * inv[k]),
                                         slot_loc[kVarXi + k]);
      }
      creep_cell(b, inner0, slot_loc, cell[s]);
    }
    // Per slot: the ends of both load nodes' pieces with their weights (load x y fraction), in
    // the order load node, end; one kernel call sums their creepage corners.
    for (int s = 0; s < n; ++s) {
      const std::size_t slot = static_cast<std::size_t>(slot_begin + s);
      const CreepCell& cc = cell[s];
      RecordPtr end[4];
      double end_w[4];
      int n_ends = 0;
      StatusBits any[kNumParts] = {}, all[kNumParts];
      for (StatusBits& v : all) v = ~0u;
      // Status: the samples' creepage cells and the grid cell of the side the piece uses.
      auto fold = [&](RecordPtr record) {
        for (int p = 0; p < b.n_parts; ++p) {
          StatusBits bits;
          std::memcpy(&bits, record + b.status_offset + p * sizeof(StatusBits), sizeof bits);
          any[p] |= bits;
          all[p] &= bits;
        }
      };
      for (int k = 0; k < nodes; ++k) {
        const Piece& piece = pieces[list][k];
        const std::size_t lnode = static_cast<std::size_t>(lc + k);
        auto slice = [&](const End& e) -> RecordPtr {
          if (e.sample)
            return js.data.data() + slot * js.slot_stride + lnode * js.load_stride +
                   static_cast<std::size_t>(e.index) * js.jump_stride + static_cast<std::size_t>(e.side) * js.side_stride;
          return b.data.data() + slot * b.slot_size + static_cast<std::size_t>(e.index) * b.stride[0] +
                 (ld >= 0 ? lnode * b.stride[ld] : 0);
        };
        const RecordPtr ends[2] = {slice(piece.a), slice(piece.b)};
        const double ends_w[2] = {1.0 - piece.t, piece.t};
        for (int e = 0; e < 2; ++e) {
          const double we = weight[k] * ends_w[e];
          if (we == 0.0) continue;  // e.g. a query on a grid node, or at a load node
          end[n_ends] = ends[e] + cc.base;
          end_w[n_ends++] = we;
        }
        if (piece.spans)
          for (int p = 0; p < b.n_parts; ++p) any[p] |= status::kLowConfidence;
        if (piece.a.sample) fold(ends[0] + cc.base);
        if (piece.b.sample) fold(ends[1] + cc.base);
        if (piece.cell >= 0)
          fold(b.data.data() + slot * b.slot_size + static_cast<std::size_t>(piece.cell) * b.stride[0] +
               (ld >= 0 ? static_cast<std::size_t>(lc) * b.stride[ld] : 0) + cc.base);
      }
      double values[kMaxSlotValues];
      js.sum(end, end_w, n_ends, cc.w, cc.off, values);
      Contact& c = contact[s];
      if (b.first_output >= 0) std::memcpy(c.value + b.first_output, values, static_cast<std::size_t>(b.n_values) * sizeof(double));
      else for (int v = 0; v < b.n_values; ++v) c.value[b.output_of[v]] = values[v];  // Block::output_of
      for (int p = 0; p < b.n_parts; ++p)
        c.part_status[b.part[p]] = (any[p] & ~kEveryCorner) | (all[p] & kEveryCorner);
      if (map.vertical_share && b.n_parts > 0 && b.part[0] == kGeometry) {
        // The contact angle is final: its sine and cosine now, off the creep block's critical path.
        angle_cos_sin(c.value[kContactAngle], cos_angle[s], sin_angle[s]);
        have_angle = true;
      }
      if (!normalised || !d.has_part[kCreep]) continue;
      // F / (mu N) minus the law, plus the law at the query's normalised creepages, times mu N (the
      // creep point's own N, already in kNormalForce), as interpolate_normalised_creep (table.cpp).
      if (map.vertical_share && !have_angle) {  // no geometry part: its angle, 0
        angle_cos_sin(c.value[kContactAngle], cos_angle[s], sin_angle[s]);
      }
      denormalise_creep(map, xn[s], cos_angle[s], sin_angle[s], c.value);
    }
  }
}

}  // namespace railtab::lookup::detail
