// SPDX-License-Identifier: Apache-2.0
// The exact half-space model on a wheel-rail contact: one planar patch per loaded region, as
// CONTACT's wheel-rail module does by default, built from the same data as the fast models.
//
// Patches: the normal layer (normal_model.hpp, STRIPES A&B with CONTACT's patch combination,
// runs within 8 mm merged) finds the loaded overlap runs, their overlap reference (position and
// interpenetration-weighted contact angle g_ref, as CONTACT places its reference) and a first
// vertical approach. Each patch is then solved on its own grid in the tangent plane at the
// reference point (x rolling, y = contact frame lateral, origin at the reference point).
// Reference points: CONTACT places them from the rigid interpenetration at the approach it solves
// for; the first approach is STRIPES's, which in flange contact lies far from the exact one (dy =
// 7 mm of ../shared block C at 166 kN: 0.96 against 0.72 mm, g_ref 62.5 against 66.1 degrees, and
// with it N 360 against 410 kN). So the references are placed again from the overlap runs at the
// exact vertical approach until the two approaches agree within `reference_tolerance` (a secant on
// their difference; it keeps the last placement where the runs change in between):
//  - lateral coordinate of band sample s: y = (P(s) - P_ref) . t_ref, t_ref the tangent of the
//    reference plane towards the field side: y points towards the field side on both wheels,
//    so the right wheel's patch is the left wheel's mirror image, one discrete problem for both
//    (the mirror of docs/conventions.md holds to the last bit). On the left wheel y is the
//    contact frame's s axis (docs/conventions.md); on the right wheel -s, and its lateral and
//    spin creepages, fy and mz change sign between the patch and the contact frame (track_sign);
//  - undeformed gap along the reference normal: h(x, y) = gap(s) / cos(g(s) - g_ref)
//    + A(s) x^2, A(s) = cos(g(s) - wheel_roll) / (2 r(s)) (the wheel's rolling-direction
//    curvature, Meusnier), interpolated linearly between band samples;
//  - normal approach of the plane: delta_z cos(g_ref) for the vertical approach delta_z.
//  - with yaw (WheelContactGeometry::wheel_yaw != 0) the patch sits at the longitudinal position
//    of its reference (x_track: the wheel's rigid shift plus its lead) and each strip's gap is
//    smallest on the wheel's silhouette, x(s) = x_track(s) - x_track(ref), curved along x by
//    Euler's k_x: h(x, y) = gap(s) / cos(g(s) - g_ref) + k_x(s)/2 (x - x(s))^2 (a sheared
//    patch in flange contact, where the lead changes fast across the patch; docs/conventions.md
//    "Yaw"). Creepages of the yawed kinematics: wheelset_kinematics.hpp.
// Potential area: the rigid overlap of the patch at the first approach (h < delta_n), widened by
// `margin` on every side, on square elements of `element_size` (default 0.3 mm: CONTACT's grid
// of block C, and the size at which the tread results are within 1 % of mu N of CONTACT; error and
// time against element size: docs/validation/halfspace.md).
// When the contact reaches the edge of the grid the area grows by half and the patch is solved
// again (up to `max_growth` times; then kAreaTooSmall stays set).
// Load control: one patch: N = F_z / cos(g_ref); several: one vertical approach for all, found by
// the secant method on sum N_k cos(g_k) = F_z.
// kNotPlanar: the contact angle varies by more than `planar_angle_limit` (default 0.2 rad,
// 11.5 deg) over the lateral extent of the contact: the planar half-space is strained (flange
// root, two-point contact merged into one patch).
#pragma once

#include <functional>
#include <limits>
#include <memory>
#include <vector>

#include "core/material.hpp"
#include "core/status.hpp"
#include "geometry/contact_geometry.hpp"
#include "halfspace/normal_solver.hpp"
#include "halfspace/tangential_solver.hpp"
#include "normal/normal_model.hpp"
#include "tangential/fastsim.hpp"
#include "wear/archard.hpp"

