// SPDX-License-Identifier: Apache-2.0
// Normal contact: one interface for Hertz, Linder, Kik-Piotrowski and STRIPES (A- and
// A&B-correction). A model takes the rigid geometry of one wheel (contact points and the gap band
// along the rail surface) and either the vertical wheel load or the vertical approach, and returns
// the loaded contact patches, discretised into lateral strips.
//
// Load: every geometric contact point carries a contribution evaluated by the model at that point
// (its curvatures, its separation). All contributions of one wheel share one rigid vertical
// approach delta_z: a point with vertical separation h and contact angle gamma sees the normal
// penetration (delta_z - h) cos(gamma), so the load splits between tread and flange by the physics.
// Hertz and Linder, whose closure is per point, weight the contributions of points that share one
// run of rigid overlap by their prominence above the saddle between them (run weights,
// normal_internal.hpp): separate wells count fully, a shallow ripple or a vanishing minimum of the
// gap hardly at all, continuously in the approach and in the geometry.
//
// Patches (what the result reports): a patch is one run of positive RIGID overlap
// d(s) = delta_z cos g(s) - gap(s) along the gap band at the solved approach, as CONTACT's contact
// search sees it (geometry/overlap_reference.hpp). The contributions of all points that lie in the
// same run are merged into one patch (forces and areas add, strips are united): two rigid minima
// inside one continuous overlap region give ONE patch; physically separate tread and flange
// contacts (separate runs) stay separate patches. With NormalOptions::combine_patches CONTACT's
// combination rule (contact_patch_rules(): runs within 8 mm merged) is applied on top.
// The reference point of a patch (band_s, contact_angle, rolling_radius, wheel_u, rail_u) is the
// run's overlap reference (interpenetration^2-weighted centre and angle; the same numbers as
// overlap_references with default options). Exception, Hertz: a Hertz patch of ONE point is the
// ellipse centred at its rigid contact point and its forces act there, so its reference is the
// contact point itself (band_s, contact_angle, rolling_radius, wheel_u, rail_u of the point; FASTSIM
// is placed at the ellipse centre) and s_start/s_end are the ellipse's lateral extent band_s -+ b
// (kProfileEdge only when the ellipse leaves the band). A Hertz patch of several ellipses in one
// overlap run is referred to their centre of force (force-weighted band_s, angle, radius, u's) and
// spans their union; with combine_patches it keeps CONTACT's combined reference.
// Patches are ordered by band_s ascending (band s grows
// towards the field side: a flange patch comes before a tread patch). Only loaded patches are
// listed.
// Pairing with the geometry: WheelNormalResult::point_patch[i] is the index of the patch that
// contains geometry.points[i] (-1: that point carries no load); several points may share a patch.
// ContactPatch::point_index is the point with the smallest separation inside the patch.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/material.hpp"
#include "core/status.hpp"
#include "geometry/contact_geometry.hpp"

