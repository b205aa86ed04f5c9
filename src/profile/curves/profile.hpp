// SPDX-License-Identifier: Apache-2.0
// A wheel or rail profile: a smooth curve z(u) with first and second derivatives anywhere in its
// range. Frames and signs are defined once in docs/conventions.md ("Profile frames"):
//   u [m]  lateral, positive towards the field side (away from the track centre), for both bodies;
//   z [m]  vertical, positive up.
//   Rail:  z is the height of the (uninclined) head surface; u = 0 on the head centreline, z = 0 at
//          the top of the head.
//   Wheel: z = -(r(u) - r_nominal): u = 0 on the nominal running circle, the flange points down
//          (z < 0 there). The rolling radius at u is r_nominal - z(u).
#pragma once

#include <memory>
#include <string>

namespace railtab {

enum class ProfileKind { wheel, rail };

struct ProfileSample {
  double z;    // height [m]
  double dz;   // slope dz/du [-]
  double d2z;  // second derivative d2z/du2 [1/m]
};

// A point of the profile as a parametric curve t -> (y(t), z(t)) with derivatives in t. For a
// function profile t = u (y = t, dy = 1, d2y = 0); for a ParametricProfile t is the arc length.
// The geometry layer works on this form only, so it handles overhangs and undercuts (a vertical
// line crossing the surface twice) the same way as single-valued profiles.
struct CurveSample {
  double y;    // lateral profile coordinate u [m]
  double z;    // height [m]
  double dy;   // dy/dt [-]
  double dz;   // dz/dt [-]
  double d2y;  // d2y/dt2 [1/m]
  double d2z;  // d2z/dt2 [1/m]
};

class Profile {
 public:
  Profile(std::string name, ProfileKind kind, double u_min, double u_max);
  virtual ~Profile() = default;
  Profile(const Profile&) = delete;
  Profile& operator=(const Profile&) = delete;

  // Height and derivatives at u. Throws railtab::Error when u is outside [u_min, u_max] or NaN.
  ProfileSample eval(double u) const;

  // Signed curvature d2z / (1 + dz^2)^1.5 [1/m]; positive where the curve is concave up (seen
  // from above). A convex rail crown has negative curvature, a concave wheel tread negative too
  // (its surface z = -F with F'' > 0); see docs/conventions.md for the contact-curvature signs.
  double curvature(double u) const;

  double u_min() const { return u_min_; }  // [m]
  double u_max() const { return u_max_; }  // [m]

  // The profile as a parametric curve, t in [t_min, t_max] ascending towards the field side at
  // both ends. Function profiles: t = u. Throws railtab::Error outside the range or for NaN.
  CurveSample curve(double t) const;
  double t_min() const { return parametric() ? t_min_parametric() : u_min_; }  // [m]
  double t_max() const { return parametric() ? t_max_parametric() : u_max_; }  // [m]
  // True when the profile is a curve that is not a function z(u) (ParametricProfile).
  virtual bool parametric() const { return false; }
  const std::string& name() const { return name_; }
  ProfileKind kind() const { return kind_; }

 protected:
  // Evaluation inside the checked range.
  virtual ProfileSample eval_unchecked(double u) const = 0;
  // Parametric profiles override these three (t inside the checked range).
  virtual CurveSample curve_unchecked(double t) const;
  virtual double t_min_parametric() const { return u_min_; }
  virtual double t_max_parametric() const { return u_max_; }

 private:
  std::string name_;
  ProfileKind kind_;
  double u_min_;
  double u_max_;
};

using ProfilePtr = std::shared_ptr<const Profile>;

}  // namespace railtab
