#include "interpolate.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace railtab::lookup::detail {
namespace {

// Status of a cell: trouble bits from ANY corner, kConverged only if ALL corners converged.
// Statuses are folded in chunks of 4 uint32 (records pad them so), one 128-bit OR/AND each.
class StatusFold {
 public:
  explicit StatusFold(int n) : chunks_((n + kStatusChunk - 1) / kStatusChunk) {
    for (int j = 0; j < chunks_ * kStatusChunk; ++j) any_[j] = 0, all_[j] = ~0u;
  }
  // `statuses` points at a record's packed uint32 statuses (after the padded values).
  void add(const double* statuses) noexcept {
    const auto* bytes = reinterpret_cast<const unsigned char*>(statuses);
    for (int c = 0; c < chunks_; ++c) {
      StatusBits bits[kStatusChunk];
      std::memcpy(bits, bytes + c * sizeof bits, sizeof bits);
      for (int q = 0; q < kStatusChunk; ++q) {
        any_[c * kStatusChunk + q] |= bits[q];
        all_[c * kStatusChunk + q] &= bits[q];
      }
    }
  }
  void write(StatusBits* status) const noexcept {
    for (int j = 0; j < chunks_ * kStatusChunk; ++j)
      status[j] = (any_[j] & ~status::kConverged) | (all_[j] & status::kConverged);
  }

 private:
  int chunks_;                     // chunks of kStatusChunk statuses per record
  StatusBits any_[kMaxStatuses];   // OR over corners
  StatusBits all_[kMaxStatuses];   // AND over corners
};

// Multilinear over the 2^D corners, D fixed at compile time so the corner loops unroll. Corner
// weights and offsets first, then the values in chunks of 4 with the sums in registers.
template <int D>
void linear_kernel(const Block& b, const AxisLoc* loc, double* values,
                   StatusBits* status) noexcept {
  constexpr int kCorners = 1 << D;
  double w[kCorners];
  std::size_t off[kCorners];
  w[0] = 1.0;
  off[0] = 0;
  std::size_t base = 0;
  for (int d = 0; d < D; ++d) {
    const AxisLoc& l = loc[b.var[d]];
    base += static_cast<std::size_t>(l.i) * b.stride[d];
    const int half = 1 << d;
    for (int c = 0; c < half; ++c) {
      w[c + half] = w[c] * l.t;
      off[c + half] = off[c] + b.stride[d];
      w[c] *= 1.0 - l.t;
    }
  }
  const double* data = b.data.data() + base;
  for (int k = 0; k < b.values_padded; k += kValueChunk) {
    double a0 = 0.0, a1 = 0.0, a2 = 0.0, a3 = 0.0;
    for (int c = 0; c < kCorners; ++c) {
      const double* r = data + off[c] + k;
      a0 += w[c] * r[0];
      a1 += w[c] * r[1];
      a2 += w[c] * r[2];
      a3 += w[c] * r[3];
    }
    values[k] = a0, values[k + 1] = a1, values[k + 2] = a2, values[k + 3] = a3;
  }
  StatusFold fold(b.n_status);
  for (int c = 0; c < kCorners; ++c) fold.add(data + off[c] + b.values_padded);
  fold.write(status);
}
static_assert(kValueChunk == 4, "linear_kernel accumulates chunks of 4");

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
  const double* data;       // block records
  int n_dims;               // D
  int n_values;             // interpolated doubles per record
  int status_offset;        // doubles before the packed statuses in a record
  const CubicAxis* axes;    // per dimension
  bool monotone;            // limit slopes
};

// Successive 1-D Hermite passes: interpolate the sub-grid of each stencil node along the
// remaining axes, then combine the (up to) 4 results along this axis. Depth <= 6, at most
// 2.3 KB of stack per level; statuses only from nodes inside the cell (j = 1, 2 on every axis).
void cubic_recurse(const CubicContext& c, int d, std::size_t offset, bool inner, double* out,
                   StatusFold& fold) noexcept {
  const int nv = c.n_values;
  if (d == c.n_dims) {
    const double* rec = c.data + offset;
    for (int k = 0; k < nv; ++k) out[k] = rec[k];
    if (inner) fold.add(rec + c.status_offset);
    return;
  }
  const CubicAxis& a = c.axes[d];
  const int lo = a.has_left ? 0 : 1, hi = a.has_right ? 3 : 2;
  double sub[4][kMaxValues];
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

void interpolate_linear(const Block& block, const AxisLoc* loc, double* values,
                        StatusBits* status) noexcept {
  switch (block.n_dims) {
    case 0: return linear_kernel<0>(block, loc, values, status);
    case 1: return linear_kernel<1>(block, loc, values, status);
    case 2: return linear_kernel<2>(block, loc, values, status);
    case 3: return linear_kernel<3>(block, loc, values, status);
    case 4: return linear_kernel<4>(block, loc, values, status);
    case 5: return linear_kernel<5>(block, loc, values, status);
    default: return linear_kernel<6>(block, loc, values, status);
  }
}

void interpolate_cubic(const Block& block, const Axis* axes, const AxisLoc* loc, bool monotone,
                       double* values, StatusBits* status) noexcept {
  CubicAxis ax[kMaxDims];
  for (int d = 0; d < block.n_dims; ++d)
    ax[d] = make_cubic_axis(axes[block.var[d]], loc[block.var[d]], block.stride[d]);
  const CubicContext c{block.data.data(), block.n_dims, block.n_values, block.values_padded, ax,
                       monotone};
  StatusFold fold(block.n_status);
  cubic_recurse(c, 0, 0, true, values, fold);
  fold.write(status);
}

}  // namespace railtab::lookup::detail
