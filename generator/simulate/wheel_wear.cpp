// SPDX-License-Identifier: Apache-2.0
// The contact model of each wear post-processor: normal model + FASTSIM + Archard/KTH per wheel.
#include "simulate/wheel_wear.hpp"

#include "core/check.hpp"
#include "simulate/halfspace_wheel_wear.hpp"
#include "normal/normal_model.hpp"
#include "scene/simulation_scene.hpp"

namespace railtab {
namespace {

// Normal model (any of src/normal) + FASTSIM (elliptic for Hertz patches, strip-wise otherwise)
// + Archard with the KTH map.
class FastsimWheelWear final : public WheelWear {
 public:
  FastsimWheelWear(const Scene& scene, NormalModel model)
      : material_(scene.material),
        normal_(scene.normal),
        fastsim_(fastsim_options(scene)),
        conditions_(creep_conditions(scene)),
        wear_(wear_options(scene)),
        running_circle_q_(scene.wheelset.back_to_back / 2.0 - scene.wheelset.flange_back_position) {
    normal_.model = model;
  }

  StatusBits wheel_wear(const WheelContactGeometry& geometry, int wheel, double load,
                        const vehicle::WheelsetMotion& motion,
                        std::vector<StripWear>& strips) override {
    strips.clear();
    // The KTH map depends on the slip velocity V |s|: the simulation's speed, not the scene's.
    conditions_.speed = motion.speed;
    solve_normal_for_load(geometry, load, material_, normal_, normal_result_);
    StatusBits bits = normal_result_.status;
    for (const ContactPatch& patch : normal_result_.patches) {
      if (!(patch.normal_force > 0.0)) continue;
      vehicle::SlotContact slot;
      slot.loaded = true;
      slot.contact_angle = patch.contact_angle;
      slot.rolling_radius = patch.rolling_radius;
      slot.wheel_u = patch.wheel_u;
      slot.normal_force = patch.normal_force;
      slot.area = patch.area;
      slot.status = patch.status;
      const vehicle::SlotCreepage c = vehicle::creepage(motion, wheel, slot, running_circle_q_);
      const FastsimResult force = fastsim_contact(geometry, patch, Creepage{c.xi, c.eta, c.phi},
                                                  conditions_, material_, fastsim_, workspace_);
      const WearResult wear = archard_wear(workspace_, wear_, distribution_);
      bits |= patch.status | force.status | wear.status;
      // archard_wear sizes distribution_.strips to this solve's strips.
      strips.insert(strips.end(), distribution_.strips.begin(), distribution_.strips.end());
    }
    return bits;
  }

 private:
  Material material_;
  NormalOptions normal_;
  FastsimOptions fastsim_;
  CreepConditions conditions_;
  WearOptions wear_;
  double running_circle_q_;  // q0 of vehicle::contact_lateral_position [m]
  // Reused between samples (they only grow).
  WheelNormalResult normal_result_;
  FastsimWorkspace workspace_;
  WearDistribution distribution_;
};

}  // namespace

std::unique_ptr<WheelWear> make_wheel_wear(const Scene& scene, const std::string& name) {
  check_wear_post_processor(name);
  if (name == "halfspace") return std::make_unique<HalfspaceWheelWear>(scene);
  return std::make_unique<FastsimWheelWear>(scene, parse_normal_model(name));
}

}  // namespace railtab
