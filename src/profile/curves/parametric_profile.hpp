// SPDX-License-Identifier: Apache-2.0
// A profile through measured points that is not a function z(u): worn rails whose gauge corner
// overhangs, undercut field sides, wheels measured round the vertical flange back. The curve is
// parametrised by the chord length s of the points: s -> (y(s), z(s)), two cubic splines on the
// same knots (docs/profiles.md "Parametric profiles").
#pragma once

#include <string>
#include <vector>

#include "profile/curves/cubic_spline.hpp"
#include "profile/curves/profile.hpp"

namespace railtab {

class ParametricProfile final : public Profile {
 public:
  // Points (y_i, z_i) in profile frames (y = u towards the field side, z up) in order along the
  // surface, ascending y at both ends; at least 4 points, consecutive points distinct.
  // smoothing_length = L_filt [m]: 0 interpolates, > 0 smooths y(s) and z(s) like SplineProfile
  // smooths z(u) (lambda = (L_filt / 2 pi)^4 with s as the abscissa).
  ParametricProfile(std::string name, ProfileKind kind, std::vector<double> y, std::vector<double> z,
                    double smoothing_length = 0.0);

  bool parametric() const override { return true; }
  const std::vector<double>& knots() const { return y_.x; }  // chord length s_i of the knots [m]
  double smoothing_length() const { return smoothing_length_; }

 protected:
  // The single-valued view z(u) for callers that need one (plots, wear updates): of all points of
  // the curve at lateral u, the one facing the other body (the highest for a rail, the lowest for
  // a wheel). Slopes are infinite where the curve is vertical.
  ProfileSample eval_unchecked(double u) const override;
  CurveSample curve_unchecked(double t) const override;
  double t_min_parametric() const override { return y_.x.front(); }
  double t_max_parametric() const override { return y_.x.back(); }

 private:
  detail::CubicSpline y_;  // y(s)
  detail::CubicSpline z_;  // z(s)
  double smoothing_length_;
};

}  // namespace railtab
