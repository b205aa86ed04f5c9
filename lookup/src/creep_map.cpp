// SPDX-License-Identifier: Apache-2.0
// Normalised creep coordinates on the lookup side (creep_map.hpp): physical creepage to node coordinate and back to N.
#include "creep_map.hpp"

#include <cmath>

#include "part_spec.hpp"
#include "table_data.hpp"

namespace railtab::lookup::detail {

void set_normal_grid(const TableData& d, NodeGrid& g) noexcept {
  g = NodeGrid{};
  for (const int var : kFileOrder) {
    if (!kPartSpecs[kNormal].uses[var] || !d.tabulated[var]) continue;
    g.var[g.n_dims] = var;
    g.size[g.n_dims] = d.axis[var].size();
    ++g.n_dims;
  }
  for (int k = g.n_dims - 1; k >= 0; --k) {
    g.stride[k] = g.nodes;
    g.nodes *= static_cast<std::size_t>(g.size[k]);
  }
}

void interpolate_node_values(const NodeGrid& g, const double* values, int width, const AxisLoc* loc,
                             double* out) noexcept {
  std::size_t origin = 0;
  for (int d = 0; d < g.n_dims; ++d) origin += static_cast<std::size_t>(loc[g.var[d]].i) * g.stride[d];
  const double* base = values + origin * static_cast<std::size_t>(width);
  if (g.n_dims == 2) {  // (y, load), the usual case: bilinear without the corner loop
    bilinear_node_values(base, g.stride[0], g.stride[1], width, loc[g.var[0]].t, loc[g.var[1]].t, out);
    return;
  }
  for (int k = 0; k < width; ++k) out[k] = 0.0;
  for (int corner = 0; corner < (1 << g.n_dims); ++corner) {
    double w = 1.0;
    std::size_t node = 0;
    for (int d = 0; d < g.n_dims; ++d) {
      const bool upper = (corner >> d) & 1;
      const double t = loc[g.var[d]].t;
      w *= upper ? t : 1.0 - t;
      node += upper ? g.stride[d] : 0;
    }
    const double* v = base + node * static_cast<std::size_t>(width);
    for (int k = 0; k < width; ++k) out[k] += w * v[k];
  }
}

void interpolate_scales(const CreepMap& map, int wheel, int slot, const AxisLoc* loc, double out[3]) noexcept {
  interpolate_node_values(map, map.scale[wheel].data() + static_cast<std::size_t>(slot) * map.nodes * 3, 3, loc, out);
}

double creep_coordinate(double q, double lo, double hi, double s) noexcept {
  const double inv = 1.0 / s;
  return creep_coordinate_normalised(q * inv, lo * inv, hi * inv);
}

namespace {

// v = -1 + 2 (m(x) - m(a)) / (m(b) - m(a)) (creep_coordinate_normalised) and its partial
// derivatives with respect to x, a and b; m(x) = x / (1 + |x|), m'(x) = 1 / (1 + |x|)^2.
void coordinate_partials(double x, double a, double b, double out[3]) noexcept {
  auto m = [](double z) { return z / (1.0 + std::abs(z)); };
  auto dm = [](double z) { return 1.0 / ((1.0 + std::abs(z)) * (1.0 + std::abs(z))); };
  const double mx = m(x), ma = m(a), mb = m(b), two_over = 2.0 / (mb - ma);  // one division
  out[0] = dm(x) * two_over;
  out[1] = dm(a) * (mx - mb) * (two_over * two_over) * 0.5;
  out[2] = -dm(b) * (mx - ma) * (two_over * two_over) * 0.5;
}

// The saturation law (creep_law) and its Jacobian with respect to (xi', eta', psi'):
// law = -q(r) (x, y), x = xi', y = eta' + psi' / 3, z = spin psi', r = |(x, y, z)|,
// q = g / r = 3 - 3 r + r^2 below r = 1, 1 / r above.
void law_jacobian(const double xn[3], double spin, double law[2], double jac[2][3]) noexcept {
  const double x = xn[0], y = xn[1] + xn[2] / 3.0, z = spin * xn[2];
  const double r = std::sqrt(x * x + y * y + z * z);
  const double q = r < 1.0 ? 3.0 - 3.0 * r + r * r : 1.0 / r;
  const double dq = r < 1.0 ? -3.0 + 2.0 * r : -1.0 / (r * r);
  // The law is 0 at r = 0 (creep_law); its derivative there is the limit -3 I.
  law[0] = r > 0.0 ? -q * x : 0.0;
  law[1] = r > 0.0 ? -q * y : 0.0;
  const double cx = r > 0.0 ? x / r : 0.0, cy = r > 0.0 ? y / r : 0.0, cz = r > 0.0 ? spin * z / r : 0.0;
  const double dxx = -(q + dq * x * cx), dxy = -dq * x * cy, dyx = -dq * y * cx, dyy = -(q + dq * y * cy);
  // d r / d psi' = cy / 3 + cz: through y and, with a spin weight, through z.
  jac[0][0] = dxx, jac[0][1] = dxy, jac[0][2] = dxy / 3.0 - dq * x * cz;
  jac[1][0] = dyx, jac[1][1] = dyy, jac[1][2] = dyy / 3.0 - dq * y * cz;
}

}  // namespace

void coordinate_gradient(const CreepMap& map, int k, double xn, double inv, const double* dxn, const double* dinv,
                         double* dv) noexcept {
  double p[3];
  coordinate_partials(xn * map.kinv[k], map.lo_k[k] * inv, map.hi_k[k] * inv, p);
  const double along = p[0] * map.kinv[k], ends = p[1] * map.lo_k[k] + p[2] * map.hi_k[k];
  for (int var = 0; var < kNumVars; ++var) dv[var] = along * dxn[var] + ends * dinv[var];
}

void denormalise_creep_gradient(const CreepMap& map, const double xn[3], const double (*dxn)[kNumVars],
                                const double* stored, double cos_angle, double sin_angle,
                                double (*dd)[kNumVars]) noexcept {
  double law[2], jac[2][3], dlaw[2][kNumVars];
  law_jacobian(xn, map.law_spin, law, jac);
  for (int c = 0; c < 2; ++c)
    for (int var = 0; var < kNumVars; ++var)
      dlaw[c][var] = jac[c][0] * dxn[0][var] + jac[c][1] * dxn[1][var] + jac[c][2] * dxn[2][var];
  const double mu = map.friction;
  double n = stored[kNormalForce];
  if (map.vertical_share) {  // N = share / (cos a + mu r_y sin a), normal_from_share
    const double share = stored[kNormalForce];
    const double ca = cos_angle, sa = sin_angle, ry = stored[kFy] + law[1];
    const double den = ca + mu * ry * sa;
    const bool guarded = !(std::abs(den) > 1e-3);
    const double used = guarded ? std::copysign(1e-3, den) : den;
    n = share / used;
    for (int var = 0; var < kNumVars; ++var) {
      const double dry = dd[kFy][var] + dlaw[1][var];
      const double dden = guarded ? 0.0 : -sa * dd[kContactAngle][var] + mu * dry * sa + mu * ry * ca * dd[kContactAngle][var];
      dd[kNormalForce][var] = (dd[kNormalForce][var] - n * dden) / used;
    }
  }
  const double mun = mu * n;
  const double rx = stored[kFx] + law[0], ry = stored[kFy] + law[1], rz = stored[kMz];
  for (int var = 0; var < kNumVars; ++var) {
    const double dmun = mu * dd[kNormalForce][var];
    dd[kFx][var] = (dd[kFx][var] + dlaw[0][var]) * mun + rx * dmun;
    dd[kFy][var] = (dd[kFy][var] + dlaw[1][var]) * mun + ry * dmun;
    dd[kMz][var] = dd[kMz][var] * mun + rz * dmun;
  }
}

}  // namespace railtab::lookup::detail
