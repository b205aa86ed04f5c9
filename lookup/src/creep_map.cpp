// SPDX-License-Identifier: Apache-2.0
// Normalised creep coordinates on the lookup side (creep_map.hpp): physical creepage to node coordinate and back to N.
#include "creep_map.hpp"

namespace railtab::lookup::detail {

void interpolate_scales(const CreepMap& map, int wheel, int slot, const AxisLoc* loc, double out[3]) noexcept {
  const double* base = map.scale[wheel].data() + static_cast<std::size_t>(slot) * map.nodes * 3;
  std::size_t origin = 0;
  for (int d = 0; d < map.n_dims; ++d) origin += static_cast<std::size_t>(loc[map.var[d]].i) * map.stride[d];
  if (map.n_dims == 2) {  // (y, load), the usual case: bilinear without the corner loop
    bilinear_scales(base + origin * 3, map.stride[0], map.stride[1], loc[map.var[0]].t, loc[map.var[1]].t, out);
    return;
  }
  out[0] = out[1] = out[2] = 0.0;
  for (int corner = 0; corner < (1 << map.n_dims); ++corner) {
    double w = 1.0;
    std::size_t node = origin;
    for (int d = 0; d < map.n_dims; ++d) {
      const bool upper = (corner >> d) & 1;
      const double t = loc[map.var[d]].t;
      w *= upper ? t : 1.0 - t;
      node += upper ? map.stride[d] : 0;
    }
    const double* v = base + node * 3;
    out[0] += w * v[0];
    out[1] += w * v[1];
    out[2] += w * v[2];
  }
}

double creep_coordinate(double q, double lo, double hi, double s) noexcept {
  const double inv = 1.0 / s;
  return creep_coordinate_normalised(q * inv, lo * inv, hi * inv);
}

}  // namespace railtab::lookup::detail
