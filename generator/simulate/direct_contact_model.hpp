// SPDX-License-Identifier: Apache-2.0
// vehicle::ContactModel evaluating the core at every call: rigid geometry at the equilibrium roll,
// the scene's normal model under the wheel load, FASTSIM per loaded patch. Slots and outputs are
// mapped exactly as the table sweep maps them (contact_kernel.hpp: assign_slots for the geometry,
// assign_patch_slots for the patches, a slot's normal force/area and creep forces the sum of its up
// to two patches by slot_normal and slot_creep), so at a grid node it returns what the table holds.
// The reference run of `railtab simulate --direct`. With the scene's load coupling
// (docs/validation/load-coupling.md) creep() re-solves the normal contact of each wheel so that
// normal and creep forces together carry the wheel load, each patch at its slot's creepage, and
// returns the slot's normal force at that creepage in SlotForces::normal_force. The exact
// half-space model (normal_model = "halfspace") goes through the same slots; its creep forces come
// from its steady rolling solution (halfspace_contact.hpp), coupled as the table's when every
// loaded slot has the same creepage, else per patch at its slot's creepage.
#pragma once

#include <cstdint>

#include "normal/normal_model.hpp"
#include "scene/scene.hpp"
#include "kernel/contact_kernel.hpp"
#include "kernel/halfspace_contact.hpp"
#include "tangential/coupled_load.hpp"
#include "tangential/fastsim_contact.hpp"
#include "vehicle/contact_model.hpp"

namespace railtab {

class DirectContactModel final : public vehicle::ContactModel {
 public:
  // Builds the scene's profiles and solver; throws railtab::Error for a bad scene.
  explicit DirectContactModel(const Scene& scene);

  // At the wheelset's `yaw` when the scene tabulates yaw ([grid] yaw with several values), as the
  // lookup model reads a yaw table; otherwise at the scene's fixed yaw (0 without the key).
  void normal(double y, double yaw, const double (&load)[vehicle::kWheels],
              vehicle::WheelContacts (&contacts)[vehicle::kWheels]) override;
  void creep(const vehicle::SlotCreepage (&creepage)[vehicle::kWheels][vehicle::kContactSlots],
             vehicle::SlotForces (&forces)[vehicle::kWheels][vehicle::kContactSlots]) override;

  // Evaluations where the core threw (the slot's outputs are zero, status kFailed) [-].
  std::uint64_t failures() const { return failures_; }
  // normal() follows the wheelset's yaw (the scene tabulates yaw).
  bool has_yaw_axis() const { return yaw_axis_; }

 private:
  // creep() of wheel w with the load coupling.
  void creep_coupled(int w, const vehicle::SlotCreepage (&creepage)[vehicle::kContactSlots],
                     vehicle::SlotForces (&forces)[vehicle::kContactSlots], FastsimWorkspace& workspace);

  // creep() of wheel w with the exact half-space model.
  void creep_exact(int w, const vehicle::SlotCreepage (&creepage)[vehicle::kContactSlots],
                   vehicle::SlotForces (&forces)[vehicle::kContactSlots]);

  ContactGeometrySolver solver_;
  Material material_;
  NormalOptions normal_options_;
  CreepConditions creep_conditions_;
  FastsimOptions fastsim_options_;
  CoupledLoadOptions coupling_;
  halfspace::HalfspaceOptions halfspace_options_;
  bool yaw_axis_ = false;                              // the scene tabulates yaw: normal() follows the wheelset's
  double fixed_yaw_ = 0.0;                             // otherwise this yaw [rad]
  halfspace::WheelHalfspaceResult exact_[vehicle::kWheels];  // of the last normal() call (halfspace model)
  double load_[vehicle::kWheels] = {0.0, 0.0};        // of the last normal() call [N]
  CoupledLoadResult coupled_;                          // scratch of creep()
  WheelContactGeometry geometry_[vehicle::kWheels];   // of the last normal() call
  WheelNormalResult normal_[vehicle::kWheels];         // of the last normal() call
  PatchSlots patches_[vehicle::kWheels];                // slot -> patches, of the last normal() call
  bool loaded_[vehicle::kWheels][vehicle::kContactSlots] = {{false, false}, {false, false}};
  std::uint64_t failures_ = 0;
};

}  // namespace railtab