namespace railtab::halfspace {

struct HalfspaceOptions {
  double element_size = 0.3e-3;       // element length and width [m]
  double margin = 0.1;                // potential area beyond the rigid overlap, relative [-]
  int max_growth = 3;                 // enlargements when the contact reaches the edge [-]
  double planar_angle_limit = 0.2;    // contact-angle variation flagged kNotPlanar [rad]
  double load_tolerance = 1e-6;       // several patches: relative vertical-load tolerance [-]
  double reference_tolerance = 1e-4;  // references placed at the solved vertical approach to
                                      //   within this times it (top of this file; block C's
                                      //   forces within 0.001 % of mu N of those at 1e-5) [-]
  double loose_round_residual = 0.01; // warm coupled solve: a round after one whose load balance
                                      //   missed by more than this times F_z is loose too [-]
  double jump_bracket = 0.5;          // warm coupled solve: stop, not converged, when full rounds
                                      //   missing the balance on either side lie closer than this
                                      //   times the load tolerance in tz (0: never) [-]
  double warm_normal_tolerance = 1e-5;     // warm coupled solve: its full rounds' normal and
  double warm_tangential_tolerance = 1e-4; //   tangential solver tolerances, where looser than
                                           //   normal's and tangential's (solve_halfspace_rolling) [-]
  NormalSolverOptions normal;
  TangentialSolverOptions tangential;
};

// The sign of the patch's lateral axis y against the contact frame's s (wheel_rail.hpp, top): +1
// on the left wheel, -1 on the right. The patch's tractions and slips along y (traction_y,
// slip_y) are in its own axis; its creepages, fy and mz are converted by this sign.
inline double track_sign(Side side) { return side == Side::left ? 1.0 : -1.0; }

struct HalfspacePatch {
  double track_sign = 1.0;      // of the wheel the patch is on (track_sign(side))
  // Reference point (the overlap reference of the normal layer's patch).
  double band_s = 0.0;          // [m]
  double contact_angle = 0.0;   // track frame (ISO sign) [rad]
  double contact_angle_side = 0.0;  // side frame [rad]
  double rolling_radius = 0.0;  // undeformed wheel radius at the reference [m]
  double wheel_u = 0.0, rail_u = 0.0;  // [m]
  double x_track = 0.0;         // longitudinal position of the reference (grid origin), track x
                                // from the axle centre; 0 without yaw [m]
  double x_wheel = 0.0;         // its lead along the wheel's rolling direction (CONTACT's XCP(W)) [m]
  Grid grid;                    // potential contact area (origin = reference point)
  std::vector<double> gap;      // undeformed gap h per element [m]
  NormalSolution normal;        // pressure, normal force, area, approach
  TangentialSolution tangential;  // traction, slip, forces (after solve_patch_tangential)
  double contact_angle_spread = 0.0;  // max - min contact angle over the contact's extent [rad]
  StatusBits status = 0;
};

struct WheelHalfspaceResult {
  std::vector<HalfspacePatch> patches;  // ascending band_s, as the normal layer's
  double vertical_approach = 0.0;       // [m]
  double carried_load = 0.0;            // sum N_k cos(g_k) [N]
  StatusBits status = 0;                // union of the patch flags; kLiftOff when none
};

// The patches the exact model solves (the first step of solve_halfspace_for_load): the normal
// layer's STRIPES A&B with CONTACT's patch combination at `load`. The exact result has
// exactly these patches, in this order; their reference points (band_s, contact_angle,
// rolling_radius, wheel_u, rail_u) are these placed again at the exact approach (top of this
// file: in flange contact some degrees steeper, on the tread up to 0.1 degree); with one
// patch its normal force is the load's share F_z / cos(g) > 0, so the patch configuration of a
// one-patch state is known without the exact solve (the contact-jump locator uses this).
WheelNormalResult candidate_patches(const WheelContactGeometry& geometry, double load,
                                    const Material& material);

// Normal problem for a prescribed vertical wheel load [N].
WheelHalfspaceResult solve_halfspace_for_load(const WheelContactGeometry& geometry,
                                              double load, const Material& material,
                                              const HalfspaceOptions& options,
                                              Workspace& workspace);

// Steady rolling on every patch with the creepages of each patch's reference point (contact
// frame, wheel minus rail, docs/conventions.md); mu >= 0. Warm-starts from the tractions held in
// the patches.
void solve_halfspace_tangential(WheelHalfspaceResult& result, const Creepage& creepage, double mu,
                                const Material& material, const HalfspaceOptions& options,
                                Workspace& workspace);

// Normal and tangential together, as CONTACT's wheel-rail module: the prescribed VERTICAL load is
// carried by the normal forces AND the vertical components of the lateral creep forces,
// F_z = sum_k (N_k cos g_k + fy_k sin g_k) (g_k the track-frame contact angle; s = (0, cos g,
// sin g) in track axes), which matters in flange contact (g about 1.1 rad: a lateral force of
// 0.3 N changes N by half). The normal load sum N_k cos g_k = F_z - sum fy_k sin g_k is found by
// the secant method on the tangential vertical part (at most 20 rounds; kNotConverged if not
// within 1e-4 F_z). Each round warm-starts the tangential solve from the previous one. A loose
// round, which only steers the secant, stops at looser solver tolerances (tangential 1e-3,
// normal 1e-4): the first (it only estimates fy sin g) and, in a warm solve (below), every round
// after one whose load balance missed by more than `loose_round_residual` F_z. In flange contact
// fy sin g is comparable to F_z: the first rounds miss by 5-90 kN at 78.5 kN, and 2-3 of the 4-5
// rounds are loose (the default creepage column in flange contact: 29 % less CPU, bench
// BM_CreepageColumnWarm/7; the tread's rounds miss by less than 1 % and stay as they were).
// The result is always a full round's. A warm solve also stops, not converged, where the balance
// jumps across its tolerance (`jump_bracket`, solve_load_fixed_point): 2 of the 105 solves of that
// flange column bounced on +-100 N of grid noise for all 20 rounds. A cold solve makes only its
// first round loose and runs all its rounds: it is railtab eval's and the error map's reference,
// and keeps its bits.
//
// Warm start along a creepage line (the table sweep): with `state`, a solve continues from the end
// of the previous solve of the same geometry and load at a neighbouring creepage, if `state` holds
// one: the fixed point starts from the load split of that solve's last normal problem, whose grid
// and pressure it keeps, so the first round's normal problem is already solved and the later ones
// start from a near pressure (the grids kept or placed again by the rules of the later rounds of a
// cold solve; on a kept grid extrapolated linearly in the load from that grid's last two pressures,
// RollingState::earlier: the tread column of BM_CreepageColumnWarm/0 takes 30 % fewer normal
// iterations); the tangential problem starts from zero traction and the first round runs at the
// looser tolerances, as in a cold solve. Where a later round places a grid again, its pressure and
// tractions start from the previous round's at the same coordinates (from the reference point),
// also when the grid's size changed (a cold solve then restarts them: flange contact, where the
// grid is placed again each round; the flange column of BM_CreepageColumnWarm/7: median of 3,
// 3260 -> 2947 ms CPU). The result is the same fixed point to within the
// tolerances (1e-4 F_z on the load balance, the solvers' own), not the same bytes as a cold solve;
// it depends only on the chain of creepages, so a fixed order gives fixed bytes. Its full rounds stop
// at `warm_normal_tolerance` and `warm_tangential_tolerance` (1e-5 and 1e-4, where a cold solve
// uses 1e-9 and 1e-7): a table's nodes need their forces to within its interpolation error (0.2 to
// 1.5 % of mu N), and the coupled balance's own tolerance already moves them by up to 2e-4 F_z mu.
// On a tread and a flange column of tables/default.toml (y = 2 and 7 mm, 78.5 kN, 245
// creepages) these tolerances moved the stored F / (mu N) by at most 7e-5 and no status; the
// column's CPU fell by 27-39 % (docs/validation/exact-tables.md, "Generation cost"). On return `state`
// holds this solve's end (cleared when it did not converge). An empty `state` (or a null pointer)
// solves from cold.
struct PlaneSamples;  // the band samples of each patch in its plane (wheel_rail.cpp)
// A single patch's pressure on a kept grid at an earlier load: with the current one, a later
// round's start is extrapolated linearly in the load (wheel_rail.cpp, resolve_on_kept_grid).
struct EarlierPressure {
  std::vector<double> pressure;  // per element; empty: none [Pa]
  double load = 0.0;             // the vertical load it carried [N]
};
struct RollingState {
  WheelHalfspaceResult result;                  // the last solve (no patches: none yet)
  std::shared_ptr<const PlaneSamples> samples;  // its patches' band samples
  EarlierPressure earlier;                      // its grid's pressure before its last load change
  void clear() { *this = RollingState{}; }
};
WheelHalfspaceResult solve_halfspace_rolling(const WheelContactGeometry& geometry,
                                             double load, const Creepage& creepage,
                                             double mu, const Material& material,
                                             const HalfspaceOptions& options,
                                             Workspace& workspace, RollingState* state = nullptr);

// The vertical-load fixed point of solve_halfspace_rolling, for callers that solve their own rounds
// (the generator's per-patch creepages): `round(tz, loose)` solves the normal problem for F_z - tz
// and the tangential problems on top, and returns the new tangential vertical part sum fy sin g;
// `loose`: this round only steers the iteration and may stop at looser solver tolerances. The fixed
// point tz = round(tz) is found by the secant method from tz = 0 (at most 20 rounds; converged
// within 1e-4 F_z, on a round that was not loose). The first round is always made, loose;
// `stop_after_first()`, asked after it, ends the iteration there (an uncoupled solve, or no
// patch), which counts as converged. Later rounds are loose when the round before missed the
// balance by more than `loose_above` F_z. Returns false when the rounds ran out, or (jump_width
// > 0) when the balance jumps across the tolerance: the latest full rounds that missed it high and
// low lie closer than `jump_width` times the tolerance (1e-4 F_z) in tz, which a continuous
// balance would not allow (wheel_rail.cpp); the caller marks its result with mark_not_converged.
// `start`: the first tz (a warm start's guess).
bool solve_load_fixed_point(double load, const std::function<double(double, bool)>& round,
                            const std::function<bool()>& stop_after_first, double start = 0.0,
                            double loose_above = std::numeric_limits<double>::infinity(),
                            double jump_width = 0.0);

// kNotConverged instead of kConverged on the result and each of its patches.
void mark_not_converged(WheelHalfspaceResult& result);

// Archard wear with the KTH map per element of one solved patch: depth per pass removed from the
// wheel material crossing each element, k(p, V|s|) p |s| dx / H [m] (elements in slip only);
// returns the worn cross-section per pass, sum of depth * dy [m2].
double archard_wear_per_pass(const HalfspacePatch& patch, double speed, const WearOptions& wear,
                             std::vector<double>& element_depth);

}  // namespace railtab::halfspace
