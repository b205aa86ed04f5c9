// SPDX-License-Identifier: Apache-2.0
// Half-space results as the generator's contact types (halfspace_contact.hpp).
#include "kernel/halfspace_contact.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/status.hpp"
#include "wear/kth_wear_map.hpp"

namespace railtab {

halfspace::HalfspaceOptions halfspace_options(const Scene& scene) {
  halfspace::HalfspaceOptions options;
  options.element_size = scene.halfspace.element_size;
  return options;
}

halfspace::Workspace& thread_halfspace_workspace() {
  thread_local halfspace::Workspace workspace;
  return workspace;
}

namespace {

ContactPatch to_contact_patch(const halfspace::HalfspacePatch& hp) {
  ContactPatch c;
  c.model = NormalModel::halfspace;
  c.pressure_shape = StripPressure::semi_elliptic;  // unused: no strips
  c.normal_force = hp.normal.normal_force;
  c.penetration = hp.normal.approach;
  c.area = hp.normal.area;
  c.max_pressure = hp.normal.max_pressure;
  c.band_s = hp.band_s;
  c.contact_angle = hp.contact_angle;
  c.rolling_radius = hp.rolling_radius;
  c.wheel_u = hp.wheel_u;
  c.rail_u = hp.rail_u;
  c.status = hp.status;
  // Lateral extent of the elements in contact; the grid's y points towards the field side,
  // y = s - band_s to first order (halfspace/wheel_rail.hpp).
  const halfspace::Grid& g = hp.grid;
  double y_min = 0.0, y_max = 0.0;
  bool any = false;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(g.index(i, j));
      if (k < hp.normal.pressure.size() && hp.normal.pressure[k] > 0.0) {
        const double lo = g.y(j) - 0.5 * g.dy, hi = g.y(j) + 0.5 * g.dy;
        y_min = any ? std::min(y_min, lo) : lo;
        y_max = any ? std::max(y_max, hi) : hi;
        any = true;
      }
    }
  c.s_start = hp.band_s + y_min;
  c.s_end = hp.band_s + y_max;
  if (!(c.normal_force > 0.0)) c.status |= status::kLiftOff;
  return c;
}

}  // namespace

WheelNormalResult to_normal_result(const halfspace::WheelHalfspaceResult& result,
                                   const WheelContactGeometry& geometry) {
  WheelNormalResult r;
  for (const halfspace::HalfspacePatch& hp : result.patches) r.patches.push_back(to_contact_patch(hp));
  r.point_patch.assign(geometry.points.size(), -1);
  for (std::size_t i = 0; i < geometry.points.size(); ++i) {
    const double s = geometry.points[i].band_s;
    for (std::size_t k = 0; k < r.patches.size(); ++k) {
      const ContactPatch& p = r.patches[k];
      if (p.normal_force > 0.0 && s >= p.s_start && s <= p.s_end) {
        r.point_patch[i] = static_cast<int>(k);
        break;
      }
    }
  }
  // point_index: the point with the smallest separation inside the patch (normal_model.hpp).
  for (std::size_t i = 0; i < geometry.points.size(); ++i) {
    const int k = r.point_patch[i];
    if (k < 0) continue;
    ContactPatch& p = r.patches[static_cast<std::size_t>(k)];
    ++p.points;
    if (p.point_index < 0 ||
        geometry.points[i].separation < geometry.points[static_cast<std::size_t>(p.point_index)].separation)
      p.point_index = static_cast<int>(i);
  }
  r.vertical_approach = result.vertical_approach;
  r.carried_load = result.carried_load;
  r.status = result.status;
  if (r.patches.size() > 1) r.status |= status::kTwoPoint;
  if (r.patches.empty()) r.status |= status::kLiftOff;
  return r;
}

FastsimResult to_creep_result(const halfspace::HalfspacePatch& hp) {
  FastsimResult r;
  if (!(hp.normal.normal_force > 0.0)) {
    r.status = status::kConverged | status::kLiftOff;
    return r;
  }
  const halfspace::TangentialSolution& t = hp.tangential;
  r.fx = t.fx;
  r.fy = t.fy;
  r.mz = t.mz;
  r.normal_force = hp.normal.normal_force;
  r.slip_fraction = hp.normal.area > 0.0 ? std::min(1.0, t.slip_area / hp.normal.area) : 0.0;
  r.frictional_work = t.frictional_work;
  r.status = t.status;
  return r;
}

