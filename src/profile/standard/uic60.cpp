// SPDX-License-Identifier: Apache-2.0
// The UIC60 / 60E1 rail head from its arcs (uic60.hpp).
#include "profile/standard/uic60.hpp"

#include <cmath>
#include <memory>

#include "core/check.hpp"

namespace railtab {
namespace {

struct Point {
  double u;  // lateral [m]
  double z;  // vertical [m]
};

// z(a), dz/da, d2z/da2 of the upper half of a circle (convex, z up) at a.
ProfileSample upper_arc(Point centre, double radius, double a) {
  const double w = a - centre.u;
  const double q = std::sqrt(radius * radius - w * w);
  return {centre.z + q, -w / q, -radius * radius / (q * q * q)};
}

class Uic60Profile final : public Profile {
 public:
  Uic60Profile(const Uic60Geometry& g, double u_end)
      : Profile("UIC60", ProfileKind::rail, -u_end, u_end), g_(g) {
    crown_centre_ = {0.0, -g.crown_radius};
    // R80 is internally tangent to R300 at |u| = crown_end: its centre lies on the crown
    // radius through that point, (R300 - R80) from the crown centre.
    const double shoulder_offset = g.crown_radius - g.shoulder_radius;
    shoulder_centre_.u = g.crown_end * shoulder_offset / g.crown_radius;
    shoulder_centre_.z = crown_centre_.z + std::sqrt(shoulder_offset * shoulder_offset -
                                                     shoulder_centre_.u * shoulder_centre_.u);
    // R13 touches the side face at |u| = side_start; the face's outward normal is
    // (1, inclination)/|.|, so the corner centre lies corner_radius inside along it. Its
    // height follows from internal tangency to R80 (centre distance R80 - R13).
    const double normal_norm = std::sqrt(1.0 + g.side_inclination * g.side_inclination);
    const double corner_offset = g.shoulder_radius - g.corner_radius;
    corner_centre_.u = g.side_start - g.corner_radius / normal_norm;
    const double du = corner_centre_.u - shoulder_centre_.u;
    RAILTAB_CHECK(du < corner_offset, "UIC60 construction: R13 centre out of reach of R80");
    corner_centre_.z = shoulder_centre_.z + std::sqrt(corner_offset * corner_offset - du * du);
    shoulder_end_ = shoulder_centre_.u + g.shoulder_radius * du / corner_offset;
    side_top_z_ = corner_centre_.z + g.corner_radius * g.side_inclination / normal_norm;
  }

 protected:
  ProfileSample eval_unchecked(double u) const override {
    const double a = std::fabs(u);
    ProfileSample s{};
    if (a <= g_.crown_end) {
      s = upper_arc(crown_centre_, g_.crown_radius, a);
    } else if (a <= shoulder_end_) {
      s = upper_arc(shoulder_centre_, g_.shoulder_radius, a);
    } else if (a <= g_.side_start) {
      s = upper_arc(corner_centre_, g_.corner_radius, a);
    } else {
      const double slope = -1.0 / g_.side_inclination;
      s = {side_top_z_ + slope * (a - g_.side_start), slope, 0.0};
    }
    // Mirror image for u < 0: z even, slope odd, second derivative even.
    if (u < 0.0) s.dz = -s.dz;
    return s;
  }

 private:
  Uic60Geometry g_;        // nominal dimensions
  Point crown_centre_;     // R300 centre [m]
  Point shoulder_centre_;  // R80 centre, u > 0 side [m]
  Point corner_centre_;    // R13 centre, u > 0 side [m]
  double shoulder_end_;    // |u| where R80 meets R13 [m]
  double side_top_z_;      // z where R13 meets the side face [m]
};

}  // namespace

ProfilePtr make_uic60_profile() {
  const Uic60Geometry g;
  // The side face is a line of slope -1/inclination from (side_start, side_top_z); find its
  // top height by building the profile once with a provisional range.
  const Uic60Profile provisional(g, g.side_start);
  const double side_top_z = provisional.eval(g.side_start).z;
  const double u_end = g.side_start + (g.side_depth + side_top_z) * g.side_inclination;
  return std::make_shared<const Uic60Profile>(g, u_end);
}

}  // namespace railtab
