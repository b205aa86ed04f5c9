// SPDX-License-Identifier: Apache-2.0
// Entry points and dispatch of the normal-contact layer: model names, preparation of the contact
// points, the per-model dispatch (evaluate) and the solve at a given approach. The band machinery
// is in normal_band.cpp, the run weights in run_weights.cpp, the patch assembly in
// patch_assembly.cpp and the load control in load_control.cpp.
//
// Shared rigid approach (docs/conventions.md "Normal contact"): all patches of one wheel move with
// one vertical approach delta_z; point i (separation h_i, contact angle g_i) is penetrated by
// delta_i = (delta_z - h_i) cos g_i. Along the gap band the VI overlap of the patch of point i is
//   STRIPES (patch follows the contact angle):  v(s) = eps delta_z cos g(s) - gap(s) + (1 - eps) h_i cos g(s)
//   Linder, KP (planar, reference normal):      v(s) = eps (delta_z - h_i) cos g_i - (gap(s) - h_i cos g_i)
// For the primary point (h = 0) the first line is eps delta_z cos g(s) - gap(s). The h_i terms make a
// secondary patch appear exactly when delta_z passes h_i (as for Hertz) and not at h_i/eps: the
// fraction eps scales the penetration of the patch, not the rigid separation (FACTS 2.1).
#include "normal/normal_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "core/check.hpp"
#include "core/root_find.hpp"
#include "normal/normal_internal.hpp"
#include "geometry/overlap_reference.hpp"

