// SPDX-License-Identifier: Apache-2.0
// FASTSIM on any contact patch of the normal layer (fastsim_contact.hpp).
#include "tangential/fastsim_contact.hpp"

namespace railtab {

FastsimResult fastsim_contact(const WheelContactGeometry& geometry, const ContactPatch& patch,
                              const Creepage& creepage, const CreepConditions& conditions,
                              const Material& material, const FastsimOptions& options,
                              FastsimWorkspace& workspace) {
  if (!(patch.normal_force > 0.0)) {
    // Empty the workspace: archard_wear reads the elements of the LAST solve, and without this an
    // unloaded patch inherited the previous patch's elements and reported its wear (found by
    // tests/stability/lift_off_test.cpp, UnloadedPatchHasNoCreepOrWear).
    workspace.strip.clear();
    workspace.strip_begin.assign(1, 0);
    for (auto* v : {&workspace.x, &workspace.pressure, &workspace.traction_x, &workspace.traction_y,
                    &workspace.slip_x, &workspace.slip_y, &workspace.slip_velocity,
                    &workspace.slip_distance, &workspace.wear_pressure})
      v->clear();
    workspace.speed = conditions.speed;
    workspace.reference_radius = patch.rolling_radius;
    FastsimResult unloaded;
    unloaded.status = status::kLiftOff;
    return unloaded;
  }
  if (patch.strips.empty() && patch.semi_axis_a > 0.0 && patch.semi_axis_b > 0.0) {
    // Hertz without strips (NormalOptions::hertz_strips off): Kalker's FASTSIM on the ellipse.
    // The ellipse lies in the contact plane; on the wheel profile it spans 2 b cos(beta), beta =
    // the contact angle relative to the wheel's own axle (roll included), and s runs towards -u
    // on the right wheel.
    const double sigma = outward_sign(geometry.side);
    const double beta = sigma * patch.contact_angle - geometry.wheel_roll;
    const EllipticPatch ellipse{patch.semi_axis_a, patch.semi_axis_b, patch.normal_force,
                                conditions.ellipse_strips, patch.rolling_radius, patch.wheel_u,
                                sigma * std::cos(beta)};
    return fastsim_ellipse(ellipse, creepage, conditions.friction, conditions.speed, material,
                           options.elements_per_strip, workspace);
  }
  return fastsim_patch(patch, placement_of(geometry, patch), creepage, conditions.friction,
                       conditions.speed, material, options, workspace);
}

}  // namespace railtab
