// SPDX-License-Identifier: Apache-2.0
// Placement of rail and wheel in the side frame (model in placement.hpp and docs/conventions.md).
#include "geometry/placement.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/check.hpp"

namespace railtab::detail {
namespace {

// Cubic Hermite interpolation on [x0, x1] with end values y and end derivatives d.
double hermite(double x0, double x1, double y0, double y1, double d0, double d1, double x) {
  const double h = x1 - x0;
  const double t = (x - x0) / h;
  const double t2 = t * t;
  const double t3 = t2 * t;
  return (2 * t3 - 3 * t2 + 1) * y0 + (t3 - 2 * t2 + t) * h * d0 + (-2 * t3 + 3 * t2) * y1 +
         (t3 - t2) * h * d1;
}

}  // namespace

PlacedRail::PlacedRail(ProfilePtr profile, const TrackGeometry& track, double table_step)
    : profile_(std::move(profile)),
      alpha_(std::atan(track.rail_inclination)),
      cos_a_(std::cos(alpha_)),
      sin_a_(std::sin(alpha_)) {
  const Profile& p = *profile_;
  const double a = p.t_min();
  const double b = p.t_max();
  const int n_scan = std::max(2, static_cast<int>(std::ceil((b - a) / table_step)));
  const double h_scan = (b - a) / n_scan;
  auto z_rot = [&](double t) {
    const CurveSample c = p.curve(t);
    return sin_a_ * c.y + cos_a_ * c.z;
  };
  auto q_rot = [&](double t) {
    const CurveSample c = p.curve(t);
    return cos_a_ * c.y - sin_a_ * c.z;
  };

  auto node = [&](int i) { return i == n_scan ? b : a + h_scan * i; };

  // Highest point of the inclined rail: best node, then Newton on dz_rot/du = 0.
  int i_top = 0;
  double z_best = z_rot(a);
  for (int i = 1; i <= n_scan; ++i) {
    const double zi = z_rot(node(i));
    if (zi > z_best) {
      z_best = zi;
      i_top = i;
    }
  }
  double u_top = node(i_top);
  for (int it = 0; it < 30 && i_top > 0 && i_top < n_scan; ++it) {
    const CurveSample e = p.curve(u_top);
    const double f = sin_a_ * e.dy + cos_a_ * e.dz;
    const double df = sin_a_ * e.d2y + cos_a_ * e.d2z;
    if (!(df < 0.0)) break;  // not a maximum in the Newton sense: keep the node
    const double next = std::clamp(u_top - f / df, node(i_top - 1), node(i_top + 1));
    const bool done = std::abs(next - u_top) < 1e-14;
    u_top = next;
    if (done) break;
  }
  const double z_top = z_rot(u_top);

  // Upper surface: the branch around the top on which q increases with u. Beyond a fold
  // (an overhanging face) the surface is hidden from a wheel coming from above.
  auto dq_du = [&](double t) {
    const CurveSample c = p.curve(t);
    return cos_a_ * c.dy - sin_a_ * c.dz;
  };
  int i_lo = i_top;
  while (i_lo > 0 && dq_du(node(i_lo - 1)) > 1e-3) --i_lo;
  int i_hi = i_top;
  while (i_hi < n_scan && dq_du(node(i_hi + 1)) > 1e-3) ++i_hi;
  const double u_lo = node(i_lo);
  const double u_hi = node(i_hi);
  RAILTAB_CHECK(u_hi > u_lo, "rail profile '{}': no upper surface after inclination {}", p.name(),
                track.rail_inclination);

  // Gauge point: first node below the measuring depth walking from the top to the gauge side,
  // then bisection on the crossing.
  const double z_gauge = z_top - track.gauge_measuring_depth;
  double u_in = u_top;
  double u_out = u_top;
  bool found = false;
  for (int i = i_top; i >= i_lo; --i) {
    if (z_rot(node(i)) < z_gauge) {
      u_out = node(i);
      found = true;
      break;
    }
    u_in = node(i);
  }
  RAILTAB_CHECK(found,
                "rail profile '{}' does not reach the gauge measuring depth {} m below its top on "
                "the gauge side",
                p.name(), track.gauge_measuring_depth);
  for (int it = 0; it < 200 && std::abs(u_in - u_out) > 1e-13; ++it) {
    const double mid = 0.5 * (u_in + u_out);
    (z_rot(mid) >= z_gauge ? u_in : u_out) = mid;
  }
  const double u_gauge = 0.5 * (u_in + u_out);
  offset_q_ = 0.5 * track.gauge - q_rot(u_gauge);
  offset_z_ = -z_top;

  // Tables on the upper branch.
  const int n = std::max(2, static_cast<int>(std::ceil((u_hi - u_lo) / table_step)));
  const double h = (u_hi - u_lo) / n;
  t_.resize(n + 1);
  q_.resize(n + 1);
  z_.resize(n + 1);
  slope_.resize(n + 1);
  s_.resize(n + 1);
  ds_.resize(n + 1);
  // 3-point Gauss-Legendre per interval for the arc length.
  const double gl_x = std::sqrt(0.6);
  auto ds_du = [&](double t) { return std::sqrt(speed_squared(p.curve(t))); };
  for (int i = 0; i <= n; ++i) {
    const double u = i == n ? u_hi : u_lo + h * i;
    const RailPoint rp = point(u);
    t_[i] = u;
    q_[i] = rp.p.q;
    z_[i] = rp.p.z;
    slope_[i] = rp.tangent.z / rp.tangent.q;
    ds_[i] = ds_du(u);
    if (i == 0) {
      s_[i] = 0.0;
    } else {
      const double m = 0.5 * (t_[i - 1] + u);
      const double r = 0.5 * (u - t_[i - 1]);
      s_[i] = s_[i - 1] + r * (5.0 / 9.0 * ds_du(m - r * gl_x) + 8.0 / 9.0 * ds_du(m) +
                               5.0 / 9.0 * ds_du(m + r * gl_x));
    }
  }
  for (int i = 1; i <= n; ++i) {
    RAILTAB_CHECK(q_[i] > q_[i - 1], "rail profile '{}': lateral position not monotone near t = {} m",
                  p.name(), t_[i]);
  }
}

RailPoint PlacedRail::point(double t) const {
  const CurveSample e = profile_->curve(t);
  RailPoint r;
  r.t = t;
  r.u = e.y;
  r.p = {cos_a_ * e.y - sin_a_ * e.z + offset_q_, sin_a_ * e.y + cos_a_ * e.z + offset_z_};
  r.tangent = {cos_a_ * e.dy - sin_a_ * e.dz, sin_a_ * e.dy + cos_a_ * e.dz};
  r.angle = alpha_ + tangent_angle(e.dy, e.dz);
  const double w = speed_squared(e);
  const double k = curvature_numerator(e);
  r.dangle_dt = k / w;
  r.curvature = -k / (w * std::sqrt(w));  // the profile counts a convex crown negative
  return r;
}

int PlacedRail::interval_of(const std::vector<double>& x, double value) const {
  const auto it = std::upper_bound(x.begin(), x.end(), value);
  const int j = static_cast<int>(it - x.begin()) - 1;
  return std::clamp(j, 0, static_cast<int>(x.size()) - 2);
}

double PlacedRail::z_at_q_table(double q, int& hint) const {
  const int last = static_cast<int>(q_.size()) - 2;
  int j = std::clamp(hint, 0, last);
  while (j < last && q > q_[j + 1]) ++j;
  while (j > 0 && q < q_[j]) --j;
  hint = j;
  return hermite(q_[j], q_[j + 1], z_[j], z_[j + 1], slope_[j], slope_[j + 1], q);
}

double PlacedRail::t_at_q(double q) const {
  const int j = interval_of(q_, q);
  const double lo = t_[j];
  const double hi = t_[j + 1];
  double u = lo + (hi - lo) * (q - q_[j]) / (q_[j + 1] - q_[j]);
  for (int it = 0; it < 30; ++it) {
    const CurveSample e = profile_->curve(u);
    const double f = cos_a_ * e.y - sin_a_ * e.z + offset_q_ - q;
    const double df = cos_a_ * e.dy - sin_a_ * e.dz;
    const double next = std::clamp(u - f / df, std::max(t_lo(), lo - (hi - lo)),
                                   std::min(t_hi(), hi + (hi - lo)));
    const bool done = std::abs(next - u) < 1e-14;
    u = next;
    if (done) break;
  }
  return u;
}

double PlacedRail::s_at_t(double t) const {
  const int j = interval_of(t_, t);
  return hermite(t_[j], t_[j + 1], s_[j], s_[j + 1], ds_[j], ds_[j + 1], t);
}

double PlacedRail::t_at_s(double s) const {
  const int j = interval_of(s_, s);
  return hermite(s_[j], s_[j + 1], t_[j], t_[j + 1], 1.0 / ds_[j], 1.0 / ds_[j + 1], s);
}

WheelSamples::WheelSamples(const Profile& wheel, double step) {
  const int n = std::max(2, static_cast<int>(std::ceil((wheel.t_max() - wheel.t_min()) / step)));
  t0 = wheel.t_min();
  h = (wheel.t_max() - wheel.t_min()) / n;
  t_end = wheel.t_max();
  y.resize(n + 1);
  z.resize(n + 1);
  dy.resize(n + 1);
  dz.resize(n + 1);
  for (int i = 0; i <= n; ++i) {
    const CurveSample e = wheel.curve(i == n ? t_end : t0 + h * i);
    y[i] = e.y;
    z[i] = e.z;
    dy[i] = e.dy;
    dz[i] = e.dz;
  }
  if (!wheel.parametric()) {
    i_running = std::clamp(static_cast<int>(std::lround(-t0 / h)), 0, n);
  } else {
    // The node nearest y = 0 among those on a part of the curve that runs towards the field side.
    i_running = -1;
    for (int i = 0; i <= n; ++i) {
      if (dy[i] > 0.0 && (i_running < 0 || std::abs(y[i]) < std::abs(y[i_running]))) i_running = i;
    }
    RAILTAB_CHECK(i_running >= 0, "wheel profile '{}': no part runs towards the field side", wheel.name());
  }
}

WheelPose make_pose(Side side, const WheelsetState& state, const WheelsetGeometry& wheelset) {
  const double sigma = outward_sign(side);
  WheelPose pose;
  pose.theta = sigma * state.roll;
  pose.qc = sigma * state.y;
  pose.zc = wheelset.nominal_radius;
  pose.cos_t = std::cos(pose.theta);
  pose.sin_t = std::sin(pose.theta);
  pose.q0 = 0.5 * wheelset.back_to_back - wheelset.flange_back_position;
  pose.r0 = wheelset.nominal_radius;
  if (state.yaw != 0.0) {
    pose.yawed = true;
    pose.psi = sigma * state.yaw;
    pose.cos_p = std::cos(pose.psi);
    pose.sin_p = std::sin(pose.psi);
  }
  return pose;
}

// Wheel axes in the side frame (x forward, q outward, z up) for the orientation R_x(theta) R_z(psi)
// (yawed about the vertical, then rolled about the track's x axis, as CONTACT places a wheelset):
// forward e_f = (cp, sp ct, sp st), up e_v = (0, -st, ct), axle (outward) e_a = (-sp, cp ct, cp st).
// Profile point u lies on the circle of radius r = r0 - z_w(u) about C + a e_a, a = q0 + y_w(u);
// at the angle tau from its lowest point it is P = C + a e_a + r rho, rho = -cos(tau) e_v +
// sin(tau) e_f, with the outward surface normal n = N_a e_a + N_r rho, (N_a, N_r) = (z', y')/|.|
// the profile normal in the (axial, radial) half-plane (N_a/N_r = tan(gamma_w), gamma_w the
// wheel's own contact angle there). The rail is extruded along x, so contact needs n_x = 0:
//   -N_a sin(psi) + N_r sin(tau) cos(psi) = 0,  i.e.  sin(tau) = tan(gamma_w) tan(psi)
// for any roll, and the contact leads the wheel's axle plane by r sin(tau) = r tan(gamma_w)
// tan(psi) (the flange lead of a yawed wheel).
TracePoint WheelPose::trace(const CurveSample& e) const {
  const double a = q0 + e.y;
  const double r = r0 - e.z;
  const double speed = std::hypot(e.dy, e.dz);
  const double na = e.dz / speed, nr = e.dy / speed;
  const double s_tau = std::clamp(na * sin_p / (nr * cos_p), -1.0, 1.0);  // nr > 0 facing the rail
  const double c_tau = std::sqrt(1.0 - s_tau * s_tau);
  // rho = -c_tau e_v + s_tau e_f
  const double rho_x = s_tau * cos_p;
  const double rho_q = c_tau * sin_t + s_tau * sin_p * cos_t;
  const double rho_z = -c_tau * cos_t + s_tau * sin_p * sin_t;
  const double ea_q = cos_p * cos_t, ea_z = cos_p * sin_t;
  TracePoint tp;
  tp.x = -a * sin_p + r * rho_x;
  tp.p = {qc + a * ea_q + r * rho_q, zc + a * ea_z + r * rho_z};
  tp.x_wheel = r * s_tau;
  const double n_q = na * ea_q + nr * rho_q, n_z = na * ea_z + nr * rho_z;  // points into the rail
  tp.angle = std::atan2(n_q, -n_z);
  tp.cos_chi = c_tau * cos_p;  // circle tangent s_tau e_v + c_tau e_f against track x
  return tp;
}

}  // namespace railtab::detail
