// SPDX-License-Identifier: Apache-2.0
// Rigid wheel-rail contact geometry of a wheelset on a track: contact points (tread and flange,
// two-point contact kept), contact angles, rolling radii, principal relative curvatures and the
// gap function along the rail surface around the contacts, which the normal-contact models use.
// Frames and signs: docs/conventions.md.
//
// Each wheel-rail pair is solved in its "side frame": q [m] lateral, positive outward (towards the
// field side of that rail), z [m] up, origin on the track centreline at top-of-rail height.
// For the left wheel q = y_track, for the right wheel q = -y_track; a wheelset shift y and roll
// phi appear in the side frame as (sigma*y, sigma*phi), sigma = +1 left, -1 right. The right wheel
// is thus the mirror image of the left one and one code path serves both.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "core/status.hpp"
#include "profile/curves/profile.hpp"

namespace railtab {

namespace detail {
class PlacedRail;
struct WheelSamples;
}  // namespace detail

enum class Side { left = 0, right = 1 };
inline constexpr double outward_sign(Side side) { return side == Side::left ? 1.0 : -1.0; }
const char* to_string(Side side);

struct TrackGeometry {
  double gauge = 1.435;                  // distance between the gauge points [m]
  double gauge_measuring_depth = 0.014;  // gauge measured this far below the top of rail [m]
  double rail_inclination = 1.0 / 40.0;  // tan of the rail cant; the head leans to the track centre [-]
};

struct WheelsetGeometry {
  double back_to_back = 1.360;           // distance between the flange backs (inner faces) [m]
  double flange_back_position = -0.070;  // inner face of the wheel in wheel-profile u [m]
  double nominal_radius = 0.460;         // rolling radius at wheel-profile u = 0 [m]
};

struct GeometrySettings {
  double search_step = 0.1e-3;         // sampling step of the rigid contact search [m]
  double max_separation = 0.5e-3;      // report secondary contacts up to this vertical gap [m]
  double band_step = 0.1e-3;           // arc-length step of the gap band [m]
  double band_half_width = 20e-3;      // band reaches this far beyond the outermost contacts [m]
  double band_max_gap = 2e-3;          // ...or stops where the normal gap exceeds this [m]
  double flange_angle = 0.35;          // contact angle above which a contact is "flange" [rad]
  // kNearEqualMinima: a second rigid point at least near_equal_distance from the primary one (on
  // the rail) would become the primary point within a lateral wheelset shift of near_equal_shift
  // (first order: its separation h closes at the rate |tan g_k - tan g_0| per metre of shift, so
  // the flag is h < near_equal_shift |tan g_k - tan g_0|). Twice the 0.05 mm step of the
  // stability sweeps: both samples around a jump of the primary point carry the flag.
  double near_equal_shift = 0.1e-3;    // [m]
  double near_equal_distance = 1e-3;   // [m]
};

struct WheelsetState {
  double y = 0.0;     // lateral displacement of the wheelset, track frame, + left [m]
  double roll = 0.0;  // roll angle relative to the track, right-hand about +x (left wheel up) [rad]
  double yaw = 0.0;   // yaw angle (angle of attack) relative to the track, right-hand about +z: +
                      // turns the wheelset's forward axis towards +y (left); orientation
                      // R_x(roll) R_z(yaw), roll about the track's x axis (as CONTACT); 0 is
                      // exactly the yaw-free geometry [rad]
};

// One sample of the gap band: a point on the rail surface and the wheel point facing it along
// the rail normal, with the wheel at rigid contact (zero approach).
struct BandSample {
  double s;                // rail arc length from the primary contact, + towards the field side [m]
  double rail_u;           // rail-profile coordinate of the rail point [m]
  double wheel_u;          // wheel-profile coordinate of the facing wheel point [m]
  double q;                // rail point, side frame lateral [m]
  double z;                // rail point, side frame vertical [m]
  double contact_angle_side;  // angle of the rail normal from vertical, side frame, + when the
                              // normal leans towards the track centre (flange side) [rad]
  double gap;              // distance rail -> wheel along the rail normal (>= 0 outside overlap) [m]
  double rolling_radius;   // wheel radius at the facing wheel point [m]
  double curvature_wheel;  // lateral curvature of the wheel surface, + convex (bulging to rail) [1/m]
  double curvature_rail;   // lateral curvature of the rail surface, + convex (crown) [1/m]
  double x_track;          // longitudinal position of the facing wheel point (the wheel's
                           // silhouette seen along the track), track x from the axle centre [m]
  double x_wheel;          // lead of that wheel point along the wheel's rolling direction, r sin(tau) [m]
  double curvature_rolling;  // normal curvature of the wheel along track x there, + convex:
                             // cos(angle - roll)/r without yaw, Euler's formula with yaw [1/m]
};

struct ContactPoint {
  double wheel_u;           // lateral position in wheel-profile coordinates [m]
  double rail_u;            // lateral position in rail-profile coordinates [m]
  double y_track;           // lateral position in the track frame [m]
  double z_track;           // vertical position in the track frame (rail at rigid contact) [m]
  double contact_angle;     // track frame, ISO sign: + for the left wheel's flange side [rad]
  double contact_angle_side;  // same angle in the side frame (+ towards the flange) [rad]
  double rolling_radius;    // wheel radius at the contact point [m]
  double separation;        // vertical gap still open at rigid contact of the wheel (0: touching) [m]
  double curvature_a;       // principal relative curvature, rolling direction, A [1/m]
  double curvature_b;       // principal relative curvature, lateral direction, B [1/m]
  double band_s;            // arc length of this point in the wheel's band [m]
  StatusBits status;        // kFlangeContact, kNonHertzian (A or B <= 0), kProfileEdge,
                            //   kNearEqualMinima (this point and the primary, see GeometrySettings)
  double wheel_t;           // wheel curve parameter (Profile::curve; = wheel_u for z(u) profiles) [m]
  double rail_t;            // rail curve parameter (= rail_u for z(u) profiles) [m]
  double x_track;           // longitudinal position, track x from the axle centre (yaw: the
                            // rigid-body shift of the wheel plus its lead; 0 without yaw) [m]
  double x_wheel;           // lead of the contact along the wheel's own rolling direction, from
                            // the vertical plane through its axle (CONTACT's XCP(W)); + ahead [m]
};

struct WheelContactGeometry {
  Side side = Side::left;
  std::vector<ContactPoint> points;  // primary (separation 0) first, then by separation
  std::vector<BandSample> band;      // uniform in s, ascending s
  double band_step = 0.0;            // s spacing of band [m]
  double wheel_drop = 0.0;           // vertical position of the wheel at rigid contact [m]
  double wheel_roll = 0.0;           // roll of the wheel in its side frame, sigma*roll [rad]
  double wheel_yaw = 0.0;            // yaw of the wheel in its side frame, sigma*yaw [rad]
  StatusBits status = 0;             // kTwoPoint when more than one point, kProfileEdge,
                                     //   kNearEqualMinima (GeometrySettings::near_equal_gap)
};

struct WheelsetContactGeometry {
  std::array<WheelContactGeometry, 2> wheels;  // [0] left, [1] right
  double rolling_radius_difference = 0.0;      // r_left - r_right of the primary contacts [m]
};

inline constexpr double kMaxYaw = 0.2;  // largest |yaw| the contact search accepts [rad]

// Profiles and geometry of one wheelset on one track. Immutable after construction; solve() is
// const and thread-safe.
class ContactGeometrySolver {
 public:
  // Left and right may share profile objects. Throws railtab::Error for inconsistent geometry.
  ContactGeometrySolver(ProfilePtr wheel_left, ProfilePtr rail_left, ProfilePtr wheel_right,
                        ProfilePtr rail_right, TrackGeometry track, WheelsetGeometry wheelset,
                        GeometrySettings settings = {});

