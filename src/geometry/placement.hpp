// SPDX-License-Identifier: Apache-2.0
// Internal to the geometry layer: the rail and wheel curves placed in a side frame (q outward,
// z up; docs/conventions.md "Side frame"), with the tables that make the hot loop cheap.
//
// Both profiles are used as parametric curves t -> (y(t), z(t)) (Profile::curve; t = u for a
// function profile, the arc length for a ParametricProfile), so overhangs and undercuts need no
// special case: only the branch that faces the other body is searched (q increasing with t).
//
// Rail: the profile (y, z_r) rotated counter-clockwise in the (q, z) plane by
// alpha = atan(rail_inclination), so that the crown slope dz/dq at u = 0 becomes +inclination:
// the head leans towards the track centre and its normal tilts inwards, like the coned wheel
// tread. Then translated so that the gauge point (innermost point gauge_measuring_depth below the
// highest point of the inclined rail) lies at q = gauge/2 and the highest point at z = 0.
// The rail does not depend on the wheelset state, so it is tabulated once.
//
// Wheel: the profile (u, z_w(u)) in wheelset axes, relative to the axle centre C:
// (Q0 + u, z_w(u) - r0) with Q0 = back_to_back/2 - flange_back_position; rotated by
// theta = sigma*roll about C and placed with C = (sigma*y, r0 + drop).
#pragma once

#include <cmath>
#include <vector>

#include "geometry/contact_geometry.hpp"

namespace railtab::detail {

struct Point2 {
  double q;  // side frame lateral [m]
  double z;  // side frame vertical [m]
};

inline double cross(const Point2& a, const Point2& b) { return a.q * b.z - a.z * b.q; }

// One rail point with everything the search and the band need.
struct RailPoint {
  double t;          // rail curve parameter [m]
  double u;          // rail-profile lateral coordinate y(t) [m]
  Point2 p;          // placed point [m]
  Point2 tangent;    // unnormalised tangent dP/du [-]
  double angle;      // angle of the outward normal from vertical, + towards the track centre [rad]
  double dangle_dt;  // d(angle)/dt = (y'z'' - z'y'')/(y'^2 + z'^2) [1/m]
  double curvature;  // lateral curvature, + convex (crown) [1/m]
};

// The rail of one side, placed in its side frame and tabulated on a uniform u grid.
class PlacedRail {
 public:
  PlacedRail(ProfilePtr profile, const TrackGeometry& track, double table_step);

  RailPoint point(double t) const;  // exact, t in [t_lo, t_hi]

  // Height of the rail at lateral q from the table (cubic Hermite in q): the coarse search only.
  // hint: table interval to start from (updated), for monotone sweeps.
  double z_at_q_table(double q, int& hint) const;

  // Exact rail curve parameter at lateral q on the upper branch (Newton, started from the table).
  double t_at_q(double q) const;

  // Arc length from t_lo (cubic Hermite on the tabulated arc length) and its inverse.
  double s_at_t(double t) const;
  double t_at_s(double s) const;

  double q_lo() const { return q_.front(); }  // [m]
  double q_hi() const { return q_.back(); }   // [m]
  double t_lo() const { return t_.front(); }  // [m]
  double t_hi() const { return t_.back(); }   // [m]
  double s_hi() const { return s_.back(); }   // [m]
  double offset_q() const { return offset_q_; }  // side-frame q of the rail-profile origin [m]
  double offset_z() const { return offset_z_; }  // side-frame z of the rail-profile origin [m]
  double alpha() const { return alpha_; }        // inclination angle [rad]
  const Profile& profile() const { return *profile_; }

 private:
  int interval_of(const std::vector<double>& x, double value) const;