namespace railtab {

// halfspace: Kalker's exact theory on elastic half-spaces (src/halfspace/wheel_rail.hpp). It is a
// choice of the same scene key and CLI option, but this layer does not solve it: the callers
// dispatch on it before solve_normal_for_load, which refuses it (railtab::Error).
enum class NormalModel { hertz, linder, kik_piotrowski, stripes_a, stripes_ab, halfspace };
const char* to_string(NormalModel model);                 // "hertz", "kik-piotrowski", "stripes-ab", ...
NormalModel parse_normal_model(std::string_view name);   // throws railtab::Error naming the value

// How STRIPES treats negative or very small lateral relative curvature B.
enum class NegativeCurvature {
  clip_and_smooth,  // classic STRIPES: replace by a small positive value, then smooth across strips
  shift,            // Sichani et al. 2014: shift the B distribution of the patch upward, no smoothing
};
const char* to_string(NegativeCurvature treatment);

// How STRIPES fixes the pressure amplitude for a given approach (stripes.cpp).
enum class StripesClosure {
  boussinesq,  // contact condition at the reference point: the Boussinesq displacement of the
               //   assumed (parabolic) strip pressures equals the true approach, times 32/(9 pi),
               //   the ratio that makes it exact for a Hertz ellipse (default)
  hertz_peak,  // p_max = 4/3 of the Hertz peak at the point (FACTS 2.4.5; first version), kept
               //   to reproduce the FACTS recipe and earlier tables
};
NegativeCurvature parse_negative_curvature(std::string_view name);

// Pressure shape along a strip (rolling direction x).
enum class StripPressure {
  semi_elliptic,  // p(x) = p_peak * sqrt(1 - x^2/a^2): Hertz, Kik-Piotrowski, Linder
  parabolic,      // p(x) = p_peak * (1 - x^2/a^2): STRIPES (Kalker's simplified theory)
};

struct NormalOptions {
  NormalModel model = NormalModel::stripes_ab;
  NegativeCurvature negative_curvature = NegativeCurvature::shift;
  int strips = 50;                        // lateral strips across each patch [-]
  double virtual_penetration = 0.55;      // epsilon of Linder and Kik-Piotrowski [-]
  double tolerance = 1e-8;                // relative tolerance on the normal load [-]
  int max_iterations = 60;                // load-control iteration limit [-]
  // Negative/small-B treatment of STRIPES (FACTS 2.4.6; Sichani et al. 2014 leaves the constants open):
  double min_curvature_ratio = 0.02;      // B floor as a fraction of A at the point [-]
  double curvature_window = 0.1e-3;       // band samples with rigid gap up to this much above the
                                          //   point's gap count for the treatment (about twice the
                                          //   virtual penetration at 150 kN) [m]
  double smoothing_half_width = 0.5e-3;   // clip_and_smooth: moving-average half-width [m]
  StripesClosure stripes_closure = StripesClosure::boussinesq;
  // Patch grouping: also merge separate overlap runs by CONTACT's rule (contact_patch_rules():
  // facing ends within 8 mm). Off by default: tread and flange contacts stay separate patches.
  bool combine_patches = false;
  // Hertz: fill ContactPatch::strips (the semi-ellipsoid cut into `strips` lateral strips). Off by
  // default: a Hertz patch is fully described by semi_axis_a/b, normal_force and max_pressure, and
  // the tangential layer solves it with fastsim_ellipse. Needed only for fastsim_patch on Hertz.
  bool hertz_strips = false;
};

// One lateral strip of a contact patch. x is the rolling direction (forward), the strip spans
// [x_trail, x_lead] at its centre.
struct Strip {
  double s;                // band arc length of the strip centre [m]
  double width;            // strip width along the rail surface [m]
  double wheel_u;          // wheel-profile coordinate of the strip centre [m]
  double rail_u;           // rail-profile coordinate of the strip centre [m]
  double contact_angle;    // local contact angle, track frame (ISO sign) [rad]
  double rolling_radius;   // wheel radius at the strip centre [m]
  double x_lead;           // leading edge (+x) [m]
  double x_trail;          // trailing edge [m]
  double pressure_peak;    // peak pressure on the strip (at x = (x_lead + x_trail)/2) [Pa]
  double ellipse_a;        // semi-axes of the strip's local (virtual) ellipse, for FASTSIM [m]
  double ellipse_b;        //   rolling (a) and lateral (b) [m]
};

struct ContactPatch {
  int point_index = -1;            // geometric point with the smallest separation inside the patch
                                   //   (index into WheelContactGeometry::points; -1: none)
  int points = 0;                  // geometric points whose load contributions form this patch
  NormalModel model = NormalModel::hertz;
  StripPressure pressure_shape = StripPressure::semi_elliptic;
  std::vector<Strip> strips;       // ascending s; empty for Hertz unless NormalOptions::hertz_strips
  double normal_force = 0.0;       // along the contact normal [N]
  double penetration = 0.0;        // normal approach (delta_z - h) cos(gamma) of point_index [m]
  double area = 0.0;               // [m2]
  double max_pressure = 0.0;       // [Pa]
  double semi_axis_a = 0.0;        // rolling semi-axis [m]: Hertz ellipse; KP equivalent ellipse
                                   //   (area and length/width kept); Linder max half-length; STRIPES 0
  double semi_axis_b = 0.0;        //   lateral semi-axis [m]: Hertz; KP equivalent; Linder half-width
  // Reference point: the overlap reference of the run (see the top of this file; Hertz of one
  // point: the contact point, s_start/s_end the ellipse's lateral extent); a contribution
  // whose point lies in no sampled overlap run (below the band resolution, or no band) keeps its
  // geometric point as reference.
  double band_s = 0.0;             // reference point, band arc length [m] (FASTSIM's placement)
  double contact_angle = 0.0;      // reference point, track frame (weighted, as CONTACT) [rad]
  double rolling_radius = 0.0;     // reference point, undeformed wheel radius [m]
  double wheel_u = 0.0;            // reference point, wheel profile [m]
  double rail_u = 0.0;             // reference point, rail profile [m]
  double s_start = 0.0;            // extent of the rigid overlap run in band s (Hertz of one
                                   //   point: of the ellipse) [m]
  double s_end = 0.0;              // [m]
  StatusBits status = 0;
};

struct WheelNormalResult {
  std::vector<ContactPatch> patches;  // loaded patches (overlap runs), ascending band_s
  std::vector<int> point_patch;       // per geometry point: index into patches, -1 when unloaded
  double vertical_approach = 0.0;     // rigid vertical approach of the wheel [m]
  double carried_load = 0.0;          // sum of patch normal forces projected on track z [N]
  int iterations = 0;                 // load-control iterations
  StatusBits status = 0;              // union of the patch flags plus solver flags; kTwoPoint
                                      //   when more than one patch is loaded, kLiftOff when none
};

// Load control: the vertical wheel load (track z) is prescribed [N].
WheelNormalResult solve_normal_for_load(const WheelContactGeometry& geometry, double load,
                                        const Material& material, const NormalOptions& options);

// The same, writing into `out` and reusing the capacity of its vectors (table sweeps: no
// allocation per solve on the Hertz fast path). Same numbers as the overload above.
void solve_normal_for_load(const WheelContactGeometry& geometry, double load,
                           const Material& material, const NormalOptions& options,
                           WheelNormalResult& out);

// Displacement control: the rigid vertical approach of the wheel is prescribed [m].
WheelNormalResult solve_normal_for_approach(const WheelContactGeometry& geometry,
                                            double vertical_approach, const Material& material,
                                            const NormalOptions& options);

// The same, writing into `out` and reusing the capacity of its vectors (the coupled load control,
// tangential/coupled_load.hpp, calls it once per iteration).
void solve_normal_for_approach(const WheelContactGeometry& geometry, double vertical_approach,
                               const Material& material, const NormalOptions& options,
                               WheelNormalResult& out);

}  // namespace railtab
