// SPDX-License-Identifier: Apache-2.0
// Gap band of one wheel at rigid contact: for rail points P(s), uniform in rail arc length s,
// the wheel point on the rail normal line P + t n and the normal gap t. The normal-contact
// models lay their strips along this band (overlap at approach dz: dz*cos(angle) - gap).
//
// The wheel point is found by Newton on cross(W(u) - P, n) = 0, continued from the neighbouring
// sample outward from the primary contact, so it follows the facing wheel surface.
#include <algorithm>
#include <cmath>

#include "geometry/placement.hpp"

namespace railtab::detail {
namespace {

enum class Facing { ok, wheel_edge, failed };

// Wheel curve parameter u on the normal line through rail point rp; u holds the start value.
Facing facing_wheel_point(const Profile& wheel, const WheelPose& pose, const RailPoint& rp,
                          const Point2& n, double& u) {
  int clamped = 0;
  for (int it = 0; it < 40; ++it) {
    const CurveSample e = wheel.curve(u);
    Point2 w, tangent;
    if (pose.yawed) {  // the silhouette; its tangent's length taken from the profile (a Newton slope)
      const TracePoint tp = pose.trace(e);
      const double speed = std::hypot(e.dy, e.dz);
      w = tp.p;
      tangent = {speed * std::cos(tp.angle), speed * std::sin(tp.angle)};
    } else {
      w = pose.place(e.y, e.z);
      tangent = pose.tangent(e.dy, e.dz);
    }
    const Point2 d{w.q - rp.p.q, w.z - rp.p.z};
    const double f = cross(d, n);
    const double df = cross(tangent, n);
    if (!(std::abs(df) > 1e-6)) return Facing::failed;  // normal tangent to the wheel
    double step = -f / df;
    step = std::clamp(step, -5e-3, 5e-3);
    double next = u + step;
    if (next < wheel.t_min() || next > wheel.t_max()) {
      next = std::clamp(next, wheel.t_min(), wheel.t_max());
      if (++clamped > 2) return Facing::wheel_edge;
    }
    const bool done = std::abs(next - u) < 1e-13;
    u = next;
    if (done) return Facing::ok;
  }
  return Facing::failed;
}

}  // namespace

bool build_band(const PlacedRail& rail, const Profile& wheel, const WheelPose& pose,
                const GeometrySettings& settings, WheelContactGeometry& out) {
  const double h = settings.band_step;
  const double s_primary = rail.s_at_t(out.points.front().rail_t);
  double s_first = s_primary, s_last = s_primary;
  for (ContactPoint& cp : out.points) {
    const double s = rail.s_at_t(cp.rail_t);
    cp.band_s = s - s_primary;
    s_first = std::min(s_first, s);
    s_last = std::max(s_last, s);
  }
  const double want_lo = s_first - settings.band_half_width;
  const double want_hi = s_last + settings.band_half_width;
  const bool rail_clipped_lo = want_lo < 0.0;
  const bool rail_clipped_hi = want_hi > rail.s_hi();
  const long k_lo = static_cast<long>(std::ceil((std::max(want_lo, 0.0) - s_primary) / h - 1e-9));
  const long k_hi = static_cast<long>(std::floor((std::min(want_hi, rail.s_hi()) - s_primary) / h + 1e-9));

  out.band_step = h;
  out.band.resize(static_cast<std::size_t>(k_hi - k_lo + 1));
  bool edge = false;

  // Walk from the primary contact in direction dir; returns the last k kept.
  auto walk = [&](long k_begin, long k_end, long dir) {
    double u = out.points.front().wheel_t;
    const double s_cut = dir > 0 ? s_last - s_primary : s_first - s_primary;
    long kept = k_begin - dir;
    for (long k = k_begin; dir > 0 ? k <= k_end : k >= k_end; k += dir) {
      const double s_rel = static_cast<double>(k) * h;
      const double s_abs = std::clamp(s_primary + s_rel, 0.0, rail.s_hi());
      const RailPoint rp = rail.point(std::clamp(rail.t_at_s(s_abs), rail.t_lo(), rail.t_hi()));
      const double norm = std::hypot(rp.tangent.q, rp.tangent.z);
      const Point2 n{-rp.tangent.z / norm, rp.tangent.q / norm};
      const Facing facing = facing_wheel_point(wheel, pose, rp, n, u);
      if (facing != Facing::ok) {
        // The wheel ends (or turns away) before the band does: a profile end if still close.
        const bool have_prev = dir < 0 || kept != k_begin - dir;  // k = 0 exists for dir < 0
        if (have_prev && out.band[static_cast<std::size_t>(kept - k_lo)].gap <= settings.band_max_gap) {
          edge = true;
        }
        break;
      }
      const CurveSample e = wheel.curve(u);
      const TracePoint tp = pose.yawed ? pose.trace(e) : TracePoint{};
      const Point2 w = pose.yawed ? tp.p : pose.place(e.y, e.z);
      const double gap = (w.q - rp.p.q) * n.q + (w.z - rp.p.z) * n.z;
      const bool beyond = dir > 0 ? s_rel > s_cut : s_rel < s_cut;
      if (beyond && gap > settings.band_max_gap) break;
      const double slope_term = speed_squared(e);
      BandSample& b = out.band[static_cast<std::size_t>(k - k_lo)];
      b.s = s_rel;
      b.rail_u = rp.u;
      b.wheel_u = e.y;
      b.q = rp.p.q;
      b.z = rp.p.z;
      b.contact_angle_side = rp.angle;
      b.gap = gap;
      b.rolling_radius = pose.r0 - e.z;
      b.curvature_wheel = curvature_numerator(e) / (slope_term * std::sqrt(slope_term));  // convex: > 0
      b.curvature_rail = rp.curvature;
      if (pose.yawed) {  // Euler: circumferential (Meusnier, N_r / r) and meridional curvatures
        const double k_circ = e.dy / (std::sqrt(slope_term) * b.rolling_radius);
        const double c2 = tp.cos_chi * tp.cos_chi;
        b.x_track = tp.x;
        b.x_wheel = tp.x_wheel;
        b.curvature_rolling = k_circ * c2 + b.curvature_wheel * (1.0 - c2);
      } else {
        b.x_track = 0.0;
        b.x_wheel = 0.0;
        b.curvature_rolling = std::cos(rp.angle - pose.theta) / b.rolling_radius;
      }
      kept = k;
    }
    // Reaching the requested extent while the rail has ended is a profile edge too.
    if (kept == k_end) {
      const BandSample& b = out.band[static_cast<std::size_t>(kept - k_lo)];
      const bool clipped = dir > 0 ? rail_clipped_hi : rail_clipped_lo;
      if (clipped && b.gap <= settings.band_max_gap) edge = true;
    }
    return kept;
  };
  const long last_kept = walk(0, k_hi, +1);
  const long first_kept = k_lo <= -1 ? walk(-1, k_lo, -1) : 0;
  const auto begin = out.band.begin();
  out.band.erase(begin + (last_kept - k_lo + 1), out.band.end());
  out.band.erase(out.band.begin(), out.band.begin() + (first_kept - k_lo));
  return edge;
}

}  // namespace railtab::detail
