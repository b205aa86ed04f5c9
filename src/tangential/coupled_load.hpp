// SPDX-License-Identifier: Apache-2.0
// Load control in track axes with the creep forces in the balance (load coupling): the vertical
// wheel load is carried by the normal force AND by the vertical component of the tangential force,
// so the approach is found such that
//     sum over patches ( N_p cos g_p + fy_p sin g_p ) = Q
// (forces on the wheel, track z up, g_p the patch's contact angle in the track frame, fy_p the
// creep force along s = (0, cos g, sin g); docs/conventions.md "Load control in track axes"),
// the creep forces being computed at that approach. In flange contact (|g| ~ 1.2 rad) this changes
// the normal force by tens of per cent; on the tread by well under one per cent.
//
// Method: secant on the vertical approach, in the variable V^(2/3) (V the total vertical force,
// nearly linear in the approach), starting from the uncoupled solution (which the caller usually
// has already: a table shares it between all creepages of a load) and a second point at the normal
// load the balance needs if the creep share scales with N, its approach scaled as Hertz would
// (N ~ delta^(3/2)); a bracket is kept once the residual changes sign. Every
// iteration is one normal solve at a given approach plus one tangential solve per patch.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "core/material.hpp"
#include "core/status.hpp"
#include "normal/normal_model.hpp"
#include "tangential/fastsim.hpp"
#include "tangential/fastsim_contact.hpp"

namespace railtab {

struct CoupledLoadOptions {
  bool couple = true;        // false: the normal problem from the vertical load alone (without
                             //   the load coupling); the creep forces are still computed on it
  double tolerance = 1e-4;   // relative tolerance on the vertical balance [-]: 8 N at 78.5 kN, far
                             //   below FASTSIM's own error against CONTACT (per cent); each tenfold
                             //   tightening costs about one more normal + FASTSIM solve per point
  int max_iterations = 30;   // normal solves beyond the uncoupled start [-]
};

// The tangential forces of every patch of a normal result, per patch (fx, fy on the wheel in the
// patch's contact frame). FASTSIM: fastsim_tangential below. The hook for other tangential models
// (the exact half-space model): any function that fills one FastsimResult per patch.
using TangentialSolver =
    std::function<void(const WheelNormalResult& normal, std::vector<FastsimResult>& per_patch)>;

// The creepage of patch `index` of a normal result (one creepage for all patches, or per slot).
using PatchCreepage = std::function<Creepage(std::size_t index, const ContactPatch& patch)>;

// FASTSIM (fastsim_contact) on every loaded patch at its creepage.
TangentialSolver fastsim_tangential(const WheelContactGeometry& geometry, PatchCreepage creepage,
                                    const CreepConditions& conditions, const Material& material,
                                    const FastsimOptions& options, FastsimWorkspace& workspace);

struct CoupledLoadResult {
  WheelNormalResult normal;          // normal contact at the coupled approach
  std::vector<FastsimResult> creep;  // per patch of normal.patches, at that approach
  double normal_vertical = 0.0;      // sum N cos g [N]
  double tangential_vertical = 0.0;  // sum fy sin g [N]: the load share of the creep forces
  int iterations = 0;                // normal solves beyond the uncoupled start [-]
  StatusBits status = 0;             // kConverged or kNotConverged (the coupling's verdict; the
                                     //   normal solver's bits stay in normal.status)
};

// sum over patches of fy sin g (the vertical component of the creep forces on the wheel) [N].
double tangential_vertical_force(const WheelNormalResult& normal,
                                 const std::vector<FastsimResult>& creep);

// Coupled load control. `uncoupled` is solve_normal_for_load(geometry, load, ...) (the
// start, reused by tables across creepages). With options.couple false the result is `uncoupled`
// with its creep forces. Lift-off or a vertical load <= 0: the uncoupled result, kConverged.
// When the balance has no solution within the iteration limit (e.g. mu tan g >= 1 on a flange
// flank, Nadal's limit) the best iterate is kept with kNotConverged.
void solve_coupled_load(const WheelContactGeometry& geometry, double load,
                        const WheelNormalResult& uncoupled, const Material& material,
                        const NormalOptions& normal_options, const TangentialSolver& tangential,
                        const CoupledLoadOptions& options, CoupledLoadResult& out);

}  // namespace railtab
