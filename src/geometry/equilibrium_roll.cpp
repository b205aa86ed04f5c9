// Kinematic roll of a rigid wheelset on rigid rails: the roll at which both wheels touch at once.
//
// Each wheel, rolled about the common axle centre, needs its own vertical drop to touch its rail;
// a rigid wheelset touches with both when the drops agree. f(roll) = drop_left - drop_right
// falls with roll at about -2*Q0 (positive roll lifts the left wheel, so the axle must sink for
// it and may rise for the right one), so a secant step from roll = 0 lands close; a bracket and
// Brent's method finish the job, also across the kink of a jump into flange contact.
#include <cmath>
#include <utility>

#include "core/check.hpp"
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

  // Brent's root finder (Numerical Recipes zbrent form).
  constexpr double kTol = 1e-14;  // [rad]
  double c = b, fc = fb, d = 0.0, e = 0.0;
  for (int it = 0; it < 200; ++it) {
    if ((fb > 0.0) == (fc > 0.0)) {
      c = a;
      fc = fa;
      d = e = b - a;
    }
    if (std::abs(fc) < std::abs(fb)) {
      a = b; b = c; c = a;
      fa = fb; fb = fc; fc = fa;
    }
    const double tol = 2.0 * 1e-16 * std::abs(b) + 0.5 * kTol;
    const double xm = 0.5 * (c - b);
    if (std::abs(xm) <= tol || fb == 0.0) return b;
    if (std::abs(e) >= tol && std::abs(fa) > std::abs(fb)) {
      const double s = fb / fa;
      double p, q;
      if (a == c) {
        p = 2.0 * xm * s;
        q = 1.0 - s;
      } else {
        const double qq = fa / fc, r = fb / fc;
        p = s * (2.0 * xm * qq * (qq - r) - (b - a) * (r - 1.0));
        q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
      }
      if (p > 0.0) q = -q;
      p = std::abs(p);
      if (2.0 * p < std::min(3.0 * xm * q - std::abs(tol * q), std::abs(e * q))) {
        e = d;
        d = p / q;
      } else {
        d = xm;
        e = d;
      }
    } else {
      d = xm;
      e = d;
    }
    a = b;
    fa = fb;
    b += std::abs(d) > tol ? d : (xm > 0.0 ? tol : -tol);
    fb = f(b);
  }
  return b;
}

}  // namespace railtab
