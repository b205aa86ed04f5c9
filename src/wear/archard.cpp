// SPDX-License-Identifier: Apache-2.0
// Archard wear over a contact patch from the FASTSIM element results (archard.hpp).
#include "wear/archard.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/check.hpp"

namespace railtab {

namespace {

// cos of the wheel-profile slope at strip i: |du/dy| from the neighbouring strips.
double profile_cosine(const FastsimWorkspace& ws, int i) {
  const int m = ws.strips();
  const auto& st = ws.strip;
  if (m >= 2) {
    const int i0 = std::max(0, i - 1), i1 = std::min(m - 1, i + 1);
    const double dy = st[static_cast<std::size_t>(i1)].y - st[static_cast<std::size_t>(i0)].y;
    const double du =
        st[static_cast<std::size_t>(i1)].wheel_u - st[static_cast<std::size_t>(i0)].wheel_u;
    if (std::abs(dy) > 0.0) return std::clamp(std::abs(du / dy), 0.05, 1.0);
  }
  return std::clamp(std::cos(st[static_cast<std::size_t>(i)].contact_angle), 0.05, 1.0);
}

}  // namespace

WearResult archard_wear(const FastsimWorkspace& ws, const WearOptions& options,
                        WearDistribution& out) {
  validate(options.map);
  const int m = ws.strips();
  out.strips.resize(static_cast<std::size_t>(m));
  out.element_depth.resize(static_cast<std::size_t>(ws.elements()));
  const double inv_h = 1.0 / options.map.hardness;
  const double circumference = 2.0 * std::numbers::pi * ws.reference_radius;

  WearResult r;
  r.status = status::kConverged;
  double seizure_volume = 0.0;
  for (int i = 0; i < m; ++i) {
    const FastsimStrip& s = ws.strip[static_cast<std::size_t>(i)];
    const int e0 = ws.strip_begin[static_cast<std::size_t>(i)];
    const int e1 = ws.strip_begin[static_cast<std::size_t>(i) + 1];
    double depth = 0.0, seizure = 0.0;
    for (int e = e0; e < e1; ++e) {
      const auto ue = static_cast<std::size_t>(e);
      const double p = ws.wear_pressure[ue];
      const double k = kth_wear_coefficient(options.map, p, ws.slip_velocity[ue],
                                            options.lubrication);
      const double dz = k * p * ws.slip_distance[ue] * inv_h;
      out.element_depth[ue] = dz;
      depth += dz;
      if (kth_region(options.map, p, ws.slip_velocity[ue]) == KthRegion::seizure) seizure += dz;
    }
    const double cb = profile_cosine(ws, i);
    StripWear& w = out.strips[static_cast<std::size_t>(i)];
    w.wheel_u = s.wheel_u;
    w.width_u = s.width * cb;
    w.depth_per_pass = depth;
    w.depth_rate = circumference > 0.0 ? depth / cb / circumference : 0.0;
    r.volume_rate += depth * s.width;
    seizure_volume += seizure * s.width;
    r.max_depth_rate = std::max(r.max_depth_rate, w.depth_rate);
  }
  r.wear_rate = circumference > 0.0 ? r.volume_rate / circumference : 0.0;
  r.seizure_fraction = r.volume_rate > 0.0 ? seizure_volume / r.volume_rate : 0.0;
  if (ws.elements() == 0) r.status |= status::kLiftOff;
  return r;
}

}  // namespace railtab