WearResult halfspace_wear(const halfspace::HalfspacePatch& hp, double speed, const WearOptions& options,
                          std::vector<double>& depth) {
  validate(options.map);
  WearResult r;
  if (!(hp.normal.normal_force > 0.0)) {
    r.status = status::kConverged | status::kLiftOff;
    return r;
  }
  r.status = status::kConverged;
  const double section = halfspace::archard_wear_per_pass(hp, speed, options, depth);
  const halfspace::Grid& g = hp.grid;
  const double circumference = 2.0 * std::numbers::pi * hp.rolling_radius;
  // Radial depth of the wheel profile: the normal depth over the cosine of the contact angle
  // relative to the axle, clamped as archard_wear clamps it (wear/archard.cpp).
  const double cb = std::clamp(std::cos(hp.contact_angle), 0.05, 1.0);
  double seizure = 0.0;
  for (int j = 0; j < g.ny; ++j) {
    double column = 0.0;
    for (int i = 0; i < g.nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(g.index(i, j));
      if (k >= depth.size() || !(depth[k] > 0.0)) continue;
      column += depth[k];
      const double slip = std::hypot(hp.tangential.slip_x[k], hp.tangential.slip_y[k]);
      if (kth_region(options.map, hp.normal.pressure[k], speed * slip) == KthRegion::seizure)
        seizure += depth[k] * g.dy;
    }
    if (circumference > 0.0) r.max_depth_rate = std::max(r.max_depth_rate, column / cb / circumference);
  }
  r.volume_rate = section;
  r.wear_rate = circumference > 0.0 ? section / circumference : 0.0;
  r.seizure_fraction = section > 0.0 ? seizure / section : 0.0;
  return r;
}

void solve_halfspace_tangential_per_patch(halfspace::WheelHalfspaceResult& result, const HalfspacePatchCreepage& creepage_of,
                                          double mu, const Material& material,
                                          const halfspace::HalfspaceOptions& options, halfspace::Workspace& workspace) {
  halfspace::WheelHalfspaceResult one;  // a result of one patch: the public call solves all it holds
  for (std::size_t k = 0; k < result.patches.size(); ++k) {
    const Creepage creepage = creepage_of(k, result.patches[k]);
    one.patches.clear();
    one.patches.push_back(std::move(result.patches[k]));
    halfspace::solve_halfspace_tangential(one, creepage, mu, material, options, workspace);
    result.patches[k] = std::move(one.patches[0]);
  }
}

halfspace::WheelHalfspaceResult solve_halfspace_rolling_per_patch(
    const WheelContactGeometry& geometry, double load, const HalfspacePatchCreepage& creepage_of, double mu,
    const Material& material, const halfspace::HalfspaceOptions& options, bool couple,
    halfspace::Workspace& workspace) {
  auto vertical_part = [](const halfspace::WheelHalfspaceResult& res) {
    double t = 0.0;
    for (const halfspace::HalfspacePatch& hp : res.patches) t += hp.tangential.fy * std::sin(hp.contact_angle);
    return t;
  };
  halfspace::WheelHalfspaceResult r;
  auto round = [&](double tz, bool) {  // normal for F_z - tz, then tangential (full tolerances); the new tz
    halfspace::WheelHalfspaceResult next =
        halfspace::solve_halfspace_for_load(geometry, std::max(0.0, load - tz), material, options, workspace);
    if (next.patches.size() == r.patches.size())  // warm start of the tractions from the previous round
      for (std::size_t k = 0; k < next.patches.size(); ++k)
        if (next.patches[k].grid.nx == r.patches[k].grid.nx && next.patches[k].grid.ny == r.patches[k].grid.ny)
          next.patches[k].tangential = std::move(r.patches[k].tangential);
    solve_halfspace_tangential_per_patch(next, creepage_of, mu, material, options, workspace);
    r = std::move(next);
    return vertical_part(r);
  };
  // The fixed point on the vertical load lives once, in src/halfspace (solve_halfspace_rolling's).
  if (!halfspace::solve_load_fixed_point(load, round,
                                      [&] { return !couple || r.patches.empty(); }))
    halfspace::mark_not_converged(r);
  return r;
}

}  // namespace railtab
