// SPDX-License-Identifier: Apache-2.0
// Reference point of a loaded contact patch from the rigid gap band: the wheel is pushed a rigid
// vertical approach delta_z beyond rigid contact, and each region of positive overlap gets one
// reference, placed and oriented the way CONTACT (Vollebregt) places its "contact reference
// point" before it solves the elastic problem. Use it to compare with CONTACT's ycp/r_roll/contact
// angle, or as the patch origin of a normal-contact model. Frames: docs/conventions.md.
//
// What CONTACT does (open-source CONTACT, src/m_wr_locatecp.f90; read, not copied):
//  - locate_interpen_1d samples the VERTICAL gap between rail profile and wheel on a grid uniform
//    in track y (about 0.3 DS). Every contiguous region of negative gap around a local minimum is
//    one candidate patch; its ends are the linearly interpolated zero crossings.
//  - compute_wgt_center_1d gives each lateral grid point y the weight integral over x of
//    pen(x)^2 (default, gapwgt = 0) or of pen(x) (gapwgt = 1), where along the rolling direction
//    pen(x) = p(y) - x^2 / (2 R_nom): the vertical interpenetration p at y, reduced by the wheel's
//    circumference with the NOMINAL radius (the same quadratic that compute_contact_length_1d
//    uses for the patch length). Done analytically this is
//        squared: (16/15) sqrt(2 R_nom) p^(5/2),   linear: (4/3) sqrt(2 R_nom) p^(3/2),
//    i.e. not the depth alone but the depth (squared) integrated over the local contact length
//    2 sqrt(2 R_nom p). wgt_ygap (lateral position) and wgt_agap (contact angle: the rail
//    surface inclination at y) are the averages with these weights; totgap is their sum.
//  - set_cpatch_reference puts the reference on the rail profile at y = wgt_ygap and takes the
//    contact angle = wgt_agap (the weighted average, not the inclination at the reference).
//  - sort_cpatches_yvalue orders the patches from the field side to the track centre;
//    combine_cpatches then merges neighbours whose facing ends (inner end of the outer patch,
//    outer end of the inner one) lie within dist_sep (default 8 mm, distance in the y-z plane)
//    unless their angles differ by more than angl_sep (default pi, i.e. never): position and
//    angle become totgap-weighted averages, totgap adds up, the extents are united. Patches kept
//    apart at dist_sep..dist_turn (default 12 mm) get their angles blended towards the combined
//    angle by the fraction (dist_turn - dist)/(dist_turn - dist_sep) (turn_cpatch_refangle).
//  - CONTACT's r_roll is the wheel radius at the reference point, which lies on the RAIL surface,
//    i.e. the undeformed radius there minus the local (radial) overlap.
//
// Our band is uniform in rail arc length s and holds the NORMAL gap. With d(s) = delta_z cos(g) -
// gap (normal overlap, docs/conventions.md) the vertical interpenetration is p = d / cos(g) and
// dy = cos(g) ds (both exact for locally parallel surfaces, which the thin overlap sliver is to
// second order), so the weight per unit s is w(p) cos(g). Positions are interpolated between band
// samples; at a zero crossing the partial cell is integrated as p^e with p linear (exact there).
#pragma once

#include <vector>

#include "geometry/contact_geometry.hpp"

namespace railtab {

enum class OverlapWeighting {
  squared,  // integral of overlap^2 along x: CONTACT's default (gapwgt = 0)
  linear,   // integral of overlap along x (CONTACT gapwgt = 1)
};

struct OverlapOptions {
  OverlapWeighting weighting = OverlapWeighting::squared;
  double nominal_radius = 0.460;  // wheel radius of the x-integration of the weight [m]
  // Patch combination (CONTACT's combine_cpatches / turn_cpatch_refangle). The default keeps one
  // reference per overlap run; contact_patch_rules() gives CONTACT's defaults.
  double combine_distance = 0.0;  // merge neighbouring runs whose facing ends are closer [m]
  double separate_angle = 3.14159265358979323846;  // ...unless their angles differ more [rad]
  double turn_distance = 0.0;     // blend angles of runs kept apart up to this distance [m]
};

// CONTACT's defaults: combine within 8 mm, never separate by angle, blend angles up to 12 mm.
OverlapOptions contact_patch_rules();

// One loaded-patch reference. Positions refer to the rail point at the reference lateral position
// and to the band's facing wheel point there (taken at rigid contact).
struct OverlapReference {
  double band_s;                 // arc length of the reference in the wheel's band [m]
  double rail_u;                 // rail-profile coordinate of the reference [m]
  double wheel_u;                // wheel-profile coordinate of the facing wheel point [m]
  double q;                      // rail point, side frame lateral (weighted average) [m]
  double z;                      // rail point, side frame vertical [m]
  double y_track;                // rail point, track frame lateral [m]
  double contact_angle_side;     // weighted average of the band's angle, side frame [rad]
  double contact_angle;          // same, track frame ISO sign (sigma * side) [rad]
  double rolling_radius;         // undeformed wheel radius at the facing wheel point [m]
  double loaded_rolling_radius;  // radial distance axle -> rail point at the approach (CONTACT's
                                 // r_roll): rolling_radius minus the local radial overlap [m]
  double overlap;                // local normal overlap d at the reference (< 0 possible after
                                 // combining runs) [m]
  double max_overlap;            // largest normal overlap in the patch [m]
  double total_weight;           // integral of the weight over the patch ([m^4] squared,
                                 // [m^3] linear); CONTACT's totgap = this / its y step [m^3|m^2]
  double s_start;                // patch extent in band s: zero crossing or band end [m]
  double s_end;                  // [m]
  int runs;                      // overlap runs merged into this reference (1 unless combined)
  bool clipped;                  // a run reaches the end of the band (extent unreliable)
};

// References of all overlap runs of one wheel at rigid vertical approach delta_z >= 0 [m] (wheel
// moved down by delta_z from rigid contact), in ascending band s. Empty when nothing overlaps
// (delta_z <= 0 or no band). Throws railtab::Error when delta_z is not finite.
std::vector<OverlapReference> overlap_references(const WheelContactGeometry& geometry,
                                                 double vertical_approach,
                                                 const OverlapOptions& options = {});

}  // namespace railtab