  // Both wheels at the given state. NaN input, or |yaw| > kMaxYaw, throws railtab::Error naming
  // the input. With yaw the contact points lie on each wheel's silhouette seen along the track
  // (docs/conventions.md "Yaw"); yaw = 0 takes the yaw-free path, bit for bit.
  WheelsetContactGeometry solve(const WheelsetState& state) const;

  // One wheel only (the table sweep solves each side on its own grid point).
  WheelContactGeometry solve_wheel(Side side, const WheelsetState& state) const;

  // Kinematic roll of a rigid wheelset on rigid rails at lateral shift y: the roll at which both
  // wheels touch their rails at once [rad].
  double equilibrium_roll(double y) const;

  const TrackGeometry& track() const { return track_; }
  const WheelsetGeometry& wheelset() const { return wheelset_; }
  const GeometrySettings& settings() const { return settings_; }

 private:
  std::array<ProfilePtr, 2> wheel_;
  std::array<ProfilePtr, 2> rail_;
  TrackGeometry track_;
  WheelsetGeometry wheelset_;
  GeometrySettings settings_;
  std::array<double, 2> rail_offset_q_{};  // side-frame lateral position of each rail origin [m]
  std::array<double, 2> rail_offset_z_{};  // side-frame height of each rail origin [m]
  std::array<std::shared_ptr<const detail::PlacedRail>, 2> placed_rail_;    // rails placed and tabulated
  std::array<std::shared_ptr<const detail::WheelSamples>, 2> wheel_nodes_;  // coarse-search wheel nodes
};

}  // namespace railtab
