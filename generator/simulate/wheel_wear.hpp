// SPDX-License-Identifier: Apache-2.0
// The contact model of one wear post-processor (Enblom and Berg 2008 sections 2.1, 4: the dynamics runs with
// one contact model, the wear is computed afterwards, once per wheel revolution, with another):
// from one wheel's contact geometry, its vertical contact force in the dynamics and the
// wheelset's motion to the radial wear rate per strip across the wheel profile. WearAccumulator
// bins the strips; which contact model made them is this interface's business only.
//
// Post-processors by name: "hertz" (elliptic: Hertz + FASTSIM on the ellipse, as Gensys),
// "stripes-a", "stripes-ab", "kik-piotrowski", "linder" (the non-elliptic normal models +
// strip-wise FASTSIM): FastsimWheelWear, one class for all, the normal model is the difference.
// "halfspace": the exact half-space model (src/halfspace), HalfspaceWheelWear
// (halfspace_wheel_wear.hpp), Enblom and Berg's (2008) CONTACT.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "scene/scene.hpp"
#include "vehicle/kinematics.hpp"

namespace railtab {

class WheelWear {
 public:
  virtual ~WheelWear() = default;

  // Strips of wheel `wheel` (0 left, 1 right) into `strips` (cleared first): the normal problem
  // at `load` [N] (the interpenetration adapted so that the patches carry the
  // dynamics' force), each patch's creepages from `motion` (vehicle::creepage with the patch's
  // own angle, radius and position), the tangential problem and Archard/KTH wear. Returns the
  // status bits of every solve. Throws railtab::Error when a solve fails.
  virtual StatusBits wheel_wear(const WheelContactGeometry& geometry, int wheel,
                                double load, const vehicle::WheelsetMotion& motion,
                                std::vector<StripWear>& strips) = 0;
};

// The post-processor `name` (checked by check_wear_post_processor, scene/simulation_scene.hpp) with the profiles, material, friction, wear map and normal-model
// settings of `scene` (its own normal model is replaced by `name`'s).
std::unique_ptr<WheelWear> make_wheel_wear(const Scene& scene, const std::string& name);

}  // namespace railtab
