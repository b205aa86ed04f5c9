// SPDX-License-Identifier: Apache-2.0
// Contact jumps in the lookup (jump_side.hpp): reading /jumps at load and the one-sided query.
#include "jump_side.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "hdf5_file.hpp"
#include "part_spec.hpp"
#include "table_data.hpp"

namespace railtab::lookup::detail {
namespace {

constexpr hsize_t kMaxJumps = 4096;  // entries of one jump list, at most (limit checked at load)

// Whether the jumps of one list may cut y cell [x0, x1] within load cell l (nodes l, l+1): a jump
// of either node inside it, or, when the lists match, a jump whose interpolated position sweeps
// across it.
bool cuts(const JumpWheel& j, int list, int l, double x0, double x1) {
  const auto& ys = j.y[list];
  const int nodes = j.load_axis ? 2 : 1;
  for (int k = 0; k < nodes; ++k)
    for (double y : ys[static_cast<std::size_t>(l + k)])
      if (y >= x0 && y <= x1) return true;
  if (!j.load_axis || !j.matched[list][static_cast<std::size_t>(l)]) return false;
  const auto& a = ys[static_cast<std::size_t>(l)];
  const auto& b = ys[static_cast<std::size_t>(l + 1)];
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::min(a[i], b[i]) <= x1 && std::max(a[i], b[i]) >= x0) return true;
  return false;
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
  for (int list = 0; list < 2; ++list) j.y[list].assign(static_cast<std::size_t>(n_load), {});
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
      if (bits & kGeometricJumps) j.y[1][l].push_back(v);
    }
  }
  j.load_cells = j.load_axis ? static_cast<int>(n_load) - 1 : 1;
  for (int list = 0; list < 2; ++list) {
    j.matched[list].assign(static_cast<std::size_t>(j.load_cells), 0);
    if (j.load_axis)
      for (int l = 0; l < j.load_cells; ++l)
        j.matched[list][static_cast<std::size_t>(l)] =
            j.y[list][static_cast<std::size_t>(l)].size() == j.y[list][static_cast<std::size_t>(l) + 1].size();
  }
  const int y_cells = ya.size() - 1;
  j.cut.assign(static_cast<std::size_t>(y_cells) * static_cast<std::size_t>(j.load_cells), 0);
  for (int i = 0; i < y_cells; ++i)
    for (int l = 0; l < j.load_cells; ++l)
      j.cut[static_cast<std::size_t>(i) * static_cast<std::size_t>(j.load_cells) + static_cast<std::size_t>(l)] =
          cuts(j, 0, l, ya.nodes()[i], ya.nodes()[i + 1]) || cuts(j, 1, l, ya.nodes()[i], ya.nodes()[i + 1]);
}

// The y cell and fraction of load node `node` (0 or 1 of the query's load cell) on the query's
// side of the jumps of `list`: the jumps' positions interpolated in load when both nodes have the
// same number of them (else the node's own), the segment between two jumps holding y, the
// segment's own grid nodes only. No node in the segment: the query's own cell (as before 2.1).
AxisLoc side_loc(const JumpWheel& j, const Axis& ya, int list, const AxisLoc* loc, double yq, int node) noexcept {
  const int l = j.load_axis ? loc[kVarLoad].i : 0;
  const double s = j.load_axis ? loc[kVarLoad].t : 0.0;
  const std::vector<double>& own = j.y[list][static_cast<std::size_t>(l + node)];
  const bool blend = j.load_axis && j.matched[list][static_cast<std::size_t>(l)];
  const std::vector<double>& lo_list = j.y[list][static_cast<std::size_t>(l)];
  const std::vector<double>& hi_list = j.y[list][static_cast<std::size_t>(j.load_axis ? l + 1 : l)];
  std::size_t m = 0;  // jumps left of the query
  while (m < own.size() && (blend ? (1.0 - s) * lo_list[m] + s * hi_list[m] : own[m]) <= yq) ++m;
  const double lo = m > 0 ? own[m - 1] : -std::numeric_limits<double>::infinity();
  const double hi = m < own.size() ? own[m] : std::numeric_limits<double>::infinity();
  const double* x = ya.nodes();
  const int n = ya.size();
  int a = 0;
  while (a < n && !(x[a] > lo)) ++a;
  int b = n - 1;
  while (b >= 0 && !(x[b] < hi)) --b;
  if (b < a) return loc[kVarY];
  int c = std::clamp(loc[kVarY].i, a, std::max(a, b - 1));
  c = std::min(c, n - 2);
  const double t = b > a ? (yq - x[c]) / (x[c + 1] - x[c]) : (x[a] - x[c]) / (x[c + 1] - x[c]);
  return AxisLoc{c, t};
}

