// SPDX-License-Identifier: Apache-2.0
// The exact half-space wear post-processor ("halfspace", Enblom and Berg's (2008) CONTACT): src/halfspace's
// planar-patch solver instead of a fast normal model + FASTSIM, then Archard/KTH wear per element.
//
// Load: the normal problem is solved for the dynamics' vertical force sum N cos(g)
// (solve_halfspace_for_load), as every other post-processor does (wheel_wear.hpp), so all of them
// carry the dynamics' normal force. solve_halfspace_rolling is NOT used: it takes the vertical
// load as N cos(g) + fy sin(g) (CONTACT's coupling) and would give the half-space patches a
// different N from the others in flange contact; the comparison would then mix the load
// definition with the contact model.
// Creepages: per patch, vehicle::creepage at the patch's reference point (its own angle, radius
// and wheel u), then solve_halfspace_tangential on that patch alone (the library applies one
// creepage to every patch of a result).
// Wear onto the wheel profile: element depths per pass (archard_wear_per_pass) summed along
// the rolling direction give the depth per pass of each grid row (one lateral position y of the
// tangent plane); each row becomes one StripWear whose extent in wheel u is the row's edges
// y -+ dy/2 mapped through the band samples (u of the facing wheel point against y in the
// patch's plane), and whose radial rate is depth / (width_u / dy) / (2 pi r_ref): the same
// conversion as archard_wear for FASTSIM strips (worn area = depth x dy per circumference).
#pragma once

#include <vector>

#include "halfspace/wheel_rail.hpp"
#include "halfspace/workspace.hpp"
#include "simulate/wheel_wear.hpp"

namespace railtab {

class HalfspaceWheelWear final : public WheelWear {
 public:
  explicit HalfspaceWheelWear(const Scene& scene);

  StatusBits wheel_wear(const WheelContactGeometry& geometry, int wheel, double load,
                        const vehicle::WheelsetMotion& motion,
                        std::vector<StripWear>& strips) override;

  // The same with one prescribed creepage for every patch (contact frame, wheel minus rail) at
  // rolling speed `speed` [m/s]: for single-patch comparisons and tests.
  StatusBits wheel_wear_at(const WheelContactGeometry& geometry, double load,
                           const Creepage& creepage, double speed, std::vector<StripWear>& strips);

  // The solution of the last call (patches with pressure, traction, slip).
  const halfspace::WheelHalfspaceResult& last_result() const { return result_; }

 private:
  // Solves patch k's tangential problem at `creepage` and appends its strips.
  StatusBits patch_wear(const WheelContactGeometry& geometry, std::size_t k, const Creepage& creepage,
                        double speed, std::vector<StripWear>& strips);

  Material material_;
  double friction_;
  WearOptions wear_;
  halfspace::HalfspaceOptions options_;
  double running_circle_q_;  // q0 of vehicle::contact_lateral_position [m]
  // One per post-processor instance (not thread-safe; a simulation's accumulators run on one thread).
  halfspace::Workspace workspace_;
  halfspace::WheelHalfspaceResult result_;
  halfspace::WheelHalfspaceResult single_;  // one patch at a time for its own creepage
  std::vector<double> element_depth_;
};

}  // namespace railtab
