#include "interpolate.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>

#include "part_spec.hpp"

namespace railtab::lookup::detail {
namespace {

// Status of a cell: trouble bits from ANY corner, kConverged only if ALL corners converged.
// A record's statuses are 4 uint32 (padded with 0), folded as two 64-bit words per corner.
class StatusFold {
 public:
  // `statuses` points at a record's packed uint32 statuses (after the padded values).
  void add(const double* statuses) noexcept {
    std::uint64_t w[2];
    std::memcpy(w, statuses, sizeof w);
    any_[0] |= w[0], any_[1] |= w[1];
    all_[0] &= w[0], all_[1] &= w[1];
  }
  void write(StatusBits* status) const noexcept {
    std::uint64_t out[2];
    for (int j = 0; j < 2; ++j) out[j] = (any_[j] & ~kConverged2) | (all_[j] & kConverged2);
    std::memcpy(status, out, sizeof out);
  }

 private:
  static constexpr std::uint64_t kConverged2 =
      std::uint64_t{status::kConverged} | (std::uint64_t{status::kConverged} << 32);
  std::uint64_t any_[2] = {0, 0};     // OR over corners
  std::uint64_t all_[2] = {~0ull, ~0ull};  // AND over corners
};
static_assert(kStatusDoubles * sizeof(double) == 4 * sizeof(StatusBits), "4 statuses per record");

// Copies one slot's values (record order: parts, outputs) and its part statuses into `c`.
void store_slot(const Block& b, const double* values, const StatusBits* status,
                Contact& c) noexcept {
  for (int k = 0; k < b.n_parts; ++k) {
    const PartSpec& spec = kPartSpecs[b.part[k]];
    for (int o = 0; o < spec.n_out; ++o) c.value[spec.first_output + o] = values[o];
    values += spec.n_out;
    c.part_status[b.part[k]] = status[k];
  }
}

// Corner weights and record offsets of the 2^D corners of the cell (bit d of the corner index
// = upper node along dimension d), and the offset of corner 0.
template <int D>
struct Corners {
  static constexpr int kCount = 1 << D;
  double w[kCount];
  std::size_t off[kCount];
  std::size_t base = 0;

