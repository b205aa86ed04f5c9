// The wheel-rail contact kernel of the table sweep: per (y, roll) column and wheel, the rigid
// geometry once (ContactGeometrySolver::solve_wheel), the normal contact once per load on top of
// it, and FASTSIM creep forces and Archard wear per creepage on top of each loaded patch. Outputs
// are declared in descriptor tables in contact_kernel.cpp: adding an output is one line there.
#pragma once

#include "normal/normal_model.hpp"
#include "scene.hpp"
#include "sweep.hpp"

namespace railtab {

// Contacts go to slots by ContactPoint::status & kFlangeContact (slot 1 flange, slot 0 tread); two
// contacts in one slot keep the lower-separation one and set kTwoPoint on that slot.
struct SlotAssignment {
  int point[kSlots] = {-1, -1};    // index into WheelContactGeometry::points, -1 = empty slot
  StatusBits extra[kSlots] = {0, 0};  // kTwoPoint when a contact was dropped from the slot
};
SlotAssignment assign_slots(const WheelContactGeometry& geometry);

// Loaded patches (normal, creep and wear parts) go to slots by their reference contact angle: slot 1
// when the side-frame angle exceeds flange_angle, else slot 0. Two patches in one slot keep the one
// with the larger normal force and set kTwoPoint on that slot (the other's load is not tabulated).
struct PatchSlots {
  int patch[kSlots] = {-1, -1};       // index into WheelNormalResult::patches, -1 = empty slot
  StatusBits extra[kSlots] = {0, 0};  // kTwoPoint when a patch was dropped from the slot
};
PatchSlots assign_patch_slots(const WheelNormalResult& normal, Side side, double flange_angle);

// Builds the profiles and solver of the scene (throws railtab::Error for bad profiles/geometry).
SweepKernel make_contact_kernel(const Scene& scene);

}  // namespace railtab