bool geometry_only(const Block& b) { return b.n_parts == 1 && b.part[0] == kGeometry; }

}  // namespace

void read_jumps(const Hdf5File& f, TableData& d) {
  if (!f.exists("/jumps")) return;  // before 2.1, or a table without jumps
  if (!d.tabulated[kVarY] || d.tabulated[kVarRoll])
    f.fail("group /jumps needs a y axis and no roll axis (jumps are located per load node)");
  for (int w = 0; w < 2; ++w) read_wheel(f, d, w);
  d.has_jumps = true;
}

bool jump_cell(const TableData& d, int w, const AxisLoc* loc) noexcept {
  const JumpWheel& j = d.jumps[w];
  const std::size_t l = j.load_axis ? static_cast<std::size_t>(loc[kVarLoad].i) : 0;
  return j.cut[static_cast<std::size_t>(loc[kVarY].i) * static_cast<std::size_t>(j.load_cells) + l] != 0;
}

void interpolate_jump_cell(const TableData& d, int w, const AxisLoc* loc, int slot_begin, int slot_end,
                           Contact* contact) noexcept {
  const JumpWheel& j = d.jumps[w];
  const Axis& ya = d.axis[kVarY];
  const double yq = ya.nodes()[loc[kVarY].i] + loc[kVarY].t * (ya.nodes()[loc[kVarY].i + 1] - ya.nodes()[loc[kVarY].i]);
  const int nodes = j.load_axis ? 2 : 1;
  const double weight[2] = {j.load_axis ? 1.0 - loc[kVarLoad].t : 1.0, j.load_axis ? loc[kVarLoad].t : 0.0};
  const int n = slot_end - slot_begin;
  for (int bi = 0; bi < d.n_blocks; ++bi) {
    const Block& b = d.block[w][bi];
    const int list = geometry_only(b) ? 1 : 0;
    Contact side[2][kMaxSlots];
    for (int k = 0; k < nodes; ++k) {
      AxisLoc l2[kNumVars];
      std::copy(loc, loc + kNumVars, l2);
      l2[kVarY] = side_loc(j, ya, list, loc, yq, k);
      if (j.load_axis) l2[kVarLoad] = AxisLoc{loc[kVarLoad].i, k == 0 ? 0.0 : 1.0};
      b.linear(b, l2, slot_begin, slot_end, side[k]);
    }
    for (int s = 0; s < n; ++s) {
      for (int p = 0; p < b.n_parts; ++p) {
        const PartSpec& spec = kPartSpecs[b.part[p]];
        for (int o = spec.first_output; o < spec.first_output + spec.n_out; ++o)
          contact[s].value[o] = nodes == 2 ? weight[0] * side[0][s].value[o] + weight[1] * side[1][s].value[o]
                                           : side[0][s].value[o];
        const StatusBits a = side[0][s].part_status[b.part[p]], c = side[nodes - 1][s].part_status[b.part[p]];
        contact[s].part_status[b.part[p]] = ((a | c) & ~status::kConverged) | (a & c & status::kConverged);
      }
    }
  }
}

}  // namespace railtab::lookup::detail