  Corners(const Block& b, const AxisLoc* loc) noexcept {
    w[0] = 1.0;
    off[0] = 0;
#pragma GCC unroll 8
    for (int d = 0; d < D; ++d) {
      const AxisLoc& l = loc[b.var[d]];
      base += static_cast<std::size_t>(l.i) * b.stride[d];
      const int half = 1 << d;
#pragma GCC unroll 64
      for (int c = 0; c < half; ++c) {
        w[c + half] = w[c] * l.t;
        off[c + half] = off[c] + b.stride[d];
        w[c] *= 1.0 - l.t;
      }
    }
  }
};

// Two doubles in one SSE2 register (GCC/Clang vector extension; x86-64 baseline).
typedef double V2 __attribute__((vector_size(16)));

inline V2 load2(const double* p) noexcept {
  V2 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// Multilinear over the 2^D corners for records of NVP (even) values, both fixed at compile time
// so the corner loop unrolls and the NVP/2 sums stay in registers: per corner, NVP/2 packed
// multiply-adds over one contiguous run of the record, then its 4 statuses folded. Sums are
// formed corner by corner in index order (split chains or a summation tree measured slower:
// more registers, spills). Values go straight into the contact's outputs.
template <int D, int NVP>
void linear_kernel(const Block& b, const AxisLoc* loc, int slot_begin, int slot_end,
                   Contact* contact) noexcept {
  constexpr int kCorners = 1 << D;
  constexpr int kPairs = NVP / 2;
  const Corners<D> corners(b, loc);
  const int nv = b.n_values;  // NVP - 1 or NVP
  for (int s = slot_begin; s < slot_end; ++s) {
    const double* data =
        b.data.data() + static_cast<std::size_t>(s) * b.slot_size + corners.base;
    V2 acc[kPairs];
#pragma GCC unroll 16
    for (int k = 0; k < kPairs; ++k) acc[k] = V2{0.0, 0.0};
    StatusFold fold;
#pragma GCC unroll 64
    for (int c = 0; c < kCorners; ++c) {
      const double* r = data + corners.off[c];
      const V2 wc = V2{corners.w[c], corners.w[c]};
#pragma GCC unroll 16
      for (int k = 0; k < kPairs; ++k) acc[k] += wc * load2(r + 2 * k);
      fold.add(r + NVP);
    }
    Contact& out_contact = contact[s - slot_begin];
    double tmp[NVP];
    std::memcpy(tmp, acc, sizeof tmp);
    StatusBits st[4];
    fold.write(st);
    if (b.first_output >= 0) {
      double* out = out_contact.value + b.first_output;
#pragma GCC unroll 16
      for (int k = 0; k < NVP - 1; ++k) out[k] = tmp[k];
      if (nv == NVP) out[NVP - 1] = tmp[NVP - 1];
      for (int p = 0; p < b.n_parts; ++p) out_contact.part_status[b.part[p]] = st[p];
    } else {
      store_slot(b, tmp, st, out_contact);
    }
  }
}

// Derivative at e of the parabola through (p[0], p[1], p[2]), as weights on the three values.
void parabola_slope(const double p[3], double e, double w[3]) noexcept {
  w[0] = ((e - p[1]) + (e - p[2])) / ((p[0] - p[1]) * (p[0] - p[2]));
  w[1] = ((e - p[0]) + (e - p[2])) / ((p[1] - p[0]) * (p[1] - p[2]));
  w[2] = ((e - p[0]) + (e - p[1])) / ((p[2] - p[0]) * (p[2] - p[1]));
}

// One axis of the cubic stencil: nodes j = 0..3 are i-1, i, i+1, i+2; 0 and 3 may be absent.
struct CubicAxis {
  std::size_t stride = 0;     // doubles between neighbouring nodes
  std::size_t idx[4] = {};    // node indices (absent ones unused)
  bool has_left = false;      // node i-1 exists
  bool has_right = false;     // node i+2 exists
  double x[4] = {};           // node coordinates
  double c0[4] = {};          // slope at node i   = sum_j c0[j] f[j]
  double c1[4] = {};          // slope at node i+1 = sum_j c1[j] f[j]
  double h00 = 0, h01 = 0;    // Hermite value basis at t
  double h10 = 0, h11 = 0;    // Hermite slope basis at t, times the cell width
};

CubicAxis make_cubic_axis(const Axis& axis, const AxisLoc& l, std::size_t stride) noexcept {
  CubicAxis a;
  const int n = axis.size();
  const double* xs = axis.nodes();
  const int i = l.i;
  a.stride = stride;
  a.has_left = i >= 1;
  a.has_right = i + 2 <= n - 1;
  for (int j = 0; j < 4; ++j) {
    const int node = std::clamp(i - 1 + j, 0, n - 1);
    a.idx[j] = static_cast<std::size_t>(node);
    a.x[j] = xs[node];
  }
  const double h = a.x[2] - a.x[1];
  double w[3];
  // Slope at node i: centred on (i-1, i, i+1) if possible, else one-sided on (i, i+1, i+2).
  if (a.has_left) {
    parabola_slope(&a.x[0], a.x[1], w);
    a.c0[0] = w[0], a.c0[1] = w[1], a.c0[2] = w[2];
  } else if (a.has_right) {
    parabola_slope(&a.x[1], a.x[1], w);
    a.c0[1] = w[0], a.c0[2] = w[1], a.c0[3] = w[2];
  } else {
    a.c0[1] = -1.0 / h, a.c0[2] = 1.0 / h;
  }
  // Slope at node i+1: centred on (i, i+1, i+2) if possible, else one-sided on (i-1, i, i+1).
  if (a.has_right) {
    parabola_slope(&a.x[1], a.x[2], w);
    a.c1[1] = w[0], a.c1[2] = w[1], a.c1[3] = w[2];
  } else if (a.has_left) {
    parabola_slope(&a.x[0], a.x[2], w);
    a.c1[0] = w[0], a.c1[1] = w[1], a.c1[2] = w[2];
  } else {
    a.c1[1] = -1.0 / h, a.c1[2] = 1.0 / h;
  }
  const double t = l.t, t2 = t * t, t3 = t2 * t;
  a.h00 = 2 * t3 - 3 * t2 + 1;
  a.h01 = -2 * t3 + 3 * t2;
  a.h10 = (t3 - 2 * t2 + t) * h;
  a.h11 = (t3 - t2) * h;
  return a;
}

// Limits a node slope m between secants s_left and s_right (equal at a table edge):
// zero at a data extremum, else same sign as the secants and at most 3x the smaller one.
// The bound depends on the node only, so neighbouring cells agree on it and the result stays C1.
double limit_slope(double m, double s_left, double s_right) noexcept {
  if (s_left * s_right <= 0.0) return 0.0;
  const double sign = s_right > 0.0 ? 1.0 : -1.0;
  const double bound = 3.0 * std::min(std::abs(s_left), std::abs(s_right));
  return sign * std::min(std::max(m * sign, 0.0), bound);
}

double hermite(const CubicAxis& a, const double f[4], bool monotone) noexcept {
  const int lo = a.has_left ? 0 : 1, hi = a.has_right ? 3 : 2;
  double m0 = 0.0, m1 = 0.0;
  for (int j = lo; j <= hi; ++j) {
    m0 += a.c0[j] * f[j];
    m1 += a.c1[j] * f[j];
  }
  if (monotone) {
    const double delta = (f[2] - f[1]) / (a.x[2] - a.x[1]);
    const double left = a.has_left ? (f[1] - f[0]) / (a.x[1] - a.x[0]) : delta;
    const double right = a.has_right ? (f[3] - f[2]) / (a.x[3] - a.x[2]) : delta;
    m0 = limit_slope(m0, left, delta);
    m1 = limit_slope(m1, delta, right);
  }
  return a.h00 * f[1] + a.h01 * f[2] + a.h10 * m0 + a.h11 * m1;
}

struct CubicContext {
  const double* data;       // record of node 0 of the first slot's grid
  int n_slots;              // slots interpolated together, grids slot_size doubles apart
  std::size_t slot_size;    // doubles per slot grid
  int n_dims;               // D
  int n_values;             // interpolated doubles per record
  int status_offset;        // doubles before the packed statuses in a record
  const CubicAxis* axes;    // per dimension
  bool monotone;            // limit slopes
};

// Successive 1-D Hermite passes: interpolate the sub-grid of each stencil node along the
// remaining axes, then combine the (up to) 4 results along this axis. All slots in one walk
// (out[slot * n_values + k]), so the stencil recursion runs once per query. Depth <= 6, at most
// 2.3 KB of stack per level; statuses only from nodes inside the cell (j = 1, 2 on every axis).
void cubic_recurse(const CubicContext& c, int d, std::size_t offset, bool inner, double* out,
                   StatusFold* fold) noexcept {
  const int nv = c.n_values * c.n_slots;
  if (d == c.n_dims) {
    for (int s = 0; s < c.n_slots; ++s) {
      const double* rec = c.data + static_cast<std::size_t>(s) * c.slot_size + offset;
      for (int k = 0; k < c.n_values; ++k) out[s * c.n_values + k] = rec[k];
      if (inner) fold[s].add(rec + c.status_offset);
    }
    return;
  }
  const CubicAxis& a = c.axes[d];
  const int lo = a.has_left ? 0 : 1, hi = a.has_right ? 3 : 2;
  double sub[4][kMaxSlots * kMaxSlotValues];
  for (int j = lo; j <= hi; ++j)
    cubic_recurse(c, d + 1, offset + a.idx[j] * a.stride, inner && (j == 1 || j == 2), sub[j],
                  fold);
  for (int k = 0; k < nv; ++k) {
    double f[4] = {0.0, sub[1][k], sub[2][k], 0.0};
    if (a.has_left) f[0] = sub[0][k];
    if (a.has_right) f[3] = sub[3][k];
    out[k] = hermite(a, f, c.monotone);
  }
}

}  // namespace

// Kernels for every (D, padded value count) pair, looked up once at load.
template <int D, int... P>
constexpr std::array<LinearKernel, sizeof...(P)> kernels_for_d(
    std::integer_sequence<int, P...>) noexcept {
  return {&linear_kernel<D, 2 * (P + 1)>...};
}
template <int... D>
constexpr std::array<std::array<LinearKernel, kMaxSlotValues / 2>, sizeof...(D)> kernel_table(
    std::integer_sequence<int, D...>) noexcept {
  return {kernels_for_d<D>(std::make_integer_sequence<int, kMaxSlotValues / 2>())...};
}
constexpr auto kLinearKernels = kernel_table(std::make_integer_sequence<int, kMaxDims + 1>());
static_assert(kMaxSlotValues % 2 == 0, "the table covers every even padded count");

LinearKernel linear_kernel_for(int n_dims, int values_padded) noexcept {
  return kLinearKernels[n_dims][values_padded / 2 - 1];
}

void interpolate_cubic(const Block& block, const Axis* axes, const AxisLoc* loc, bool monotone,
                       int slot_begin, int slot_end, Contact* contact) noexcept {
  CubicAxis ax[kMaxDims];
  for (int d = 0; d < block.n_dims; ++d)
    ax[d] = make_cubic_axis(axes[block.var[d]], loc[block.var[d]], block.stride[d]);
  const int n = slot_end - slot_begin;
  const CubicContext c{block.data.data() + static_cast<std::size_t>(slot_begin) * block.slot_size,
                       n, block.slot_size, block.n_dims, block.n_values, block.values_padded, ax,
                       monotone};
  StatusFold fold[kMaxSlots];
  double values[kMaxSlots * kMaxSlotValues];
  cubic_recurse(c, 0, 0, true, values, fold);
  for (int s = 0; s < n; ++s) {
    StatusBits st[4];
    fold[s].write(st);
    store_slot(block, values + s * block.n_values, st, contact[s]);
  }
}

}  // namespace railtab::lookup::detail
