// SPDX-License-Identifier: Apache-2.0
// The exact half-space wear post-processor: src/halfspace + Archard/KTH per element, per row onto
// the wheel profile.
#include "simulate/halfspace_wheel_wear.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/check.hpp"

namespace railtab {
namespace {

struct RowMap {  // one band sample in the patch's tangent plane
  double y;        // contact-frame lateral coordinate [m]
  double wheel_u;  // wheel-profile coordinate of the facing wheel point [m]
};

// The band samples seen in the tangent plane of patch `hp`, sorted by y: the transform of
// halfspace::build_grid (y = (P(s) - P_ref) . t_ref, t_ref = (cos g_ref, sin g_ref) in the
// side frame), so a grid row's y finds the wheel point it belongs to.
std::vector<RowMap> plane_map(const WheelContactGeometry& g, const halfspace::HalfspacePatch& hp) {
  std::vector<RowMap> out;
  const int nb = static_cast<int>(g.band.size());
  if (nb < 2 || !(g.band_step > 0.0)) return out;
  const double t = (hp.band_s - g.band.front().s) / g.band_step;
  const int k0 = std::clamp(static_cast<int>(std::floor(t)), 0, nb - 2);
  const double f = std::clamp(t - k0, 0.0, 1.0);
  const auto& b0 = g.band[static_cast<std::size_t>(k0)];
  const auto& b1 = g.band[static_cast<std::size_t>(k0) + 1];
  const double q_ref = (1 - f) * b0.q + f * b1.q;
  const double z_ref = (1 - f) * b0.z + f * b1.z;
  const double tq = std::cos(hp.contact_angle_side), tz = std::sin(hp.contact_angle_side);
  out.reserve(g.band.size());
  for (const BandSample& b : g.band) out.push_back({(b.q - q_ref) * tq + (b.z - z_ref) * tz, b.wheel_u});
  std::sort(out.begin(), out.end(), [](const RowMap& a, const RowMap& b) { return a.y < b.y; });
  return out;
}

// wheel u at plane coordinate y (linear; the end segments extended beyond the band).
double wheel_u_at(const std::vector<RowMap>& m, double y) {
  auto it = std::lower_bound(m.begin(), m.end(), y, [](const RowMap& a, double v) { return a.y < v; });
  if (it == m.begin()) ++it;
  if (it == m.end()) --it;
  const RowMap& a = *(it - 1);
  const RowMap& b = *it;
  const double f = b.y > a.y ? (y - a.y) / (b.y - a.y) : 0.0;
  return a.wheel_u + f * (b.wheel_u - a.wheel_u);
}

}  // namespace

HalfspaceWheelWear::HalfspaceWheelWear(const Scene& scene)
    : material_(scene.material),
      friction_(scene.tangential.friction),
      wear_(wear_options(scene)),
      running_circle_q_(scene.wheelset.back_to_back / 2.0 - scene.wheelset.flange_back_position) {}

StatusBits HalfspaceWheelWear::patch_wear(const WheelContactGeometry& geometry, std::size_t k,
                                          const Creepage& creepage, double speed,
                                          std::vector<StripWear>& strips) {
  // The library solves every patch of a result at one creepage: hand it this patch alone.
  single_.patches.resize(1);
  std::swap(single_.patches[0], result_.patches[k]);
  solve_halfspace_tangential(single_, creepage, friction_, material_, options_, workspace_);
  std::swap(single_.patches[0], result_.patches[k]);
  const halfspace::HalfspacePatch& hp = result_.patches[k];
  RAILTAB_CHECK(std::isfinite(hp.tangential.fx) && std::isfinite(hp.tangential.fy),
                "half-space wear: creep force not finite (patch at wheel u {} m)", hp.wheel_u);

  halfspace::archard_wear_per_pass(hp, speed, wear_, element_depth_);
  const halfspace::Grid& g = hp.grid;
  const std::vector<RowMap> map = plane_map(geometry, hp);
  RAILTAB_CHECK(!map.empty(), "half-space wear: the wheel has no contact band");
  const double circumference = 2.0 * std::numbers::pi * hp.rolling_radius;
  for (int j = 0; j < g.ny; ++j) {
    double depth = 0.0;  // normal depth per pass of a wheel point crossing row j [m]
    for (int i = 0; i < g.nx; ++i) depth += element_depth_[static_cast<std::size_t>(g.index(i, j))];
    if (!(depth > 0.0)) continue;
    const double u0 = wheel_u_at(map, g.y(j) - 0.5 * g.dy);
    const double u1 = wheel_u_at(map, g.y(j) + 0.5 * g.dy);
    StripWear w;
    w.wheel_u = 0.5 * (u0 + u1);
    // As archard_wear: cos of the profile slope |du/dy|, bounded where the map is degenerate.
    const double cb = std::clamp(std::abs(u1 - u0) / g.dy, 0.05, 1.0);
    w.width_u = g.dy * cb;
    w.depth_per_pass = depth;
    w.depth_rate = circumference > 0.0 ? depth / cb / circumference : 0.0;
    strips.push_back(w);
  }
  return hp.status;
}

StatusBits HalfspaceWheelWear::wheel_wear(const WheelContactGeometry& geometry, int wheel, double load,
                                          const vehicle::WheelsetMotion& motion,
                                          std::vector<StripWear>& strips) {
  strips.clear();
  result_ = halfspace::solve_halfspace_for_load(geometry, load, material_, options_, workspace_);
  RAILTAB_CHECK(!(result_.status & status::kInvalidInput),
                "half-space wear: the normal problem rejected its input (vertical force {} N)", load);
  StatusBits bits = result_.status;
  for (std::size_t k = 0; k < result_.patches.size(); ++k) {
    const halfspace::HalfspacePatch& hp = result_.patches[k];
    if (!(hp.normal.normal_force > 0.0)) continue;
    vehicle::SlotContact slot;
    slot.loaded = true;
    slot.contact_angle = hp.contact_angle;
    slot.rolling_radius = hp.rolling_radius;
    slot.wheel_u = hp.wheel_u;
    slot.normal_force = hp.normal.normal_force;
    slot.area = hp.normal.area;
    slot.status = hp.status;
    const vehicle::SlotCreepage c = vehicle::creepage(motion, wheel, slot, running_circle_q_);
    bits |= patch_wear(geometry, k, Creepage{c.xi, c.eta, c.phi}, motion.speed, strips);
  }
  return bits;
}

StatusBits HalfspaceWheelWear::wheel_wear_at(const WheelContactGeometry& geometry, double load,
                                             const Creepage& creepage, double speed,
                                             std::vector<StripWear>& strips) {
  RAILTAB_CHECK(std::isfinite(speed) && speed > 0.0, "half-space wear: speed must be > 0 m/s, got {}", speed);
  strips.clear();
  result_ = halfspace::solve_halfspace_for_load(geometry, load, material_, options_, workspace_);
  RAILTAB_CHECK(!(result_.status & status::kInvalidInput),
                "half-space wear: the normal problem rejected its input (vertical force {} N)", load);
  StatusBits bits = result_.status;
  for (std::size_t k = 0; k < result_.patches.size(); ++k) {
    if (!(result_.patches[k].normal.normal_force > 0.0)) continue;
    bits |= patch_wear(geometry, k, creepage, speed, strips);
  }
  return bits;
}

}  // namespace railtab
