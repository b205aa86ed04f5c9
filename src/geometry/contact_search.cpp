// SPDX-License-Identifier: Apache-2.0
// Rigid contact search of one wheel on its rail: local minima of the vertical gap.
//
// Both profiles are parametric curves (t = u for function profiles; placement.hpp).
// Coarse stage: the wheel nodes (uniform in wheel t, step search_step) are placed in the side
// frame and compared with the tabulated rail (cubic Hermite in q); every local minimum of the
// sampled gap is a candidate, so a second (flange) contact is never hidden behind the first.
// Fine stage: each candidate is refined on the exact curves by a safeguarded Newton iteration
// on the angle difference between wheel and rail tangents (zero at a stationary gap), bracketed
// by the neighbouring nodes; golden-section on the gap itself if the bracket has no sign change.
#include <algorithm>
#include <cmath>

#include "core/check.hpp"
#include "geometry/placement.hpp"

namespace railtab::detail {
namespace {

struct GapEval {
  double g;       // vertical gap wheel - rail at drop 0 [m]
  double phi;     // tangent angle wheel - rail; sign of dg/dq [rad]
  double dphi;    // d(phi)/dt_wheel [1/m]
  double rail_t;  // rail point below the wheel point (curve parameter) [m]
};

GapEval eval_gap(const PlacedRail& rail, const Profile& wheel, const WheelPose& pose, double u) {
  const CurveSample e = wheel.curve(u);
  if (pose.yawed) {  // the silhouette; dphi keeps the yaw-free curvature (a Newton slope only)
    const TracePoint tp = pose.trace(e);
    const double q = std::clamp(tp.p.q, rail.q_lo(), rail.q_hi());
    const double ur = rail.t_at_q(q);
    const RailPoint rp = rail.point(ur);
    const Point2 tw = pose.tangent(e.dy, e.dz);
    return {tp.p.z - rp.p.z, tp.angle - rp.angle,
            curvature_numerator(e) / speed_squared(e) - rp.dangle_dt * (tw.q / rp.tangent.q), ur};
  }
  const Point2 w = pose.place(e.y, e.z);
  const double q = std::clamp(w.q, rail.q_lo(), rail.q_hi());
  const double ur = rail.t_at_q(q);
  const RailPoint rp = rail.point(ur);
  const Point2 tw = pose.tangent(e.dy, e.dz);
  GapEval r;
  r.g = w.z - rp.p.z;
  r.phi = pose.theta + tangent_angle(e.dy, e.dz) - rp.angle;
  r.dphi = curvature_numerator(e) / speed_squared(e) - rp.dangle_dt * (tw.q / rp.tangent.q);
  r.rail_t = ur;
  return r;
}

// Minimum of the gap inside [a, b] (wheel u): safeguarded Newton on phi, or golden section.
RawContact refine(const PlacedRail& rail, const Profile& wheel, const WheelPose& pose, double a,
                  double b, double start) {
  constexpr double kTol = 1e-11;  // [m] in wheel t
  const GapEval fa = eval_gap(rail, wheel, pose, a);
  const GapEval fb = eval_gap(rail, wheel, pose, b);
  if (fa.phi < 0.0 && fb.phi > 0.0) {
    double lo = a, hi = b;
    double u = start;
    GapEval f = eval_gap(rail, wheel, pose, u);
    for (int it = 0; it < 100; ++it) {
      if (f.phi < 0.0) lo = u; else hi = u;
      double next = (f.dphi > 0.0) ? u - f.phi / f.dphi : 0.5 * (lo + hi);
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      const double step = std::abs(next - u);
      u = next;
      f = eval_gap(rail, wheel, pose, u);
      if (step < kTol || hi - lo < kTol) break;
    }
    return {u, f.rail_t, f.g, false};
  }
  // No sign change (cusp or very flat gap): golden section on the gap.
  const double ratio = 0.5 * (3.0 - std::sqrt(5.0));
  double x1 = a + ratio * (b - a), x2 = b - ratio * (b - a);
  double g1 = eval_gap(rail, wheel, pose, x1).g, g2 = eval_gap(rail, wheel, pose, x2).g;
  while (b - a > kTol) {
    if (g1 < g2) {
      b = x2; x2 = x1; g2 = g1;
      x1 = a + ratio * (b - a);
      g1 = eval_gap(rail, wheel, pose, x1).g;
    } else {
      a = x1; x1 = x2; g1 = g2;
      x2 = b - ratio * (b - a);
      g2 = eval_gap(rail, wheel, pose, x2).g;
    }
  }
  const GapEval f = eval_gap(rail, wheel, pose, 0.5 * (a + b));
  return {0.5 * (a + b), f.rail_t, f.g, false};
}

struct Candidate {
  int i;      // wheel node
  double g;   // coarse gap [m]
  bool edge;  // at the end of the searchable range
};

}  // namespace

SearchResult search_contacts(const PlacedRail& rail, const Profile& wheel,
                             const WheelSamples& samples, const WheelPose& pose,
                             double max_separation) {
  const int n = samples.size();
  // Branch of the wheel around its running circle on which q increases with u: beyond a fold
  // (the flange back turned by the roll) the wheel surface faces away from the rail.
  const int i0 = samples.i_running;
  auto dq_du = [&](int i) { return pose.cos_t * samples.dy[i] - pose.sin_t * samples.dz[i]; };
  int lo = i0, hi = i0;
  while (lo > 0 && dq_du(lo - 1) > 1e-3) --lo;
  while (hi < n - 1 && dq_du(hi + 1) > 1e-3) ++hi;

  // Coarse gap, streamed; candidates are the local minima of the sampled gap.
  Candidate cand[16];
  int n_cand = 0;
  int hint = 0;
  int first = -1, last = -1;
  int i_prev = -1;
  double g_prev = 0.0, g_prev2 = 0.0;
  double g_min = HUGE_VAL;
  auto add = [&](int i, double g, bool edge) {
    if (n_cand < 16) {
      cand[n_cand++] = {i, g, edge};
    } else {  // keep the lowest 16
      Candidate* worst = std::max_element(cand, cand + 16, [](const Candidate& x, const Candidate& y) {
        return x.g < y.g;
      });
      if (g < worst->g) *worst = {i, g, edge};
    }
  };
  for (int i = lo; i <= hi; ++i) {
    const Point2 w = pose.yawed ? pose.trace(samples.at(i)).p : pose.place(samples.y[i], samples.z[i]);
    if (w.q < rail.q_lo()) continue;
    if (w.q > rail.q_hi()) break;
    const double g = w.z - rail.z_at_q_table(w.q, hint);
    g_min = std::min(g_min, g);
    if (first < 0) {
      first = i;
    } else if (i_prev == first) {
      if (g_prev < g) add(i_prev, g_prev, true);
    } else if (g_prev < g_prev2 && g_prev <= g) {
      add(i_prev, g_prev, false);
    }
    g_prev2 = g_prev;
    g_prev = g;
    i_prev = i;
    last = i;
  }
  RAILTAB_CHECK(first >= 0 && last > first,
                "wheel '{}' does not overlap its rail laterally (wheel off the rail): wheelset "
                "shift {} m, roll {} rad in the side frame",
                wheel.name(), pose.qc, pose.theta);
  if (g_prev < g_prev2) add(last, g_prev, true);

  SearchResult result;
  result.minima.reserve(4);
  result.gap_min = HUGE_VAL;
  // A node can miss a minimum's depth by about g''*h^2/2; refine generously, filter exactly.
  const double coarse_margin = 1e-5;
  for (int k = 0; k < n_cand; ++k) {
    const Candidate& c = cand[k];
    if (c.g - g_min > max_separation + coarse_margin) continue;
    RawContact rc;
    if (c.edge) {
      const double u = samples.t(c.i);
      const GapEval f = eval_gap(rail, wheel, pose, u);
      rc = {u, f.rail_t, f.g, true};
    } else {
      rc = refine(rail, wheel, pose, samples.t(c.i - 1), samples.t(c.i + 1), samples.t(c.i));
    }
    if (!std::isfinite(rc.gap)) continue;  // absurd coordinates (checked by the readers too)
    const bool duplicate = std::any_of(result.minima.begin(), result.minima.end(), [&](const RawContact& m) {
      return std::abs(m.wheel_t - rc.wheel_t) < 1e-9;
    });
    if (duplicate) continue;
    result.minima.push_back(rc);
    result.gap_min = std::min(result.gap_min, rc.gap);
  }
  std::erase_if(result.minima, [&](const RawContact& m) {
    return m.gap - result.gap_min > max_separation;
  });
  RAILTAB_CHECK(!result.minima.empty(),
                "wheel '{}' on its rail: no contact point found (wheelset shift {} m, roll {} rad in "
                "the side frame); are the profile coordinates plausible?",
                wheel.name(), pose.qc, pose.theta);
  return result;
}

}  // namespace railtab::detail
