// SPDX-License-Identifier: Apache-2.0
// The wheel-rail contact kernel of the table sweep: per (y, roll) column and wheel, the rigid
// geometry once (ContactGeometrySolver::solve_wheel), the normal contact once per load on top of
// it, and FASTSIM creep forces and Archard wear per creepage on top of each slot's loaded patches
// (a slot's outputs are the sum of its up to two patches). Outputs
// are declared in descriptor tables in contact_kernel.cpp: adding an output is one line there.
#pragma once

#include <cstddef>
#include <functional>

#include "normal/normal_model.hpp"
#include "scene/scene.hpp"
#include "engine/sweep.hpp"
#include "halfspace/wheel_rail.hpp"
#include "tangential/fastsim_contact.hpp"
#include "tangential/linear_creep.hpp"
#include "wear/archard.hpp"

namespace railtab {

// Contacts go to slots by ContactPoint::status & kFlangeContact (slot 1 flange, slot 0 tread); two
// contacts in one slot keep the lower-separation one and set kTwoPoint on that slot.
struct SlotAssignment {
  int point[kSlots] = {-1, -1};    // index into WheelContactGeometry::points, -1 = empty slot
  StatusBits extra[kSlots] = {0, 0};  // kTwoPoint when a contact was dropped from the slot
};
SlotAssignment assign_slots(const WheelContactGeometry& geometry);

// Loaded patches (normal, creep and wear parts) go to slots by their reference contact angle: slot 1
// when the side-frame angle exceeds flange_angle, else slot 0. A slot holds up to two patches and its
// outputs are their sum (slot_normal, slot_creep); patch[s][0] is the one with the larger normal force
// (the lower index on a tie). Two patches in one slot set kTwoPoint on that slot. A third patch in one
// slot (rare) is dropped, the one with the smallest normal force: its load is not tabulated, the
// slot keeps kTwoPoint and `dropped` counts it.
inline constexpr std::size_t kPatchesPerSlot = 2;
struct PatchSlots {
  int patch[kSlots][kPatchesPerSlot] = {{-1, -1}, {-1, -1}};  // into WheelNormalResult::patches, -1 = none
  StatusBits extra[kSlots] = {0, 0};  // kTwoPoint when the slot holds two patches (or dropped one)
  int dropped[kSlots] = {0, 0};       // patches beyond two dropped from the slot
  bool occupied(std::size_t slot) const { return patch[slot][0] >= 0; }
};
PatchSlots assign_patch_slots(const WheelNormalResult& normal, Side side, double flange_angle);

// The normal part of a slot: a copy of its larger-N patch (reference point, approach, a, b) with
// normal_force and area summed over the slot's patches, max_pressure the larger, status the OR of
// the patches' bits (without the solver's and the slot's extra bits). The slot must be occupied.
ContactPatch slot_normal(const WheelNormalResult& normal, const PatchSlots& slots, std::size_t slot);

// Wear on top of slot_creep: the options in, the slot's summed result out.
struct SlotWear {
  const WearOptions& options;
  WearDistribution& distribution;
  WearResult result;
};

// Creep forces of a slot at ONE creepage (the table has one per slot): FASTSIM on each loaded patch
// of the slot at that creepage, fx, fy, mz (each about its own patch's reference) and the normal
// force added, slip_fraction area-weighted, status the OR of the patches' bits. With `wear`, Archard
// wear per patch on top of its FASTSIM result: wear_rate and volume_rate added, the largest depth
// rate, seizure_fraction volume-weighted, status OR. A slot without a loaded patch gives zeros with
// kConverged | kLiftOff. Throws what fastsim_contact / archard_wear throw.
FastsimResult slot_creep(const WheelContactGeometry& geometry, const WheelNormalResult& normal,
                         const PatchSlots& slots, std::size_t slot, const Creepage& creepage,
                         const CreepConditions& conditions, const Material& material, const FastsimOptions& options,
                         FastsimWorkspace& workspace, SlotWear* wear = nullptr);

// The summation of slot_creep over a slot's loaded patches, with each patch's creep result (and,
// when `wear` is given, its wear into the WearResult*) from `solve_patch(patch index, wear)`:
// FASTSIM for the fast models, the exact solution for the half-space model (halfspace_contact.hpp).
using PatchCreep = std::function<FastsimResult(std::size_t patch, WearResult* wear)>;
FastsimResult sum_slot_creep(const WheelNormalResult& normal, const PatchSlots& slots, std::size_t slot,
                             const PatchCreep& solve_patch, SlotWear* wear = nullptr);

// The linear creep coefficients of a slot (the normal part's creep_coefficient_* datasets): the
// slopes of the slot's creep forces at zero creepage in full adhesion, summed over its loaded
// patches (mz each about its own patch's reference, as slot_creep sums). The fast models:
// fastsim_linear_creep on each patch of `normal`; with `exact` (the half-space model's own
// result, whose patches are those of `normal`): its steady rolling solution on each patch
// (halfspace::patch_linear_creep). A slot without a loaded patch gives zeros. Throws what those
// throw (a steady rolling solve that does not converge).
LinearCreep slot_linear_creep(const WheelContactGeometry& geometry, const WheelNormalResult& normal,
                              const halfspace::WheelHalfspaceResult* exact, const PatchSlots& slots, std::size_t slot,
                              const CreepConditions& conditions, const Material& material,
                              const FastsimOptions& fastsim, const halfspace::HalfspaceOptions& halfspace);

// The kinematic equilibrium roll at y as tables use it: exactly odd in y (the solver's at |y|,
// negated for y < 0), so that the mirror (y, roll) -> (-y, -roll) swaps the wheels to the last
// bit (engine/mirror.hpp); the solver's own search, run at each y, is odd only to its tolerance.
double table_equilibrium_roll(const ContactGeometrySolver& solver, double y);

// Run time per computed grid point of the scene's contact chain (the exact half-space model's,
// scaled to the scene's element size, or the fast models'), for the table size check and the
// estimate (engine/table_size.hpp).
PointCost contact_point_cost(const Scene& scene);

// Builds the profiles and solver of the scene (throws railtab::Error for bad profiles/geometry).
// With normalised creep coordinates (format 2.1) the kernel brings the normalised xi, eta, phi
// axes and the root attribute creep_map (kernel/creep_map.hpp) to the sweep.
SweepKernel make_contact_kernel(const Scene& scene);
// The same with the scene's geometry solver made once by the caller (make_geometry_solver(scene)):
// for callers that build many one-state kernels of one scene (the error map), where making the
// solver costs about 3 times solving the state. `creep_coefficients` false: the normal part's
// creep_coefficient_* outputs stay 0 and are not computed (a caller that reads only forces, normal
// force, area and angle: the exact model's coefficients are six steady rolling solves in full
// adhesion per patch, most of an exact-model state's cost); a normalised scene's creep scales are
// still computed as in the table.
SweepKernel make_contact_kernel(const Scene& scene, const ContactGeometrySolver& geometry,
                                bool creep_coefficients = true);

}  // namespace railtab
