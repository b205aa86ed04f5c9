// SPDX-License-Identifier: Apache-2.0
// The Profile interface (profile.hpp): what every wheel and rail curve shares.
#include "profile/curves/profile.hpp"

#include <cmath>
#include <utility>

#include "core/check.hpp"

namespace railtab {

Profile::Profile(std::string name, ProfileKind kind, double u_min, double u_max)
    : name_(std::move(name)), kind_(kind), u_min_(u_min), u_max_(u_max) {
  RAILTAB_CHECK(std::isfinite(u_min) && std::isfinite(u_max) && u_min < u_max,
                "profile '{}': invalid lateral range [{}, {}] m", name_, u_min, u_max);
}

ProfileSample Profile::eval(double u) const {
  RAILTAB_CHECK(u >= u_min_ && u <= u_max_,
                "profile '{}': u = {} m is outside its range [{}, {}] m", name_, u, u_min_, u_max_);
  return eval_unchecked(u);
}

CurveSample Profile::curve(double t) const {
  RAILTAB_CHECK(t >= t_min() && t <= t_max(),
                "profile '{}': curve parameter t = {} m is outside its range [{}, {}] m", name_, t,
                t_min(), t_max());
  return curve_unchecked(t);
}

CurveSample Profile::curve_unchecked(double t) const {
  const ProfileSample p = eval_unchecked(t);
  return {t, p.z, 1.0, p.dz, 0.0, p.d2z};
}

double Profile::curvature(double u) const {
  const ProfileSample p = eval(u);
  const double slope_term = 1.0 + p.dz * p.dz;
  return p.d2z / (slope_term * std::sqrt(slope_term));
}

}  // namespace railtab
