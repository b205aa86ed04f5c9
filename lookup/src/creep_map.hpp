// SPDX-License-Identifier: Apache-2.0
// Normalised creep coordinates of format 2.1 (docs/table-format.md, "Normalised creep part";
// docs/lookup.md): the creep and wear parts of such a table are tabulated over v in [-1, 1] per
// creepage axis instead of the physical creepage, per (y, roll, load) node and slot, and store
// the creep forces as F / (mu N) minus a saturation law. A query maps its physical creepages to v
// with the scales of the slot's normal contact (interpolated at (y, roll, load)), interpolates,
// and scales back to N. The generator's side is generator/kernel/creep_map.hpp: same formulas.
// Also the normal part's grid (NodeGrid) and the one interpolation of the fields on it (the
// scales here, the linear creep coefficients), and the derivatives of the map, law and N.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "grid.hpp"
#include "railtab/lookup.hpp"

namespace railtab::lookup::detail {

// The normal part's grid: its tabulated axes among y, roll, load (file order), their sizes and
// strides in nodes. Fields of a few values per node and slot live on it: the creep scales
// (CreepMap) and the linear creep coefficients (creep_coefficients.hpp), interpolated by one
// function (interpolate_node_values; one-sided at jumps: one_sided_node_values, jump_piece.hpp).
struct NodeGrid {                 // its axes among y, roll, yaw, load, in file order
  int n_dims = 0;
  int var[kMaxNormalDims] = {};
  int size[kMaxNormalDims] = {};
  std::size_t stride[kMaxNormalDims] = {};  // in nodes
  std::size_t nodes = 1;
  int dim_of(int v) const noexcept {  // the dimension of variable v, -1: not tabulated
    for (int k = 0; k < n_dims; ++k)
      if (var[k] == v) return k;
    return -1;
  }
};

// Sets g to the normal part's grid of a loaded table (its axes read).
struct TableData;
void set_normal_grid(const TableData& d, NodeGrid& g) noexcept;

// Bilinear interpolation of `width` values per node over (y, load): `p00` the values of the cell's
// lowest corner, `stride0` / `stride1` the two axes' strides in nodes, t0 / t1 the cell fractions.
// The one formula of interpolate_node_values' usual case and of the fused query.
inline void bilinear_node_values(const double* p00, std::size_t stride0, std::size_t stride1, int width, double t0,
                                 double t1, double* out) noexcept {
  const double w00 = (1.0 - t0) * (1.0 - t1), w01 = (1.0 - t0) * t1, w10 = t0 * (1.0 - t1), w11 = t0 * t1;
  const double* p01 = p00 + stride1 * static_cast<std::size_t>(width);
  const double* p10 = p00 + stride0 * static_cast<std::size_t>(width);
  const double* p11 = p10 + stride1 * static_cast<std::size_t>(width);
  for (int k = 0; k < width; ++k) out[k] = w00 * p00[k] + w01 * p01[k] + w10 * p10[k] + w11 * p11[k];
}

// Multilinear interpolation of `width` values per node of grid g at the located cell (loc indexed
// by Var): `values` the slot's first node, [node * width + k].
void interpolate_node_values(const NodeGrid& g, const double* values, int width, const AxisLoc* loc,
                             double* out) noexcept;

struct CreepMap : NodeGrid {      // on the normal part's grid
  bool active = false;            // the table has normalised creep coordinates
  double friction = 0.0;          // mu of F / (mu N)
  bool swept[3] = {};             // xi, eta, phi tabulated (else fixed: their value is used)
  double lo[3] = {}, hi[3] = {};  // physical range of each swept axis (the scene's)
  // Knee k of each axis's node map m(x / k) (creep_map `<axis>_knee`, 1 when absent): the
  // coordinate is taken of x / k on the range [lo, hi] / k (kinv = 1 / k, lo_k = lo / k, hi_k = hi / k;
  // with k = 1 the same numbers as before the knee).
  double kinv[3] = {1.0, 1.0, 1.0};
  bool vertical_share = false;    // the creep part's normal_force is N cos(angle) + Fy sin(angle)
  double law_spin = 0.0;          // the law's spin weight (creep_map `law_spin`, 0 when absent)
  double lo_k[3] = {}, hi_k[3] = {};
  // Reciprocal scales 1/s_xi, 1/s_eta, 1/s_phi per node of the normal part's grid and slot:
  // scale[wheel][(slot * nodes + node) * 3 + k]. The query interpolates the reciprocals (the
  // same at the nodes, and no division on its path).
  std::vector<double> scale[2];
};

// The slot's reciprocal scales at the located (y, roll, load) cell (multilinear, as the normal part).
void interpolate_scales(const CreepMap& map, int wheel, int slot, const AxisLoc* loc, double out[3]) noexcept;

// The coordinate v in [-1, 1] of physical creepage q in [lo, hi] at scale s > 0:
// m(x) = x / (1 + |x|), v = -1 + 2 (m(q/s) - m(lo/s)) / (m(hi/s) - m(lo/s)).
double creep_coordinate(double q, double lo, double hi, double s) noexcept;
// The same with q, lo, hi already divided by s (x = q / s, a = lo / s, b = hi / s). Inline (with
// the two below): the query path runs it three times per slot.
inline double creep_coordinate_normalised(double x, double a, double b) noexcept {
  // (m(x) - m(a)) / (m(b) - m(a)), m(x) = x / (1 + |x|), over one common denominator: one division instead of four
  // (the query path's cost), the same value to rounding.
  const double ax = 1.0 + std::abs(x), aa = 1.0 + std::abs(a), ab = 1.0 + std::abs(b);
  return -1.0 + 2.0 * ((x * aa - a * ax) * ab) / ((b * aa - a * ab) * ax);
}

// cos(angle) and sin(angle) of a contact angle, both at once. |angle| <= 2 (every contact angle:
// |angle| < pi / 2): the Taylor polynomials to x^24 (cos) and x^25 (sin), whose next terms are
// below 1e-18 there, by Horner in the two lanes of one SSE2 vector (about 30 instructions; the
// library's sin and cos were ~8 % of a query's time); a few ulp of the library's values. Any other
// angle (or NaN): std::cos and std::sin. Every query path uses this one, so they agree to the byte.
inline void angle_cos_sin(double angle, double& cos_angle, double& sin_angle) noexcept {
  if (!(std::abs(angle) <= 2.0)) {
    cos_angle = std::cos(angle);
    sin_angle = std::sin(angle);
    return;
  }
  typedef double Pair __attribute__((vector_size(16)));  // lane 0: cos, lane 1: sin / angle
  // (-1)^k / (2k)! and (-1)^k / (2k + 1)!, k = 12 .. 1 (k = 0: 1 and 1, the last step).
  static constexpr Pair kCoefficient[12] = {
      {1.0 / 620448401733239439360000.0, 1.0 / 15511210043330985984000000.0},
      {-1.0 / 1124000727777607680000.0, -1.0 / 25852016738884976640000.0},
      {1.0 / 2432902008176640000.0, 1.0 / 51090942171709440000.0},
      {-1.0 / 6402373705728000.0, -1.0 / 121645100408832000.0},
      {1.0 / 20922789888000.0, 1.0 / 355687428096000.0},
      {-1.0 / 87178291200.0, -1.0 / 1307674368000.0},
      {1.0 / 479001600.0, 1.0 / 6227020800.0},
      {-1.0 / 3628800.0, -1.0 / 39916800.0},
      {1.0 / 40320.0, 1.0 / 362880.0},
      {-1.0 / 720.0, -1.0 / 5040.0},
      {1.0 / 24.0, 1.0 / 120.0},
      {-1.0 / 2.0, -1.0 / 6.0},
  };
  const double z = angle * angle;
  const Pair zz = {z, z};
  Pair acc = kCoefficient[0];
  for (int k = 1; k < 12; ++k) acc = acc * zz + kCoefficient[k];
  acc = acc * zz + Pair{1.0, 1.0};  // the last row: cos's 1, sin's 1 (times angle below)
  cos_angle = acc[0];
  sin_angle = acc[1] * angle;
}

// N from the creep part's stored vertical load share (creep_map "normal_force": "vertical_share";
// generator/kernel/creep_map.hpp): N = share / (cos(angle) + mu r_y sin(angle)), r_y = fy / (mu N)
// the interpolated normalised force, angle the slot's contact angle (geometry part).
// `cos_angle`, `sin_angle`: angle_cos_sin of the angle (the fast path computes them early,
// off the critical path, fast_path.cpp).
inline double normal_from_share(double share, double cos_angle, double sin_angle, double mu_ry) noexcept {
  const double den = cos_angle + mu_ry * sin_angle;
  // The coupled solve keeps den well above 0 (a flange at 70 deg: >= 0.1 for |r_y| <= 1); the
  // guard only keeps a corrupt or extrapolated value finite.
  return share / (std::abs(den) > 1e-3 ? den : std::copysign(1e-3, den));
}
inline double normal_from_share(double share, double angle, double mu_ry) noexcept {
  double cos_angle, sin_angle;
  angle_cos_sin(angle, cos_angle, sin_angle);
  return normal_from_share(share, cos_angle, sin_angle, mu_ry);
}

// The saturation law of the stored forces: F / (mu N) = stored + law(xi', eta', psi'), with
// x = xi', y = eta' + psi' / 3, r = |(x, y, spin psi')|, g = 1 - (1 - min(r, 1))^3,
// law = -g (x, y) / r; spin the table's law_spin (0: the law of tables before it, same numbers).
inline void creep_law(double xi_n, double eta_n, double psi_n, double spin, double out[2]) noexcept {
  const double x = xi_n, y = eta_n + psi_n / 3.0, z = spin * psi_n;
  const double r = std::sqrt(x * x + y * y + z * z);  // O(1) values: no need for hypot's care (or cost)
  if (!(r > 0.0)) {
    out[0] = out[1] = 0.0;
    return;
  }
  const double w = 1.0 - std::min(r, 1.0);
  const double g = 1.0 - w * w * w;
  out[0] = -g * x / r;
  out[1] = -g * y / r;
}

// The slot's outputs back in newtons: the interpolated F / (mu N) minus the law, plus the law at the
// query's normalised creepages xn, times mu N, N first recovered from the vertical share when the
// table stores it (cos_angle, sin_angle of the slot's contact angle; unused otherwise). `value`
// is indexed by lookup::Output. Every query path ends with this, in this order of operations.
inline void denormalise_creep(const CreepMap& map, const double xn[3], double cos_angle, double sin_angle,
                              double* value) noexcept {
  double law[2];
  creep_law(xn[0], xn[1], xn[2], map.law_spin, law);
  if (map.vertical_share)
    value[kNormalForce] = normal_from_share(value[kNormalForce], cos_angle, sin_angle, map.friction * (value[kFy] + law[1]));
  const double mun = map.friction * value[kNormalForce];
  value[kFx] = (value[kFx] + law[0]) * mun;
  value[kFy] = (value[kFy] + law[1]) * mun;
  value[kMz] *= mun;
}

// ---- Derivatives of the above (Table::query_derivatives, derivatives.cpp and the fused path of
// fast_path.cpp: one formula for both).

// The row d v / d variable of creepage axis k's coordinate v = creep_coordinate_normalised(xn
// kinv, lo_k inv, hi_k inv) at the normalised creepage xn = creepage inv (inv the slot's
// reciprocal scale), from d xn / d variable (`dxn`) and d inv / d variable (`dinv`), rows over
// the state variables.
void coordinate_gradient(const CreepMap& map, int k, double xn, double inv, const double* dxn, const double* dinv,
                         double* dv) noexcept;

// The derivatives of denormalise_creep's outputs: `stored` the block's values before it (indexed
// by Output: the contact angle, the normal force or its vertical share, the fx, fy, mz
// residuals), xn the normalised creepages and dxn their rows, cos_angle and sin_angle those of
// stored[kContactAngle] (used with a vertical share only); `dd` (rows by Output, columns by state
// variable) holds the stored values' derivatives on entry and those of the forces in N
// (kNormalForce, kFx, kFy, kMz) on return.
void denormalise_creep_gradient(const CreepMap& map, const double xn[3], const double (*dxn)[kNumVars],
                                const double* stored, double cos_angle, double sin_angle,
                                double (*dd)[kNumVars]) noexcept;

}  // namespace railtab::lookup::detail
