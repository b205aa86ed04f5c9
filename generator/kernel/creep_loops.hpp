// SPDX-License-Identifier: Apache-2.0
// The contact kernel's creep and wear loops: one wheel, one load node, every creepage of the grid,
// written into the column's creep and wear cells (and, with the load coupling, the creep part's
// normal outputs). Internal to the sweep (contact_kernel.cpp calls them).
#pragma once

#include <cstddef>
#include <vector>

#include "halfspace/wheel_rail.hpp"
#include "kernel/kernel_cells.hpp"

namespace railtab::kernel {

// FASTSIM on one slot's loaded patches, the load's creepage-free normal contact (no coupling).
// `scales`: the slots' creepage scales with normalised coordinates, else nullptr.
void solve_creep(const KernelData& k, const WheelContactGeometry& geometry, const WheelNormalResult& normal,
                 const PatchSlots& slots, const ColumnState& state, std::size_t wheel, std::size_t il,
                 std::size_t slot, const creep_map::Scales* scales, ColumnOutput& out);

// With the load coupling: per creepage the normal contact is re-solved so that normal
// and creep forces together carry the load, starting from `uncoupled`; both slots' cells.
void solve_creep_coupled(const KernelData& k, const WheelContactGeometry& geometry,
                         const WheelNormalResult& uncoupled, const PatchSlots& uncoupled_slots,
                         const ColumnState& state, std::size_t wheel, std::size_t il,
                         const creep_map::Scales* scales, ColumnOutput& out);

// The order in which the exact model's creepages are solved, each warm-started from the one
// before: node indices (ix * neta + ie) * nphi + ip of the creep grid in a snake (boustrophedon)
// order, so that consecutive nodes differ in one creepage by one grid step.
std::vector<std::size_t> creepage_chain(std::size_t nxi, std::size_t neta, std::size_t nphi);

// The exact half-space model's steady rolling solution per creepage; `scales` as for solve_creep.
void solve_creep_halfspace(const KernelData& k, const WheelContactGeometry& geometry,
                           const halfspace::WheelHalfspaceResult& uncoupled, const PatchSlots& uncoupled_slots,
                           const ColumnState& state, std::size_t wheel, std::size_t il,
                           const creep_map::Scales* scales, ColumnOutput& out);

}  // namespace railtab::kernel
