// SPDX-License-Identifier: Apache-2.0
#include "creep_map.hpp"

#include <algorithm>
#include <cmath>

namespace railtab::lookup::detail {
namespace {

inline double m(double x) noexcept { return x / (1.0 + std::abs(x)); }

}  // namespace

void interpolate_scales(const CreepMap& map, int wheel, int slot, const AxisLoc* loc, double out[3]) noexcept {
  const double* base = map.scale[wheel].data() + static_cast<std::size_t>(slot) * map.nodes * 3;
  std::size_t origin = 0;
  for (int d = 0; d < map.n_dims; ++d) origin += static_cast<std::size_t>(loc[map.var[d]].i) * map.stride[d];
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
  const double mlo = m(lo / s), mhi = m(hi / s);
  return -1.0 + 2.0 * (m(q / s) - mlo) / (mhi - mlo);
}

void creep_law(double xi_n, double eta_n, double psi_n, double out[2]) noexcept {
  const double x = xi_n, y = eta_n + psi_n / 3.0;
  const double r = std::hypot(x, y);
  if (!(r > 0.0)) {
    out[0] = out[1] = 0.0;
    return;
  }
  const double w = 1.0 - std::min(r, 1.0);
  const double g = 1.0 - w * w * w;
  out[0] = -g * x / r;
  out[1] = -g * y / r;
}

}  // namespace railtab::lookup::detail
