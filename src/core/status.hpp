// SPDX-License-Identifier: Apache-2.0
// Status flags carried by every result and every table point. Numerical trouble is data:
// a result is always returned, and these bits say how far to trust it.
#pragma once

#include <cstdint>
#include <string>

namespace railtab {

using StatusBits = std::uint32_t;

namespace status {
inline constexpr StatusBits kConverged = 1u << 0;         // the solver met its tolerance
inline constexpr StatusBits kNotConverged = 1u << 1;      // iteration limit hit; best estimate kept
inline constexpr StatusBits kTwoPoint = 1u << 2;          // more than one contact on this wheel
inline constexpr StatusBits kLiftOff = 1u << 3;           // no contact at this load/approach
inline constexpr StatusBits kCurvatureClipped = 1u << 4;  // negative/small B clipped (+ smoothing)
inline constexpr StatusBits kCurvatureShifted = 1u << 5;  // negative/small B shifted upward
inline constexpr StatusBits kFallbackModel = 1u << 6;     // the chosen model failed; a simpler one ran
inline constexpr StatusBits kFlangeContact = 1u << 7;     // contact angle beyond the tread range
inline constexpr StatusBits kNonHertzian = 1u << 8;       // A or B <= 0 at the point: Hertz invalid
inline constexpr StatusBits kFullSlip = 1u << 9;          // tangential force saturated at mu*N
inline constexpr StatusBits kOutOfRange = 1u << 10;       // query clamped to the table edge
inline constexpr StatusBits kInvalidInput = 1u << 11;     // NaN/inf or otherwise unusable input
inline constexpr StatusBits kProfileEdge = 1u << 12;      // contact band reached a profile end
inline constexpr StatusBits kFailed = 1u << 13;           // the core threw here: outputs are zero
// Half-space model (src/halfspace).
inline constexpr StatusBits kAreaTooSmall = 1u << 14;     // contact reaches the potential area's edge
inline constexpr StatusBits kNotPlanar = 1u << 15;        // contact angle varies across the patch
                                                          //   beyond the planar limit
// Geometry (src/geometry): the wheel has two rigid contact points at least
// GeometrySettings::near_equal_distance apart whose separations differ by less than
// near_equal_gap, e.g. the two minima of a hollow-worn tread: the primary point (and its radius
// and angle) may jump between them from one lateral position to the next.
inline constexpr StatusBits kNearEqualMinima = 1u << 16;
// Geometry: a lateral curvature step of the wheel or rail profile (a radius transition, e.g.
// UIC60's R300/R80 at |u| = 10.5 mm) lies within one band step of the rigid point. The point's
// B, and every model answer that depends on it (Hertz; Linder's load closure; STRIPES' virtual
// penetration and curvature treatment), steps where the point crosses it: the models' constant-
// curvature assumption at the point fails there. Set on the point and on the wheel.
inline constexpr StatusBits kCurvatureStep = 1u << 17;
// Table lookup only (never set by the core): the query's interpolation cell spans a change the
// table does not resolve, so the interpolated value may be far from the model's (the criteria:
// docs/lookup.md, "Low confidence"). Set by railtab::lookup at load, per cell and slot.
inline constexpr StatusBits kLowConfidence = 1u << 18;

// Comma-separated names of the set bits, e.g. "converged,two_point"; "none" for 0.
std::string describe(StatusBits bits);
}  // namespace status

}  // namespace railtab
