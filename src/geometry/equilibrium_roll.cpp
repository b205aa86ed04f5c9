// SPDX-License-Identifier: Apache-2.0
// Kinematic roll of a rigid wheelset on rigid rails: the roll at which both wheels touch at once.
//
// Each wheel, rolled about the common axle centre, needs its own vertical drop to touch its rail;
// a rigid wheelset touches with both when the drops agree. f(roll) = drop_left - drop_right
// falls with roll at about -2*Q0 (positive roll lifts the left wheel, so the axle must sink for
// it and may rise for the right one), so a secant step from roll = 0 lands close; a bracket and
// Brent's method (core/root_find.hpp) finish the job, also across the kink of a jump into flange
// contact.
#include <cmath>

#include "core/check.hpp"
#include "core/root_find.hpp"
#include "geometry/contact_geometry.hpp"
#include "geometry/placement.hpp"

namespace railtab {

double ContactGeometrySolver::equilibrium_roll(double y) const {
  RAILTAB_CHECK(std::isfinite(y), "contact geometry: equilibrium_roll y = {} is not finite", y);
  auto drop = [&](Side side, double roll) {
    const int i = static_cast<int>(side);
    const detail::WheelPose pose = detail::make_pose(side, WheelsetState{y, roll}, wheelset_);
    return -detail::search_contacts(*placed_rail_[i], *wheel_[i], *wheel_nodes_[i], pose, 0.0).gap_min;
  };
  auto f = [&](double roll) { return drop(Side::left, roll) - drop(Side::right, roll); };

  const double slope_guess = -(wheelset_.back_to_back - 2.0 * wheelset_.flange_back_position);
  double a = 0.0;
  double fa = f(a);
  if (fa == 0.0) return a;
  // Bracket: step along the secant estimate, doubling until the sign changes.
  double step = -fa / slope_guess;
  double b = a + step;
  double fb = f(b);
  for (int it = 0; it < 60 && (fa > 0.0) == (fb > 0.0); ++it) {
    a = b;
    fa = fb;
    step *= 2.0;
    b = a + step;
    fb = f(b);
  }
  RAILTAB_CHECK((fa > 0.0) != (fb > 0.0), "contact geometry: no equilibrium roll found at y = {} m", y);

  constexpr double kTol = 1e-14;  // [rad]
  return brent_root(f, a, b, fa, fb, kTol, 0.0, 200).x;
}

}  // namespace railtab