namespace railtab {

const char* to_string(NormalModel model) {
  switch (model) {
    case NormalModel::hertz: return "hertz";
    case NormalModel::linder: return "linder";
    case NormalModel::kik_piotrowski: return "kik-piotrowski";
    case NormalModel::stripes_a: return "stripes-a";
    case NormalModel::stripes_ab: return "stripes-ab";
    case NormalModel::halfspace: return "halfspace";
  }
  return "unknown";
}

NormalModel parse_normal_model(std::string_view name) {
  for (NormalModel m : {NormalModel::hertz, NormalModel::linder, NormalModel::kik_piotrowski,
                        NormalModel::stripes_a, NormalModel::stripes_ab, NormalModel::halfspace}) {
    if (name == to_string(m)) return m;
  }
  throw Error(fmt::format(
      "unknown normal model '{}' (expected hertz, linder, kik-piotrowski, stripes-a, stripes-ab, halfspace)",
      name));
}

const char* to_string(NegativeCurvature treatment) {
  return treatment == NegativeCurvature::shift ? "shift" : "clip-and-smooth";
}

NegativeCurvature parse_negative_curvature(std::string_view name) {
  if (name == "shift") return NegativeCurvature::shift;
  if (name == "clip-and-smooth") return NegativeCurvature::clip_and_smooth;
  throw Error(fmt::format(
      "unknown negative-curvature treatment '{}' (expected shift, clip-and-smooth)", name));
}

namespace detail {

Workspace& thread_workspace() {
  thread_local Workspace workspace;  // per-thread scratch: the hot loop allocates nothing
  return workspace;
}

namespace {

constexpr StatusBits kPointBits =
    status::kFlangeContact | status::kNonHertzian | status::kProfileEdge;

}  // namespace

void prepare(const WheelContactGeometry& g, const Material& m, const NormalOptions& o,
             Workspace& w) {
  const int np = static_cast<int>(g.points.size());
  const int nb = static_cast<int>(g.band.size());
  w.points.assign(np, PointContext{});
  w.grp_lead = -1;  // the STRIPES run integral belongs to the previous solve
  if (static_cast<int>(w.hertz_cache.size()) < np) w.hertz_cache.resize(np);
  const bool band_ok = nb >= 2 && g.band_step > 0.0 && std::isfinite(g.band_step);
  if (band_ok) {
    w.cos_angle.resize(nb);
    w.A.resize(nb);
    w.q.resize(nb);
    w.B_treated.resize(nb);
    w.v.resize(nb);
    w.cosb.resize(nb);
    w.weight.resize(nb);
    w.A_int.resize(nb);
    w.A_grp.resize(nb);
  }
  w.strip_len.resize(std::max(o.strips, 1));
  w.strip_pos.resize(std::max(o.strips, 1));
  w.strip_A.resize(std::max(o.strips, 1));
  w.strip_v.resize(std::max(o.strips, 1));
  w.strip_c.resize(std::max(o.strips, 1));
  w.strip_F.resize(std::max(o.strips, 1) + 1);
  w.refs.resize(std::max(np, 1));
  w.log_arg.resize(8 * std::max(o.strips, 1));  // two references at a time (stripes.cpp)
  w.log_coef.resize(8 * std::max(o.strips, 1));

  for (int i = 0; i < np; ++i) {
    const ContactPoint& cp = g.points[i];
    PointContext& p = w.points[i];
    p.point = i;
    p.model = o.model;
    p.h = std::max(cp.separation, 0.0);
    p.cos_ref = std::cos(cp.contact_angle_side);
    if (!(p.cos_ref > 1e-6)) p.cos_ref = 1e-6;  // a vertical wall cannot carry vertical load
    p.A0 = cp.curvature_a;
    p.B0 = cp.curvature_b;
    p.B0t = p.B0;
    p.r_ref = cp.rolling_radius;
    p.eps = o.virtual_penetration;
    p.flags = cp.status & kPointBits;
    if (band_ok) {
      const double pos = band_position(g, cp.band_s);
      if (std::isfinite(pos)) p.i0 = std::clamp(static_cast<int>(std::lround(pos)), 0, nb - 1);
    }
  }
  // Band domains (only the VI models use them; Hertz needs none): consecutive points (by band
  // position) split at the largest gap between them.
  bool vi_possible = o.model != NormalModel::hertz;
  for (const PointContext& p : w.points)
    vi_possible = vi_possible ||
                  !(std::isfinite(p.A0) && std::isfinite(p.B0) && p.A0 > 0.0 && p.B0 > 0.0);
  if (band_ok && vi_possible) {
    std::vector<int> order;  // small (<= a few points); allocation outside the load loop
    order.reserve(np);
    for (int i = 0; i < np; ++i)
      if (w.points[i].i0 >= 0) order.push_back(i);
    std::sort(order.begin(), order.end(),
              [&](int a, int b) { return w.points[a].i0 < w.points[b].i0; });
    // The continuous split (planar models' run ends, find_run): the vertex of the parabola
    // through the gap at the largest-gap sample and its neighbours, within half a step of it.
    // The sample index alone jumps by a band step when the saddle moves past a sample, and a run
    // cut there lost or gained a whole cell of overlap (Car7216 / avg_HR, Linder: area 84.40 ->
    // 83.30 mm2 between y = -2.510 and -2.505 mm). At an index switch (equal gaps at j, j + 1)
    // both parabolas give s_j + h/2: continuous. Only for a saddle strictly between the points.
    auto saddle_s = [&](int split, int i_lo, int i_hi) {
      if (!(split > i_lo && split < i_hi)) return std::numeric_limits<double>::quiet_NaN();
      const double gm = g.band[split - 1].gap, g0 = g.band[split].gap, gp = g.band[split + 1].gap;
      const double d2 = gm - 2.0 * g0 + gp;
      const double off = d2 < 0.0 ? std::clamp(0.5 * (gm - gp) / d2, -0.5, 0.5) : 0.0;
      return g.band[split].s + off * g.band_step;
    };
    for (std::size_t k = 0; k < order.size(); ++k) {
      PointContext& p = w.points[order[k]];
      p.lo = 0;
      p.hi = nb - 1;
      p.s_lo_split = std::numeric_limits<double>::quiet_NaN();
      p.s_hi_split = std::numeric_limits<double>::quiet_NaN();
      if (k > 0) {
        const PointContext& q = w.points[order[k - 1]];
        if (q.i0 == p.i0) {  // the same spot twice: the first point owns it
          p.lo = 1;
          p.hi = 0;
          continue;
        }
        int split = q.i0 + 1;
        for (int j = q.i0 + 1; j < p.i0; ++j)
          if (g.band[j].gap > g.band[split].gap) split = j;
        p.lo = std::min(split + 1, p.i0);
        p.s_lo_split = saddle_s(split, q.i0, p.i0);
      }
      if (k + 1 < order.size()) {
        const PointContext& q = w.points[order[k + 1]];
        if (q.i0 != p.i0) {
          int split = p.i0 + 1;
          for (int j = p.i0 + 1; j < q.i0; ++j)
            if (g.band[j].gap > g.band[split].gap) split = j;
          p.hi = std::max(split, p.i0);
          p.s_hi_split = saddle_s(split, p.i0, q.i0);
        }
      }
    }
  }
  for (PointContext& p : w.points) {
    p.hertz_valid = std::isfinite(p.A0) && std::isfinite(p.B0) && p.A0 > 0.0 && p.B0 > 0.0;
    if (!p.hertz_valid) p.flags |= status::kNonHertzian;
    const bool vi = o.model != NormalModel::hertz;
    if (vi && p.i0 < 0) {
      // No gap band: the VI models cannot run; Hertz at the point instead.
      p.model = NormalModel::hertz;
      p.flags |= status::kFallbackModel;
    }
    if (p.model == NormalModel::hertz && !p.hertz_valid) {
      if (p.i0 >= 0) {
        // Hertz cannot run with A or B <= 0. Kik-Piotrowski needs no positive curvature (patch from
        // the real separation, load from the Boussinesq condition, FACTS 2.3): fall back to it.
        p.model = NormalModel::kik_piotrowski;
        p.flags |= status::kFallbackModel;
      } else {
        // Nothing else available: Hertz with the curvatures clipped to a small positive floor.
        p.A0 = std::max(p.A0, 1e-3);
        p.B0 = std::max(p.B0, o.min_curvature_ratio * p.A0);
        p.B0t = p.B0;
        p.hertz_valid = true;
        p.flags |= status::kFallbackModel | status::kCurvatureClipped;
      }
    }
    if (is_stripes(p.model) && !(p.A0 > 0.0)) {
      p.model = NormalModel::kik_piotrowski;
      p.flags |= status::kFallbackModel;
    }
    if (p.hertz_valid) {
      // Cached per point index: repeated solves on one geometry (load sweeps) find the shape once.
      Workspace::HertzCache& hc = w.hertz_cache[p.point];
      if (!(hc.A == p.A0 && hc.B == p.B0)) hc = {p.A0, p.B0, hertz_coefficients_fast(p.A0, p.B0)};
      p.hz = hc.hz;
    }
    if (is_stripes(p.model)) prepare_stripes(g, m, o, p, w);
  }
  // Per-sample data is filled lazily on the intervals of each PointContext (empty after assign).
  // Run weights (run_weights): neighbouring points by band position and the sample of the largest
  // rigid gap between each pair (geometry only, where their overlap runs join last).
  w.order.clear();
  w.saddle.clear();
  if (band_ok && np >= 2) {
    for (int i = 0; i < np; ++i)
      if (w.points[i].i0 >= 0) w.order.push_back(i);
    std::sort(w.order.begin(), w.order.end(), [&](int a, int b) {
      return w.points[a].i0 < w.points[b].i0 || (w.points[a].i0 == w.points[b].i0 && a < b);
    });
    for (std::size_t k = 0; k + 1 < w.order.size(); ++k) {
      const int j0 = w.points[w.order[k]].i0, j1 = w.points[w.order[k + 1]].i0;
      int split = j0;
      for (int j = j0; j <= j1; ++j)
        if (g.band[j].gap > g.band[split].gap) split = j;
      w.saddle.push_back(split);
    }
  }
}

PatchSums evaluate(const WheelContactGeometry& g, const Material& m, const NormalOptions& o,
                   PointContext& p, Workspace& w, double dz, ContactPatch* out) {
  if (out) {
    const ContactPoint& cp = g.points[p.point];
    *out = ContactPatch{};
    out->point_index = p.point;
    out->model = p.model;
    out->band_s = cp.band_s;
    out->contact_angle = cp.contact_angle;
    out->rolling_radius = cp.rolling_radius;
    out->wheel_u = cp.wheel_u;
    out->rail_u = cp.rail_u;
    out->status = p.flags;
  }
  PatchSums sums;
  if (dz > p.h) {
    switch (p.model) {
      case NormalModel::hertz: sums = hertz_patch(g, m, o, p, w, dz, out); break;
      case NormalModel::linder: sums = linder_patch(g, m, o, p, w, dz, out); break;
      case NormalModel::kik_piotrowski: sums = kik_piotrowski_patch(g, m, o, p, w, dz, out); break;
      case NormalModel::stripes_a:
      case NormalModel::stripes_ab: sums = stripes_patch(g, m, o, p, w, dz, out); break;
      case NormalModel::halfspace: break;  // refused by check_options
    }
  }
  if (!(sums.normal > 0.0) || !std::isfinite(sums.normal)) sums = PatchSums{};
  if (out) {
    out->penetration = std::max(dz - p.h, 0.0) * p.cos_ref;
    if (sums.normal <= 0.0) {
      out->strips.clear();
      out->normal_force = out->area = out->max_pressure = 0.0;
      out->semi_axis_a = out->semi_axis_b = 0.0;
      out->status |= status::kLiftOff;
    }
  }
  return sums;
}

double carried_load(const WheelContactGeometry& g, const Material& m, const NormalOptions& o,
                     Workspace& w, double dz) {
  run_weights(g, w, dz);
  double total = 0.0;
  for (PointContext& p : w.points) total += evaluate(g, m, o, p, w, dz, nullptr).vertical;
  return total;
}

void check_options(const NormalOptions& o) {
  RAILTAB_CHECK(o.model != NormalModel::halfspace,
                "normal model 'halfspace' is solved by halfspace::solve_halfspace_for_load "
                "(src/halfspace/wheel_rail.hpp), not by the fast normal layer");
  RAILTAB_CHECK(o.strips >= 1 && o.strips <= 100000, "normal options: strips = {} must be >= 1",
                o.strips);
  RAILTAB_CHECK(o.virtual_penetration > 0.0 && o.virtual_penetration <= 1.0,
                "normal options: virtual_penetration = {} not in (0, 1]", o.virtual_penetration);
  RAILTAB_CHECK(o.tolerance > 0.0 && o.max_iterations >= 1,
                "normal options: tolerance = {}, max_iterations = {}", o.tolerance,
                o.max_iterations);
  RAILTAB_CHECK(o.min_curvature_ratio > 0.0, "normal options: min_curvature_ratio = {} must be > 0",
                o.min_curvature_ratio);
}

WheelNormalResult lift_off(const WheelContactGeometry& g, StatusBits extra) {
  WheelNormalResult r;
  r.point_patch.assign(g.points.size(), -1);
  r.status = status::kLiftOff | extra;
  return r;
}

}  // namespace detail

WheelNormalResult solve_normal_for_approach(const WheelContactGeometry& geometry,
                                            double vertical_approach, const Material& material,
                                            const NormalOptions& options) {
  WheelNormalResult r;
  solve_normal_for_approach(geometry, vertical_approach, material, options, r);
  return r;
}

void solve_normal_for_approach(const WheelContactGeometry& geometry, double vertical_approach,
                               const Material& material, const NormalOptions& options,
                               WheelNormalResult& r) {
  detail::check_options(options);
  if (!std::isfinite(vertical_approach)) {
    r = detail::lift_off(geometry, status::kInvalidInput);
    return;
  }
  if (geometry.points.empty() || vertical_approach <= 0.0) {
    r = detail::lift_off(geometry, status::kConverged);
    r.vertical_approach = vertical_approach;
    return;
  }
  detail::Workspace& w = detail::thread_workspace();
  detail::prepare(geometry, material, options, w);
  detail::fill(geometry, material, options, w, vertical_approach, r);
  r.status |= status::kConverged;
}

}  // namespace railtab
