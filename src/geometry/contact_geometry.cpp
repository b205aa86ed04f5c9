// SPDX-License-Identifier: Apache-2.0
// ContactGeometrySolver: input checks, one wheel's contact points and band, both wheels.
#include "geometry/contact_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "core/check.hpp"
#include "geometry/curvature_steps.hpp"
#include "geometry/placement.hpp"
#include "profile/formats/profile_checks.hpp"

namespace railtab {

const char* to_string(Side side) { return side == Side::left ? "left" : "right"; }

namespace {

void check_profile(const ProfilePtr& p, ProfileKind kind, const char* what) {
  RAILTAB_CHECK(p != nullptr, "contact geometry: {} profile is missing", what);
  RAILTAB_CHECK(p->kind() == kind, "contact geometry: {} profile '{}' is not a {} profile", what,
                p->name(), kind == ProfileKind::wheel ? "wheel" : "rail");
}

void check_positive(double value, const char* name) {
  RAILTAB_CHECK(std::isfinite(value) && value > 0.0, "contact geometry: {} = {} must be finite and > 0",
                name, value);
}

constexpr double kMaxCurveLength = 4.0;  // [m]; readers limit coordinates to 1 m

// A rail file that already holds the cant (MBench_UIC60_v3.prr) would be inclined twice. A head
// that is mirror-symmetric (to 0.02 mm) about an axis tilted by more than 0.005 rad, and clearly
// not (by 0.1 mm or more) about the vertical, is such a file.
void check_not_canted_twice(const Profile& rail, double inclination) {
  const ApparentCant cant = apparent_cant(rail);
  RAILTAB_CHECK(!(cant.asymmetry < 2e-5 && cant.asymmetry_as_given > 1e-4 && std::abs(cant.beta) > 5e-3),
                "contact geometry: rail profile '{}' is already inclined (its head is symmetric about "
                "an axis tilted by {:.5f} rad, 1:{:.1f}); track.rail_inclination = {} would cant it "
                "twice: set rail_inclination = 0 for a pre-inclined rail, or give the uninclined profile",
                rail.name(), cant.beta, 1.0 / std::tan(std::abs(cant.beta)), inclination);
}

// Which rigid point is the primary one is decided by a gap difference that crosses zero as y
// changes. A local minimum's gap changes with the wheelset shift at the rate -tan(g) of its
// contact angle g (the gap is stationary in the wheel coordinate there), so the separation h of
// point k closes at |tan g_k - tan g_0| per metre of shift. Where that happens within
// near_equal_shift (the two minima of a hollow tread, a flange onset), the primary point and its
// radius and angle may jump from one y to the next. The loads need not jump: both points stay in
// `points`, and the normal models load both once the approach exceeds h. The flag tells a user
// of the primary point's quantities (a table's geometry slot).
void flag_near_equal_minima(const GeometrySettings& settings, WheelContactGeometry& out) {
  ContactPoint& primary = out.points.front();
  for (std::size_t k = 1; k < out.points.size(); ++k) {
    ContactPoint& p = out.points[k];
    const double distance = std::hypot(p.y_track - primary.y_track, p.z_track - primary.z_track);
    const double closing_rate =
        std::abs(std::tan(p.contact_angle_side) - std::tan(primary.contact_angle_side));
    if (p.separation < settings.near_equal_shift * closing_rate &&
        distance >= settings.near_equal_distance) {
      p.status |= status::kNearEqualMinima;
      primary.status |= status::kNearEqualMinima;
      out.status |= status::kNearEqualMinima;
    }
  }
}

// A lateral curvature step of either profile (a radius transition: UIC60's R300/R80 at |u| =
// 10.5 mm and R80/R13 at 26 mm, S1002's section joins) within half a band step of a rigid point.
// B at the point is the profiles' curvature there, so it steps by half the curvature step where
// the point crosses a transition, and with it Hertz, Linder's load closure and STRIPES'
// virtual penetration (Car7216 / UIC60: B 11.5 -> 6.9 1/m, Hertz's approach 0.1143 -> 0.1078 mm
// between y = -0.10 and -0.05 mm). A cell [i, i + 1] of the band holds a step when its curvature
// difference exceeds 1 1/m and 10 % of the larger value (the thresholds of the STRIPES cell
// averages, src/normal/stripes.cpp) and 4 times the differences of both neighbouring cells (a
// steep but smooth curvature, e.g. of a smoothed measured profile, is no step). The step is
// located inside its cell as STRIPES locates it (geometry/curvature_steps.hpp). Half a band step: when
// the point moves less than a band step per step of a y sweep, one of the two samples around
// the crossing carries the flag, and the flag stays narrow (the continuity checks lose no more
// neighbouring steps than needed).
void flag_curvature_steps(WheelContactGeometry& out) {
  const std::vector<BandSample>& band = out.band;
  const int nb = static_cast<int>(band.size());
  const double h = out.band_step;
  if (nb < 6 || !(h > 0.0)) return;
  // A step stands out from both neighbouring cells' differences (reads samples i - 1 .. i + 2).
  auto stands_out = [&](int i, double BandSample::*k) {
    const double d = band[i + 1].*k - band[i].*k;
    const double dl = band[i].*k - band[i - 1].*k, dr = band[i + 2].*k - band[i + 1].*k;
    return std::abs(d) > 4.0 * std::max(std::abs(dl), std::abs(dr));
  };
  // Arc length of the step in cell i (NaN: none there).
  auto step_s = [&](int i) {
    if (i < 2 || i + 3 >= nb) return std::numeric_limits<double>::quiet_NaN();
    const double tr = stands_out(i, &BandSample::curvature_rail) ? detail::rail_step_fraction(out, i)
                                                                  : std::numeric_limits<double>::quiet_NaN();
    if (std::isfinite(tr)) return band[i].s + tr * h;
    const double tw = stands_out(i, &BandSample::curvature_wheel) ? detail::wheel_step_fraction(out, i)
                                                                   : std::numeric_limits<double>::quiet_NaN();
    return band[i].s + tw * h;  // NaN when neither steps
  };
  for (ContactPoint& p : out.points) {
    const double pos = (p.band_s - band.front().s) / h;
    if (!std::isfinite(pos)) continue;
    const int c = static_cast<int>(std::floor(pos));
    for (int i = c - 1; i <= c + 1; ++i) {  // the cells within half a step of the point
      const double st = step_s(i);
      if (std::abs(st - p.band_s) < 0.5 * h) {
        p.status |= status::kCurvatureStep;
        out.status |= status::kCurvatureStep;
        break;
      }
    }
  }
}

}  // namespace

ContactGeometrySolver::ContactGeometrySolver(ProfilePtr wheel_left, ProfilePtr rail_left,
                                             ProfilePtr wheel_right, ProfilePtr rail_right,
                                             TrackGeometry track, WheelsetGeometry wheelset,
                                             GeometrySettings settings)
    : wheel_{std::move(wheel_left), std::move(wheel_right)},
      rail_{std::move(rail_left), std::move(rail_right)},
      track_(track),
      wheelset_(wheelset),
      settings_(settings) {
  check_profile(wheel_[0], ProfileKind::wheel, "left wheel");
  check_profile(wheel_[1], ProfileKind::wheel, "right wheel");
  check_profile(rail_[0], ProfileKind::rail, "left rail");
  check_profile(rail_[1], ProfileKind::rail, "right rail");
  check_positive(track_.gauge, "track.gauge");
  check_positive(track_.gauge_measuring_depth, "track.gauge_measuring_depth");
  RAILTAB_CHECK(std::isfinite(track_.rail_inclination) && std::abs(track_.rail_inclination) < 1.0,
                "contact geometry: track.rail_inclination = {} must be finite with |value| < 1",
                track_.rail_inclination);
  check_positive(wheelset_.back_to_back, "wheelset.back_to_back");
  RAILTAB_CHECK(std::isfinite(wheelset_.flange_back_position),
                "contact geometry: wheelset.flange_back_position = {} is not finite",
                wheelset_.flange_back_position);
  check_positive(wheelset_.nominal_radius, "wheelset.nominal_radius");
  check_positive(settings_.search_step, "settings.search_step");
  RAILTAB_CHECK(std::isfinite(settings_.max_separation) && settings_.max_separation >= 0.0,
                "contact geometry: settings.max_separation = {} must be finite and >= 0",
                settings_.max_separation);
  check_positive(settings_.band_step, "settings.band_step");
  RAILTAB_CHECK(std::isfinite(settings_.band_half_width) && settings_.band_half_width >= 0.0,
                "contact geometry: settings.band_half_width = {} must be finite and >= 0",
                settings_.band_half_width);
  check_positive(settings_.band_max_gap, "settings.band_max_gap");
  RAILTAB_CHECK(std::isfinite(settings_.near_equal_shift) && settings_.near_equal_shift >= 0.0,
                "contact geometry: settings.near_equal_shift = {} must be finite and >= 0",
                settings_.near_equal_shift);
  RAILTAB_CHECK(std::isfinite(settings_.near_equal_distance) && settings_.near_equal_distance >= 0.0,
                "contact geometry: settings.near_equal_distance = {} must be finite and >= 0",
                settings_.near_equal_distance);
  RAILTAB_CHECK(std::isfinite(settings_.flange_angle),
                "contact geometry: settings.flange_angle = {} is not finite", settings_.flange_angle);

  // Sizes before any table is allocated: a profile wider than a few metres is a unit error, and
  // its tables would take gigabytes (docs/profiles.md "Limits").
  for (const ProfilePtr& p : {wheel_[0], wheel_[1], rail_[0], rail_[1]}) {
    RAILTAB_CHECK(p->t_max() - p->t_min() <= kMaxCurveLength,
                  "contact geometry: profile '{}' is {} m long along its curve, more than the limit "
                  "of {} m: wrong length unit?",
                  p->name(), p->t_max() - p->t_min(), kMaxCurveLength);
  }
  if (track_.rail_inclination != 0.0) {
    for (const ProfilePtr& p : {rail_[0], rail_[1]}) check_not_canted_twice(*p, track_.rail_inclination);
  }

  // The rail table must resolve the coarse search and the band; half their step is plenty for
  // cubic Hermite interpolation, and a floor keeps absurd settings from exhausting memory.
  const double table_step = std::max(0.5 * std::min(settings_.search_step, settings_.band_step), 2e-6);
  for (int i = 0; i < 2; ++i) {
    const bool shared_rail = i == 1 && rail_[1] == rail_[0];
    placed_rail_[i] = shared_rail ? placed_rail_[0]
                                  : std::make_shared<const detail::PlacedRail>(rail_[i], track_, table_step);
    const bool shared_wheel = i == 1 && wheel_[1] == wheel_[0];
    wheel_nodes_[i] = shared_wheel ? wheel_nodes_[0]
                                   : std::make_shared<const detail::WheelSamples>(
                                         *wheel_[i], std::max(settings_.search_step, 2e-6));
    rail_offset_q_[i] = placed_rail_[i]->offset_q();
    rail_offset_z_[i] = placed_rail_[i]->offset_z();
  }
}

WheelContactGeometry ContactGeometrySolver::solve_wheel(Side side, const WheelsetState& state) const {
  RAILTAB_CHECK(std::isfinite(state.y), "contact geometry: wheelset state y = {} is not finite", state.y);
  RAILTAB_CHECK(std::isfinite(state.roll), "contact geometry: wheelset state roll = {} is not finite",
                state.roll);
  RAILTAB_CHECK(std::isfinite(state.yaw) && std::abs(state.yaw) <= kMaxYaw,
                "contact geometry: wheelset state yaw = {} rad must be finite with |yaw| <= {} rad",
                state.yaw, kMaxYaw);
  const int i = static_cast<int>(side);
  const double sigma = outward_sign(side);
  const detail::PlacedRail& rail = *placed_rail_[i];
  const Profile& wheel = *wheel_[i];
  detail::WheelPose pose = detail::make_pose(side, state, wheelset_);
  const detail::SearchResult found =
      detail::search_contacts(rail, wheel, *wheel_nodes_[i], pose, settings_.max_separation);

  WheelContactGeometry out;
  out.side = side;
  out.wheel_drop = -found.gap_min;  // lower the wheel until the smallest gap closes
  out.wheel_roll = pose.theta;
  out.wheel_yaw = pose.psi;
  pose.zc += out.wheel_drop;
  out.points.reserve(found.minima.size());
  for (const detail::RawContact& m : found.minima) {
    const CurveSample ew = wheel.curve(m.wheel_t);
    const detail::RailPoint rp = rail.point(m.rail_t);
    ContactPoint cp{};
    cp.wheel_u = ew.y;
    cp.rail_u = rp.u;
    cp.wheel_t = m.wheel_t;
    cp.rail_t = m.rail_t;
    cp.y_track = sigma * rp.p.q;
    cp.z_track = rp.p.z;
    cp.contact_angle_side = rp.angle;
    cp.contact_angle = sigma * rp.angle;
    cp.rolling_radius = wheelset_.nominal_radius - ew.z;
    cp.separation = m.gap - found.gap_min;
    // Meusnier: the circumferential curvature of the wheel is cos(g_w)/r with g_w the normal's
    // angle to the wheel's own radial plane, i.e. the side-frame angle minus the wheel's roll.
    cp.curvature_a = 0.5 * std::cos(rp.angle - pose.theta) / cp.rolling_radius;
    const double slope_term = detail::speed_squared(ew);
    const double k_wheel = detail::curvature_numerator(ew) / (slope_term * std::sqrt(slope_term));  // convex: > 0
    cp.curvature_b = 0.5 * (k_wheel + rp.curvature);
    cp.status = 0;
    cp.x_track = 0.0;
    cp.x_wheel = 0.0;
    if (pose.yawed) {
      // A is half the wheel's normal curvature along track x, by Euler's formula between the
      // circumferential (Meusnier) and the meridional curvature: the rail's rolling direction
      // crosses the circle at the angle chi.
      const detail::TracePoint tp = pose.trace(ew);
      const double c2 = tp.cos_chi * tp.cos_chi;
      const double k_circ = ew.dy / (std::sqrt(slope_term) * cp.rolling_radius);
      cp.curvature_a = 0.5 * (k_circ * c2 + k_wheel * (1.0 - c2));
      cp.x_track = tp.x;
      cp.x_wheel = tp.x_wheel;
    }
    if (cp.contact_angle_side > settings_.flange_angle) cp.status |= status::kFlangeContact;
    if (!(cp.curvature_a > 0.0) || !(cp.curvature_b > 0.0)) cp.status |= status::kNonHertzian;
    if (m.edge) cp.status |= status::kProfileEdge;
    out.points.push_back(cp);
  }
  std::stable_sort(out.points.begin(), out.points.end(), [](const ContactPoint& a, const ContactPoint& b) {
    return a.separation < b.separation;
  });
  out.points.front().separation = 0.0;  // exactly: the drop is defined by it
  flag_near_equal_minima(settings_, out);

  const bool band_edge = detail::build_band(rail, wheel, pose, settings_, out);
  flag_curvature_steps(out);
  if (out.points.size() > 1) out.status |= status::kTwoPoint;
  const bool point_edge = std::any_of(out.points.begin(), out.points.end(), [](const ContactPoint& p) {
    return (p.status & status::kProfileEdge) != 0;
  });
  if (band_edge || point_edge) out.status |= status::kProfileEdge;
  return out;
}

WheelsetContactGeometry ContactGeometrySolver::solve(const WheelsetState& state) const {
  WheelsetContactGeometry result;
  result.wheels[0] = solve_wheel(Side::left, state);
  result.wheels[1] = solve_wheel(Side::right, state);
  result.rolling_radius_difference = result.wheels[0].points.front().rolling_radius -
                                     result.wheels[1].points.front().rolling_radius;
  return result;
}

}  // namespace railtab
