// SPDX-License-Identifier: Apache-2.0
// The exact half-space model (src/halfspace/wheel_rail.hpp) in the shapes the rest of the generator
// consumes: its patches become ContactPatch (model halfspace, no strips, semi-axes 0) in a
// WheelNormalResult, its tangential solution a FastsimResult and its element wear a WearResult, so
// slots, tables, eval and the simulation treat it like every other normal model. One conversion,
// used by eval, the table sweep and the direct contact model.
#pragma once

#include <functional>
#include <vector>

#include "halfspace/wheel_rail.hpp"
#include "normal/normal_model.hpp"
#include "scene/scene.hpp"
#include "tangential/fastsim.hpp"
#include "wear/archard.hpp"

namespace railtab {

// The scene's half-space settings ([contact] element_size).
halfspace::HalfspaceOptions halfspace_options(const Scene& scene);

// One per thread (halfspace::Workspace is not thread-safe; it caches FFT plans and kernel spectra).
halfspace::Workspace& thread_halfspace_workspace();

// Normal part. Patch i of the result is patch i of `result` (same order, ascending band_s).
// area: CONTACT's element count (halfspace::NormalSolution::area); penetration: the normal approach
// of the patch plane; s_start/s_end: lateral extent of the elements in contact mapped to band s.
// point_patch: a geometric point belongs to the patch whose contact extent contains its band_s
// (-1: none). Status: the patch flags (kAreaTooSmall, kNotPlanar, kConverged/kNotConverged, ...);
// the wheel's adds kTwoPoint for several patches, as the normal layer.
WheelNormalResult to_normal_result(const halfspace::WheelHalfspaceResult& result,
                                   const WheelContactGeometry& geometry);

// Creep forces of one patch after a tangential solve (forces on the wheel, contact frame; mz about
// the patch reference). slip_fraction = slip area / contact area; kFullSlip when every element in
// contact slips. An unloaded patch: zeros with kConverged | kLiftOff.
FastsimResult to_creep_result(const halfspace::HalfspacePatch& patch);

// Archard wear (KTH map) per element of the exact slip and traction, in the units of archard_wear:
// volume_rate = worn cross-section per pass [m3/m], wear_rate = that over the circumference
// 2 pi r (r the patch's rolling radius) [m2/m], max_depth_rate the largest radial depth of a
// lateral column of elements per metre rolled (normal depth / cos(contact angle), as archard_wear
// does for a single strip), seizure_fraction the share of the volume from seizure elements.
WearResult halfspace_wear(const halfspace::HalfspacePatch& patch, double speed, const WearOptions& options,
                          std::vector<double>& element_depth);

// halfspace::solve_halfspace_rolling with its own creepage per patch (the simulation gives each
// slot its own): the same coupled load control (F_z = sum N cos g + fy sin g, secant on the
// tangential vertical part, at most 20 rounds, kNotConverged beyond 1e-4 F_z), built on the public
// calls; each patch's tangential problem is solved alone at creepage_of(patch index, patch).
// With `couple` false: the normal contact from the load alone, then the tangential problems.
using HalfspacePatchCreepage = std::function<Creepage(std::size_t, const halfspace::HalfspacePatch&)>;
halfspace::WheelHalfspaceResult solve_halfspace_rolling_per_patch(
    const WheelContactGeometry& geometry, double load, const HalfspacePatchCreepage& creepage_of, double mu,
    const Material& material, const halfspace::HalfspaceOptions& options, bool couple,
    halfspace::Workspace& workspace);

// The tangential problem of every patch of `result` at its own creepage (warm start from the
// tractions the patches hold).
void solve_halfspace_tangential_per_patch(halfspace::WheelHalfspaceResult& result, const HalfspacePatchCreepage& creepage_of,
                                          double mu, const Material& material,
                                          const halfspace::HalfspaceOptions& options, halfspace::Workspace& workspace);

}  // namespace railtab