  ProfilePtr profile_;
  double alpha_, cos_a_, sin_a_;
  double offset_q_ = 0.0, offset_z_ = 0.0;
  // Table on the branch of the rail whose q increases with t (the upper surface), step h in t.
  std::vector<double> t_;      // nodes [m]
  std::vector<double> q_;      // placed q at the nodes, strictly increasing [m]
  std::vector<double> z_;      // placed z at the nodes [m]
  std::vector<double> slope_;  // dz/dq at the nodes [-]
  std::vector<double> s_;      // arc length from the first node [m]
  std::vector<double> ds_;     // ds/dt = sqrt(y'^2 + z'^2) at the nodes [-]
};

// Wheel profile samples on a uniform grid of the curve parameter t (the coarse search walks them).
struct WheelSamples {
  double t0;                // first node [m]
  double h;                 // node spacing [m]
  std::vector<double> y;    // lateral profile coordinate at the nodes [m]
  std::vector<double> z;    // z_w at the nodes [m]
  std::vector<double> dy;   // dy/dt at the nodes [-]
  std::vector<double> dz;   // dz_w/dt at the nodes [-]
  int i_running;            // node nearest the running circle (y = 0) on the part facing the rail
  WheelSamples(const Profile& wheel, double step);
  double t_end;             // last node = wheel t_max [m]
  double t(int i) const { return i + 1 == size() ? t_end : t0 + h * i; }
  CurveSample at(int i) const {  // position and slope of node i (no second derivatives)
    CurveSample c{};
    c.y = y[i];
    c.z = z[i];
    c.dy = dy[i];
    c.dz = dz[i];
    return c;
  }
  int size() const { return static_cast<int>(z.size()); }
};

// Angle of the curve tangent (dy, dz) from the lateral axis [rad]: atan(dz/dy) where dy > 0,
// which is atan(dz) exactly for a function profile (dy = 1).
inline double tangent_angle(double dy, double dz) {
  return dy > 0.0 ? std::atan(dz / dy) : std::atan2(dz, dy);
}

// Signed curvature numerator y'z'' - z'y'' (d2z for a function profile) and |r'|^2.
inline double curvature_numerator(const CurveSample& c) { return c.dy * c.d2z - c.dz * c.d2y; }
inline double speed_squared(const CurveSample& c) { return c.dy * c.dy + c.dz * c.dz; }

// The point of a yawed wheel's circle through one profile point at which the wheel surface
// normal has no component along the track (x): the silhouette of the wheel seen along the track,
// which is where a rail extruded along x can touch it (docs/conventions.md "Yaw").
struct TracePoint {
  Point2 p;        // silhouette point in the side plane [m]
  double x;        // its longitudinal position, track x from the axle centre [m]
  double x_wheel;  // along the wheel's forward axis from the vertical plane through the axle,
                   // r sin(tau) (tau the angle on the circle from its lowest point) [m]
  double angle;    // tangent angle of the silhouette from the q axis = angle of the wheel's
                   // normal from vertical in the side plane [rad]
  double cos_chi;  // cos of the angle between track x and the circle's tangent there [-]
};

// Pose of one wheel in its side frame.
struct WheelPose {
  double qc;      // axle centre, lateral = sigma*y [m]
  double zc;      // axle centre height = r0 + drop [m]
  double cos_t;   // cos(sigma*roll)
  double sin_t;   // sin(sigma*roll)
  double theta;   // sigma*roll [rad]
  double q0;      // lateral distance axle centre -> running circle, back_to_back/2 - flange_back [m]
  double r0;      // nominal radius [m]
  bool yawed = false;  // psi != 0: the contact search works on trace() instead of place()
  double psi = 0.0;    // sigma*yaw [rad]
  double cos_p = 1.0;  // cos(psi)
  double sin_p = 0.0;  // sin(psi)

  Point2 place(double y_w, double z_w) const {
    const double a = q0 + y_w;
    const double b = z_w - r0;
    return {qc + cos_t * a - sin_t * b, zc + sin_t * a + cos_t * b};
  }
  Point2 tangent(double dy_w, double dz_w) const {
    return {cos_t * dy_w - sin_t * dz_w, sin_t * dy_w + cos_t * dz_w};
  }
  // Silhouette point of the circle through profile sample e (yawed wheel; placement.cpp).
  TracePoint trace(const CurveSample& e) const;
};

WheelPose make_pose(Side side, const WheelsetState& state, const WheelsetGeometry& wheelset);

// Rigid contact search result of one wheel (before the band).
struct RawContact {
  double wheel_t;  // wheel curve parameter [m]
  double rail_t;   // rail curve parameter [m]
  double gap;      // vertical gap with the wheel at drop 0 [m]
  bool edge;       // minimum sits at the end of the searchable range
};

struct SearchResult {
  std::vector<RawContact> minima;  // refined local minima, any order
  double gap_min;                  // smallest vertical gap at drop 0 [m]
};

// Local minima of the vertical gap g(q) = z_wheel - z_rail with the wheel at drop 0, coarse
// sampling at the wheel nodes then refined to ~1e-10 m on the exact curves. Only minima within
// max_separation of the lowest are kept. Throws railtab::Error when wheel and rail do not overlap.
SearchResult search_contacts(const PlacedRail& rail, const Profile& wheel,
                             const WheelSamples& samples, const WheelPose& pose,
                             double max_separation);

// Gap band (see contact_geometry.hpp BandSample). The pose must include the drop. Returns
// true when the band was cut by a profile end while the gap was still within band_max_gap.
bool build_band(const PlacedRail& rail, const Profile& wheel, const WheelPose& pose,
                const GeometrySettings& settings, WheelContactGeometry& out);

}  // namespace railtab::detail
