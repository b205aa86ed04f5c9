// Entry points of the normal-contact layer: preparation of the contact points, the shared band
// machinery of the virtual-interpenetration (VI) models and the load control.
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
  }
  return "unknown";
}

NormalModel parse_normal_model(std::string_view name) {
  for (NormalModel m : {NormalModel::hertz, NormalModel::linder, NormalModel::kik_piotrowski,
                        NormalModel::stripes_a, NormalModel::stripes_ab}) {
    if (name == to_string(m)) return m;
  }
  throw Error(fmt::format(
      "unknown normal model '{}' (expected hertz, linder, kik-piotrowski, stripes-a, stripes-ab)",
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

bool is_stripes(NormalModel m) {
  return m == NormalModel::stripes_a || m == NormalModel::stripes_ab;
}

double band_position(const WheelContactGeometry& g, double s) {
  return (s - g.band.front().s) / g.band_step;
}

}  // namespace


namespace {

// One sample j of point p: cos (already ready for STRIPES), A and q.
inline void compute_sample(const WheelContactGeometry& g, const PointContext& p, Workspace& w,
                           int j, const NormalOptions& o) {
  const BandSample& b = g.band[j];
  const double radius = b.rolling_radius > 0.0 ? b.rolling_radius : p.r_ref;
  const double scale_r = p.r_ref > 0.0 ? p.r_ref / radius : 1.0;
  if (is_stripes(p.model)) {
    // Local A from the local radius and contact angle (Meusnier, conventions "Contact frame"),
    // scaled so that it equals the geometry's A at the point.
    const double A = p.A0 * scale_r * w.cos_angle[j] / p.cos_ref;
    const double B = std::max(w.B_treated[j], o.min_curvature_ratio * p.A0);
    const double ratio = std::min(A, B) / std::max(A, B);
    const double gr = hertz_axis_ratio_fast(ratio);
    // (b/a)^2 of the local Hertz ellipse: the long axis lies along the smaller curvature.
    const double q = A <= B ? gr * gr : 1.0 / (gr * gr);
    w.q[j] = q;
    // Seed 000: A-correction A_c = (n/m)^2 B; A&B-correction A_c = (A + B)(n/m)^2 / (1 + (n/m)^2).
    w.A[j] = p.model == NormalModel::stripes_a ? q * B : (A + B) * q / (1.0 + q);
  } else {
    w.A[j] = p.A0 * scale_r;  // planar models: A from the local rolling radius
    w.q[j] = 0.0;
  }
}

// Samples [a, b] of point p (a <= b): as compute_sample for each, with the local Hertz shapes of
// STRIPES computed together (hertz_axis_ratio_fast_n: the same numbers).
inline void compute_samples(const WheelContactGeometry& g, const PointContext& p, Workspace& w,
                            int a, int b, const NormalOptions& o) {
  if (!is_stripes(p.model)) {
    for (int j = a; j <= b; ++j) compute_sample(g, p, w, j, o);
    return;
  }
  double* Aw = w.A.data();
  double* qw = w.q.data();
  const double Bfloor = o.min_curvature_ratio * p.A0;
  const double* cw = w.cos_angle.data();
  const double* Bt = w.B_treated.data();
  // Two samples per SSE2 step, the same operations (std::max(x, y) = maxpd(y, x), std::min(x, y)
  // = minpd(y, x), NaNs included), then the scalar loop for the rest.
  int j1 = a;
#if defined(__SSE2__)
  {
    const __m128d vr = _mm_set1_pd(p.r_ref), vA0 = _mm_set1_pd(p.A0),
                  vcr = _mm_set1_pd(p.cos_ref), vBf = _mm_set1_pd(Bfloor),
                  zero = _mm_setzero_pd(), one = _mm_set1_pd(1.0);
    const bool r_pos = p.r_ref > 0.0;
    for (; j1 + 1 <= b; j1 += 2) {
      const __m128d rr = _mm_set_pd(g.band[j1 + 1].rolling_radius, g.band[j1].rolling_radius);
      const __m128d pos = _mm_cmpgt_pd(rr, zero);
      const __m128d radius = _mm_or_pd(_mm_and_pd(pos, rr), _mm_andnot_pd(pos, vr));
      const __m128d scale_r = r_pos ? _mm_div_pd(vr, radius) : one;
      const __m128d A =
          _mm_div_pd(_mm_mul_pd(_mm_mul_pd(vA0, scale_r), _mm_loadu_pd(cw + j1)), vcr);
      const __m128d B = _mm_max_pd(vBf, _mm_loadu_pd(Bt + j1));
      _mm_storeu_pd(Aw + j1, A);
      _mm_storeu_pd(qw + j1, _mm_div_pd(_mm_min_pd(B, A), _mm_max_pd(B, A)));
    }
  }
#endif
  for (int j = j1; j <= b; ++j) {  // local A, and the curvature ratio in q
    const BandSample& bs = g.band[j];
    const double radius = bs.rolling_radius > 0.0 ? bs.rolling_radius : p.r_ref;
    const double scale_r = p.r_ref > 0.0 ? p.r_ref / radius : 1.0;
    const double A = p.A0 * scale_r * w.cos_angle[j] / p.cos_ref;
    const double B = std::max(w.B_treated[j], Bfloor);
    Aw[j] = A;
    qw[j] = std::min(A, B) / std::max(A, B);
  }
  hertz_axis_ratio_fast_n(qw + a, b - a + 1);
  const bool corr_a = p.model == NormalModel::stripes_a;
  int j3 = a;
#if defined(__SSE2__)
  {
    const __m128d vBf = _mm_set1_pd(Bfloor), one = _mm_set1_pd(1.0);
    for (; j3 + 1 <= b; j3 += 2) {
      const __m128d A = _mm_loadu_pd(Aw + j3);
      const __m128d B = _mm_max_pd(vBf, _mm_loadu_pd(Bt + j3));
      const __m128d gr = _mm_loadu_pd(qw + j3);
      const __m128d g2 = _mm_mul_pd(gr, gr);
      const __m128d le = _mm_cmple_pd(A, B);
      const __m128d q = _mm_or_pd(_mm_and_pd(le, g2), _mm_andnot_pd(le, _mm_div_pd(one, g2)));
      _mm_storeu_pd(qw + j3, q);
      _mm_storeu_pd(Aw + j3, corr_a ? _mm_mul_pd(q, B)
                                    : _mm_div_pd(_mm_mul_pd(_mm_add_pd(A, B), q),
                                                 _mm_add_pd(one, q)));
    }
  }
#endif
  for (int j = j3; j <= b; ++j) {
    const double A = Aw[j];
    const double B = std::max(w.B_treated[j], Bfloor);
    const double gr = qw[j];
    const double q = A <= B ? gr * gr : 1.0 / (gr * gr);
    qw[j] = q;
    Aw[j] = corr_a ? q * B : (A + B) * q / (1.0 + q);
  }
}

// Grows the ready interval [*lo, *hi] to cover [j0, j1] (contiguous: the gap in between too),
// calling fn(j) for every new sample.
template <class Fn>
inline void grow(int* lo, int* hi, int j0, int j1, Fn&& fn) {
  if (*lo > *hi) {
    for (int j = j0; j <= j1; ++j) fn(j);
    *lo = j0;
    *hi = j1;
    return;
  }
  for (int j = std::min(j0, *lo); j < *lo; ++j) fn(j);
  for (int j = *hi + 1; j <= std::max(j1, *hi); ++j) fn(j);
  *lo = std::min(*lo, j0);
  *hi = std::max(*hi, j1);
}

// As grow, calling fn(a, b) for the (at most two) new contiguous ranges.
template <class Fn>
inline void grow_ranges(int* lo, int* hi, int j0, int j1, Fn&& fn) {
  if (*lo > *hi) {
    if (j0 <= j1) fn(j0, j1);
    *lo = j0;
    *hi = j1;
    return;
  }
  if (std::min(j0, *lo) < *lo) fn(std::min(j0, *lo), *lo - 1);
  if (*hi + 1 <= std::max(j1, *hi)) fn(*hi + 1, std::max(j1, *hi));
  *lo = std::min(*lo, j0);
  *hi = std::max(*hi, j1);
}

}  // namespace

void extend_cos(const WheelContactGeometry& g, PointContext& p, Workspace& w, int j0, int j1) {
  double* c = w.cos_angle.data();
  const BandSample* band = g.band.data();
  grow(&p.cos_lo, &p.cos_hi, j0, j1, [&](int j) { c[j] = band_cos(band[j].contact_angle); });
}

void extend_samples(const WheelContactGeometry& g, PointContext& p, Workspace& w, int j0, int j1,
                    const NormalOptions& o) {
  if (is_stripes(p.model)) ensure_cos(g, p, w, j0, j1);
  grow_ranges(&p.smp_lo, &p.smp_hi, j0, j1,
              [&](int a, int b) { compute_samples(g, p, w, a, b, o); });
}

void point_A_integral(const WheelContactGeometry& g, PointContext& p, Workspace& w) {
  // Running integral of A over the ready samples (trapezoids, exact for the linear interpolant),
  // from smp_lo: STRIPES averages A over each strip (stripes.cpp). Kept while smp_lo stays, only
  // extended (the same sums).
  double* A_int = w.A_int.data();
  const double* A = w.A.data();
  const double half_h = 0.5 * g.band_step;
  int from = p.smp_lo;
  if (p.aint_lo == p.smp_lo && p.aint_hi >= p.aint_lo) {
    from = p.aint_hi;
  } else {
    A_int[p.smp_lo] = 0.0;
  }
  for (int j = from; j < p.smp_hi; ++j) A_int[j + 1] = A_int[j] + half_h * (A[j] + A[j + 1]);
  p.aint_lo = p.smp_lo;
  p.aint_hi = std::max(p.smp_hi, from);
}

namespace {

// Scans the run of positive overlap(j) outward from i0 inside [lo, hi]; overlap stores v[j].
template <class Overlap>
inline Run scan_run(const WheelContactGeometry& g, int i0, int lo, int hi, Overlap&& overlap) {
  Run run;
  const double v0 = overlap(i0);
  if (!(v0 > 0.0)) return run;
  run.loaded = true;
  double vmax = v0;
  const BandSample* band = g.band.data();
  const double step = g.band_step;
  int j = i0;
  double vj = v0;
  for (;;) {
    if (j == lo) {
      run.s_lo = band[j].s;
      run.at_band_end = j == 0;
      break;
    }
    const double vn = overlap(j - 1);
    if (!(vn > 0.0)) {
      run.s_lo = band[j].s - step * vj / (vj - vn);
      break;
    }
    --j;
    vj = vn;
    vmax = std::max(vmax, vn);
  }
  j = i0;
  vj = v0;
  const int last = static_cast<int>(g.band.size()) - 1;
  for (;;) {
    if (j == hi) {
      run.s_hi = band[j].s;
      run.at_band_end = run.at_band_end || j == last;
      break;
    }
    const double vn = overlap(j + 1);
    if (!(vn > 0.0)) {
      run.s_hi = band[j].s + step * vj / (vj - vn);
      break;
    }
    ++j;
    vj = vn;
    vmax = std::max(vmax, vn);
  }
  run.v_max = vmax;
  if (!(run.s_hi > run.s_lo)) run.loaded = false;
  return run;
}

}  // namespace

double planar_strip_lengths(const WheelContactGeometry& g, PointContext& p, Workspace& w,
                            const Run& run, int n, double s_ref, const NormalOptions& o) {
  const double width = (run.s_hi - run.s_lo) / n;
  int j0, j1;
  strip_sample_range(g, run.s_lo, width, n, &j0, &j1);
  ensure_samples(g, p, w, j0, j1, o);
  double L_max = 0.0;
  for (int k = 0; k < n; ++k) {
    const double s = run.s_lo + (k + 0.5) * width;
    int j;
    double t;
    locate(g, s, &j, &t);
    const double v = std::max(lerp_at(w.v.data(), j, t), 0.0);
    const double A = lerp_at(w.A.data(), j, t);
    const double L = A > 0.0 ? std::sqrt(v / A) : 0.0;
    w.strip_len[k] = L;
    w.strip_pos[k] = s - s_ref;
    L_max = std::max(L_max, L);
  }
  return L_max;
}

Run find_run(const WheelContactGeometry& g, PointContext& p, Workspace& w, double dz,
             const NormalOptions& /*options*/) {
  if (p.i0 < 0 || p.hi < p.lo) return Run{};
  const double eps = p.eps;
  const BandSample* band = g.band.data();
  double* v = w.v.data();
  if (!is_stripes(p.model)) {
    // Planar patch: v = eps (dz - h) cos g_ref - (gap - h cos g_ref); Linder's penetration scaled
    // like its force by the run weight (w^(2/3), normal_internal.hpp), so the patch matches it.
    const double wscale = p.weight != 1.0 ? std::cbrt(p.weight * p.weight) : 1.0;
    const double vp = eps * (dz - p.h) * p.cos_ref * wscale, hc = p.h * p.cos_ref;
    return scan_run(g, p.i0, p.lo, p.hi, [&](int j) { return v[j] = vp - (band[j].gap - hc); });
  }
  // STRIPES (own angle): v = eps dz cos g - gap + (1 - eps) h cos g. cos is ready on a block
  // around the last run (grown in blocks of 16: the run moves little between evaluations).
  const double edz = eps * dz, eh = (1.0 - eps) * p.h;
  const double* c = w.cos_angle.data();
  ensure_cos(g, p, w, p.i0, p.i0);
  int clo = p.cos_lo, chi = p.cos_hi;
  return scan_run(g, p.i0, p.lo, p.hi, [&](int j) {
    if (j < clo || j > chi) [[unlikely]] {
      extend_cos(g, p, w, std::max(p.lo, j - 16), std::min(p.hi, j + 16));
      clo = p.cos_lo;
      chi = p.cos_hi;
    }
    return v[j] = edz * c[j] - band[j].gap + eh * c[j];
  });
}

double interp_band(const WheelContactGeometry& g, double s, double BandSample::*field) {
  int j;
  double t;
  locate(g, s, &j, &t);
  const double a = g.band[j].*field;
  if (t == 0.0) return a;
  return a + t * (g.band[j + 1].*field - a);
}

Strip band_strip(const WheelContactGeometry& g, const PointContext& p, double s, double width,
                 bool own_angle) {
  const ContactPoint& cp = g.points[p.point];
  Strip st{};
  st.s = s;
  st.width = width;
  if (p.i0 >= 0) {
    int j;
    double t;
    locate(g, s, &j, &t);
    const BandSample& a = g.band[j];
    const BandSample& b = t == 0.0 ? a : g.band[j + 1];
    auto lerp = [t](double x, double y) { return x + t * (y - x); };
    st.wheel_u = lerp(a.wheel_u, b.wheel_u);
    st.rail_u = lerp(a.rail_u, b.rail_u);
    st.rolling_radius = lerp(a.rolling_radius, b.rolling_radius);
    st.contact_angle = own_angle ? outward_sign(g.side) * lerp(a.contact_angle, b.contact_angle)
                                 : cp.contact_angle;
  } else {
    st.wheel_u = cp.wheel_u + (s - cp.band_s);
    st.rail_u = cp.rail_u + (s - cp.band_s);
    st.rolling_radius = cp.rolling_radius;
    st.contact_angle = cp.contact_angle;
  }
  return st;
}

namespace {

constexpr StatusBits kPointBits =
    status::kFlangeContact | status::kNonHertzian | status::kProfileEdge;

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
    for (std::size_t k = 0; k < order.size(); ++k) {
      PointContext& p = w.points[order[k]];
      p.lo = 0;
      p.hi = nb - 1;
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
      }
      if (k + 1 < order.size()) {
        const PointContext& q = w.points[order[k + 1]];
        if (q.i0 != p.i0) {
          int split = p.i0 + 1;
          for (int j = p.i0 + 1; j < q.i0; ++j)
            if (g.band[j].gap > g.band[split].gap) split = j;
          p.hi = std::max(split, p.i0);
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

bool uses_run_weight(const PointContext& p) {
  return (p.model == NormalModel::hertz || p.model == NormalModel::linder) && p.hertz_valid;
}

// Sets PointContext::weight of every point for approach dz (normal_internal.hpp, run weights).
void run_weights(const WheelContactGeometry& g, Workspace& w, double dz) {
  for (PointContext& p : w.points) {
    p.weight = 1.0;
    p.run_group = -1;
  }
  const int n = static_cast<int>(w.order.size());
  int k0 = 0;
  while (k0 < n) {
    // Component [k0, k1]: consecutive weighted, loaded points joined by positive saddle overlap.
    int k1 = k0;
    auto penetration = [&](int k) {
      const PointContext& p = w.points[w.order[k]];
      return (dz - p.h) * p.cos_ref;
    };
    auto saddle_overlap = [&](int k) {  // between order[k] and order[k + 1]
      const BandSample& b = g.band[w.saddle[k]];
      return dz * band_cos(b.contact_angle) - b.gap;
    };
    auto joinable = [&](int k) {
      const PointContext& p = w.points[w.order[k]];
      return uses_run_weight(p) && dz > p.h;
    };
    if (joinable(k0))
      while (k1 + 1 < n && joinable(k1 + 1) && saddle_overlap(k1) > 0.0) ++k1;
    for (int k = k0; k <= k1; ++k) w.points[w.order[k]].run_group = k0;
    if (k1 > k0) {
      double prominence_sum = 0.0;
      for (int k = k0; k <= k1; ++k) {
        double ds = 0.0;
        if (k > k0) ds = std::max(ds, saddle_overlap(k - 1));
        if (k < k1) ds = std::max(ds, saddle_overlap(k));
        const double d = penetration(k);
        PointContext& p = w.points[w.order[k]];
        p.weight = std::max(d - ds, 0.0);  // prominence for now
        prominence_sum += p.weight;
      }
      const double m = k1 - k0 + 1;
      for (int k = k0; k <= k1; ++k) {
        PointContext& p = w.points[w.order[k]];
        const double prominence = p.weight, d = penetration(k);
        const double t = std::clamp(prominence / d, 0.0, 1.0);
        const double share = prominence_sum > 0.0 ? prominence / prominence_sum : 1.0 / m;
        p.weight = std::clamp(t + (1.0 - t) * share, 0.0, 1.0);
      }
    }
    k0 = k1 + 1;
  }
  // STRIPES: consecutive loaded points joined by positive rigid overlap at their saddles form one
  // run, evaluated once by its lead (the largest penetration), stripes_patch.
  for (PointContext& p : w.points) {
    p.stripes_lead = p.grp_k0 = p.grp_k1 = -1;
    p.sweight = 1.0;
    p.sblend = 1.0;
  }
  k0 = 0;
  while (k0 < n) {
    auto joinable = [&](int k) {
      const PointContext& p = w.points[w.order[k]];
      return is_stripes(p.model) && dz > p.h;
    };
    auto saddle_overlap = [&](int k) {
      const BandSample& b = g.band[w.saddle[k]];
      return dz * band_cos(b.contact_angle) - b.gap;
    };
    int k1 = k0;
    if (joinable(k0))
      while (k1 + 1 < n && joinable(k1 + 1) && saddle_overlap(k1) > 0.0) ++k1;
    if (k1 > k0) {
      int lead = w.order[k0];
      double best = -std::numeric_limits<double>::infinity();
      for (int k = k0; k <= k1; ++k) {
        const PointContext& p = w.points[w.order[k]];
        const double d = (dz - p.h) * p.cos_ref;
        if (d > best) {
          best = d;
          lead = w.order[k];
        }
      }
      double prominence_sum = 0.0;
      for (int k = k0; k <= k1; ++k) {
        PointContext& p = w.points[w.order[k]];
        p.stripes_lead = lead;
        p.grp_k0 = k0;
        p.grp_k1 = k1;
        double ds = 0.0;
        if (k > k0) ds = std::max(ds, saddle_overlap(k - 1));
        if (k < k1) ds = std::max(ds, saddle_overlap(k));
        p.sweight = std::max((dz - p.h) * p.cos_ref - ds, 0.0);  // prominence for now
        prominence_sum += p.sweight;
      }
      // Blend from the per-point patches (the run just joined: saddle overlap 0) to the one-run
      // patch (saddle overlap >= the smallest prominence, e.g. a ripple's): continuous in dz and y.
      double ds_max = 0.0, p_min = std::numeric_limits<double>::infinity();
      for (int k = k0; k < k1; ++k) ds_max = std::max(ds_max, saddle_overlap(k));
      for (int k = k0; k <= k1; ++k) p_min = std::min(p_min, w.points[w.order[k]].sweight);
      const double blend = ds_max >= p_min ? 1.0 : ds_max / p_min;
      const double count = k1 - k0 + 1;
      for (int k = k0; k <= k1; ++k) {
        PointContext& p = w.points[w.order[k]];
        p.sblend = blend;
        const double prominence = p.sweight, d = (dz - p.h) * p.cos_ref;
        const double t = std::clamp(prominence / d, 0.0, 1.0);
        const double share = prominence_sum > 0.0 ? prominence / prominence_sum : 1.0 / count;
        p.sweight = std::clamp(t + (1.0 - t) * share, 0.0, 1.0);
      }
    }
    k0 = k1 + 1;
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

double vertical_load(const WheelContactGeometry& g, const Material& m, const NormalOptions& o,
                     Workspace& w, double dz) {
  run_weights(g, w, dz);
  double total = 0.0;
  for (PointContext& p : w.points) total += evaluate(g, m, o, p, w, dz, nullptr).vertical;
  return total;
}

// Reference of one rigid-overlap run (geometry/overlap_reference.cpp, default options: squared
// weighting; the constant factor of the weight cancels), found by expanding from a seed sample.
struct RunReference {
  int a = 0, b = -1;                 // first and last band sample of the run
  double s_start = 0.0, s_end = 0.0;
  double band_s = 0.0, rail_u = 0.0, wheel_u = 0.0, angle_side = 0.0, radius = 0.0;
  bool clipped = false;
};

bool rigid_run(const WheelContactGeometry& g, Workspace& ws, double dz, int seed,
               RunReference* out) {
  const std::vector<BandSample>& band = g.band;
  const int n = static_cast<int>(band.size());
  if (seed < 0 || seed >= n) return false;
  double* d = ws.v.data();      // rigid normal overlap per sample (scratch)
  double* c = ws.cosb.data();   // cos of the sample's angle (scratch)
  auto eval = [&](int i) {
    c[i] = band_cos(band[i].contact_angle);
    d[i] = dz * c[i] - band[i].gap;
    return d[i];
  };
  if (!(eval(seed) > 0.0)) return false;
  // Expansion: cos g >= 1 - g^2/2 makes dz (1 - g^2/2) - gap > 0 a cheap sufficient test; the
  // exact overlap is evaluated only where it fails (near the ends of the run).
  auto inside = [&](int i) {
    const BandSample& bs = band[i];
    if (dz * (1.0 - 0.5 * bs.contact_angle * bs.contact_angle) - bs.gap > 0.0) return true;
    return bs.gap < dz && eval(i) > 0.0;
  };
  int a = seed, b = seed;
  while (a > 0 && inside(a - 1)) --a;
  while (b + 1 < n && inside(b + 1)) ++b;
  if (a > 0) eval(a - 1);
  if (b + 1 < n) eval(b + 1);
  // Weight per unit s: p^(5/2) cos g with p = d / cos g (the factor of the weight cancels).
  double* wt = ws.weight.data();
  for (int j = a; j <= b; ++j) eval(j);
  int j0 = a;
#if defined(__SSE2__)
  // Two samples per step: the scalar loop is bound by the latency of divsd/sqrtsd (std::sqrt must
  // also keep errno, which stops the compiler from vectorising it).
  for (; j0 + 1 <= b; j0 += 2) {
    const __m128d cc = _mm_loadu_pd(c + j0);
    const __m128d p = _mm_div_pd(_mm_loadu_pd(d + j0), cc);
    _mm_storeu_pd(wt + j0, _mm_mul_pd(_mm_mul_pd(_mm_mul_pd(p, p), _mm_sqrt_pd(p)), cc));
  }
#endif
  for (int j = j0; j <= b; ++j) {
    const double p = d[j] / c[j];
    wt[j] = p * p * std::sqrt(p) * c[j];
  }
  // Trapezoids on the uniform band: interior samples full weight, the two ends half.
  double sum_w = 0.0, sum_wq = 0.0, sum_wa = 0.0;
  if (b > a) {
    for (int j = a; j <= b; ++j) {
      const BandSample& p = band[j];
      sum_w += wt[j];
      sum_wq += wt[j] * p.q;
      sum_wa += wt[j] * p.contact_angle;
    }
    const double ends[2] = {wt[a], wt[b]};
    sum_w -= 0.5 * (ends[0] + ends[1]);
    sum_wq -= 0.5 * (ends[0] * band[a].q + ends[1] * band[b].q);
    sum_wa -= 0.5 * (ends[0] * band[a].contact_angle + ends[1] * band[b].contact_angle);
    const double step = g.band_step;
    sum_w *= step;
    sum_wq *= step;
    sum_wa *= step;
  }
  constexpr double e = 2.5;
  auto end_cell = [&](int k, int m) {
    const double dk = d[k], dm = d[m];
    const double h = band[m].s - band[k].s;
    const double len = h * dk / (dk - dm);
    const double part = wt[k] * std::abs(len) / (e + 1.0);
    const double t = len / (e + 2.0) / h;
    sum_w += part;
    sum_wq += part * (band[k].q + t * (band[m].q - band[k].q));
    sum_wa += part * (band[k].contact_angle + t * (band[m].contact_angle - band[k].contact_angle));
    return band[k].s + len;
  };
  RunReference& r = *out;
  r = RunReference{};
  r.a = a;
  r.b = b;
  if (a > 0) {
    r.s_start = end_cell(a, a - 1);
  } else {
    r.s_start = band[a].s;
    r.clipped = true;
  }
  if (b + 1 < n) {
    r.s_end = end_cell(b, b + 1);
  } else {
    r.s_end = band[b].s;
    r.clipped = true;
  }
  double q = band[a].q;
  r.angle_side = band[a].contact_angle;
  if (sum_w > 0.0) {
    q = sum_wq / sum_w;
    r.angle_side = sum_wa / sum_w;
  }
  // Band point at the weighted q (q grows with s along the band).
  int j = a;
  if (q <= band.front().q) {
    j = 0;
  } else if (q >= band.back().q) {
    j = n - 1;
  } else {
    const auto it = std::partition_point(band.begin(), band.end(),
                                         [q](const BandSample& x) { return x.q <= q; });
    j = static_cast<int>(it - band.begin()) - 1;
  }
  const BandSample& lo = band[j];
  const BandSample& hi = band[std::min(j + 1, n - 1)];
  const double t = (j + 1 < n && hi.q > lo.q) ? std::clamp((q - lo.q) / (hi.q - lo.q), 0.0, 1.0) : 0.0;
  auto mix = [t](double x, double y) { return x + t * (y - x); };
  r.band_s = mix(lo.s, hi.s);
  r.rail_u = mix(lo.rail_u, hi.rail_u);
  r.wheel_u = mix(lo.wheel_u, hi.wheel_u);
  r.radius = mix(lo.rolling_radius, hi.rolling_radius);
  return true;
}

// Merges the contributions parts[k] (k in members, ascending band s) into one patch.
ContactPatch merge_parts(const WheelContactGeometry& g, std::vector<ContactPatch>& parts,
                         const std::vector<int>& members) {
  if (members.size() == 1) return std::move(parts[members.front()]);
  ContactPatch out;
  double length = 0.0;
  std::size_t nstrips = 0;
  for (int k : members) nstrips += parts[k].strips.size();
  out.strips.reserve(nstrips);
  for (int k : members) {
    ContactPatch& p = parts[k];
    out.normal_force += p.normal_force;
    out.area += p.area;
    out.max_pressure = std::max(out.max_pressure, p.max_pressure);
    out.status |= p.status;
    out.strips.insert(out.strips.end(), p.strips.begin(), p.strips.end());
    if (p.strips.empty()) {
      length = std::max(length, 2.0 * p.semi_axis_a);
    } else {
      for (const Strip& st : p.strips) length = std::max(length, st.x_lead - st.x_trail);
    }
  }
  std::sort(out.strips.begin(), out.strips.end(),
            [](const Strip& x, const Strip& y) { return x.s < y.s; });
  const ContactPatch& first = parts[members.front()];
  out.model = first.model;
  out.pressure_shape = first.pressure_shape;
  out.status &= ~status::kLiftOff;
  (void)g;
  // Equivalent ellipse of the merged patch (area and length/width kept, as Kik-Piotrowski's).
  double s_lo = std::numeric_limits<double>::infinity(), s_hi = -s_lo;
  for (int k : members) {
    const ContactPatch& p = parts[k];
    if (!p.strips.empty()) {
      s_lo = std::min(s_lo, p.strips.front().s - 0.5 * p.strips.front().width);
      s_hi = std::max(s_hi, p.strips.back().s + 0.5 * p.strips.back().width);
    } else {
      s_lo = std::min(s_lo, p.band_s - p.semi_axis_b);
      s_hi = std::max(s_hi, p.band_s + p.semi_axis_b);
    }
  }
  const double width = s_hi - s_lo;
  if (out.area > 0.0 && length > 0.0 && width > 0.0) {
    out.semi_axis_a = std::sqrt(out.area / std::numbers::pi) * std::sqrt(length / width);
    out.semi_axis_b = std::sqrt(out.area / std::numbers::pi) * std::sqrt(width / length);
  }
  return out;
}

// Reference of a Hertz patch of one point: the ellipse centre, i.e. the rigid contact point; its
// lateral extent is the ellipse's, band_s -+ b (kProfileEdge when that leaves the band).
void set_ellipse_reference(const WheelContactGeometry& g, const ContactPoint& cp,
                           ContactPatch& patch) {
  patch.band_s = cp.band_s;
  patch.contact_angle = cp.contact_angle;
  patch.rolling_radius = cp.rolling_radius;
  patch.wheel_u = cp.wheel_u;
  patch.rail_u = cp.rail_u;
  patch.s_start = cp.band_s - patch.semi_axis_b;
  patch.s_end = cp.band_s + patch.semi_axis_b;
  if (g.band.size() >= 2 && (patch.s_start < g.band.front().s || patch.s_end > g.band.back().s))
    patch.status |= status::kProfileEdge;
}

// One loaded point running Hertz: its patch is the ellipse at the point whatever the grouping
// (an unloaded point has a larger separation, so it is never the patch's point_index), so no band
// scan is needed. Writes r in place (its vectors keep their capacity); false: not that case.
bool fill_single_hertz(const WheelContactGeometry& g, const Material& m, const NormalOptions& o,
                       Workspace& w, double dz, WheelNormalResult& r) {
  const int np = static_cast<int>(w.points.size());
  int k = -1;
  for (int i = 0; i < np; ++i) {
    if (!(dz > w.points[i].h)) continue;
    if (k >= 0) return false;
    k = i;
  }
  if (k < 0 || w.points[k].model != NormalModel::hertz) return false;
  r.patches.resize(1);
  ContactPatch& patch = r.patches.front();
  const PatchSums sums = evaluate(g, m, o, w.points[k], w, dz, &patch);
  if (!(sums.normal > 0.0)) return false;
  r.vertical_approach = dz;
  r.vertical_load = sums.vertical;
  r.iterations = 0;
  r.status = 0;
  for (const PointContext& p : w.points) r.status |= p.flags;  // as the unloaded parts report
  r.status = (r.status | patch.status) & ~status::kLiftOff;
  r.point_patch.assign(np, -1);
  r.point_patch[k] = 0;
  patch.points = 1;
  patch.point_index = k;
  set_ellipse_reference(g, g.points[k], patch);
  return true;
}

WheelNormalResult fill_general(const WheelContactGeometry& g, const Material& m,
                               const NormalOptions& o, Workspace& w, double dz) {
  WheelNormalResult r;
  r.vertical_approach = dz;
  const int np = static_cast<int>(w.points.size());
  r.point_patch.assign(np, -1);
  std::vector<ContactPatch> parts(np);
  std::vector<int> loaded_points;
  for (int i = 0; i < np; ++i) {
    const PatchSums s = evaluate(g, m, o, w.points[i], w, dz, &parts[i]);
    r.vertical_load += s.vertical;
    if (s.normal > 0.0) loaded_points.push_back(i);
    r.status |= parts[i].status & ~status::kLiftOff;
  }
  if (loaded_points.empty()) {
    r.status |= status::kLiftOff;
    return r;
  }
  // STRIPES points evaluated by their run's lead (one strip set, stripes.cpp) belong to its patch.
  for (int i = 0; i < np; ++i) {
    const int lead = w.points[i].stripes_lead;
    if (lead >= 0 && lead != i && parts[lead].normal_force > 0.0 &&
        std::find(loaded_points.begin(), loaded_points.end(), i) == loaded_points.end())
      loaded_points.push_back(i);
  }
  // Rigid overlap runs holding the loaded points.
  struct Group {
    RunReference ref;
    bool has_ref = false;
    std::vector<int> members;  // loaded contributions
    int key = -1;              // Hertz: PointContext::run_group of the members
  };
  std::vector<Group> groups;
  const double half_step = 0.5 * g.band_step;
  auto contains = [&](const Group& gr, double s) {
    return gr.has_ref && s >= gr.ref.s_start - half_step && s <= gr.ref.s_end + half_step;
  };
  if (o.combine_patches && g.band.size() >= 2) {
    for (const OverlapReference& ref : overlap_references(g, dz, contact_patch_rules())) {
      Group gr;
      gr.has_ref = true;
      gr.ref.s_start = ref.s_start;
      gr.ref.s_end = ref.s_end;
      gr.ref.band_s = ref.band_s;
      gr.ref.rail_u = ref.rail_u;
      gr.ref.wheel_u = ref.wheel_u;
      gr.ref.angle_side = ref.contact_angle_side;
      gr.ref.radius = ref.rolling_radius;
      gr.ref.clipped = ref.clipped;
      groups.push_back(std::move(gr));
    }
  }
  // Hertz points: grouped by run_weights' runs (positive overlap at the saddles between them), no
  // band scan; the patch of several ellipses is referred to their force-weighted centre below.
  auto hertz_grouped = [&](int i) {
    return !o.combine_patches && w.points[i].model == NormalModel::hertz &&
           w.points[i].run_group >= 0;
  };
  for (int i : loaded_points) {
    if (!hertz_grouped(i)) continue;
    Group* home = nullptr;
    for (Group& gr : groups)
      if (gr.key == w.points[i].run_group) home = &gr;
    if (!home) {
      groups.emplace_back();
      home = &groups.back();
      home->key = w.points[i].run_group;
    }
    home->members.push_back(i);
  }
  for (Group& gr : groups) {
    if (gr.key < 0 || gr.members.size() < 2) continue;
    // Centre of force of the ellipses (each centred at its point); extent: their union.
    double sum = 0.0, s = 0.0, angle = 0.0, radius = 0.0, wu = 0.0, ru = 0.0;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int k : gr.members) {
      const ContactPoint& cp = g.points[k];
      const double f = parts[k].normal_force;
      sum += f;
      s += f * cp.band_s;
      angle += f * cp.contact_angle_side;
      radius += f * cp.rolling_radius;
      wu += f * cp.wheel_u;
      ru += f * cp.rail_u;
      lo = std::min(lo, cp.band_s - parts[k].semi_axis_b);
      hi = std::max(hi, cp.band_s + parts[k].semi_axis_b);
    }
    gr.ref.band_s = s / sum;
    gr.ref.angle_side = angle / sum;
    gr.ref.radius = radius / sum;
    gr.ref.wheel_u = wu / sum;
    gr.ref.rail_u = ru / sum;
    gr.ref.s_start = lo;
    gr.ref.s_end = hi;
    gr.ref.clipped = g.band.size() >= 2 && (lo < g.band.front().s || hi > g.band.back().s);
    gr.has_ref = true;
  }
  for (int i : loaded_points) {
    if (hertz_grouped(i)) continue;
    const double s = g.points[i].band_s;
    Group* home = nullptr;
    for (Group& gr : groups)
      if (contains(gr, s)) home = &gr;
    if (!home) {
      Group gr;
      gr.has_ref = !o.combine_patches && rigid_run(g, w, dz, w.points[i].i0, &gr.ref);
      groups.push_back(std::move(gr));
      home = &groups.back();
    }
    home->members.push_back(i);
  }
  std::erase_if(groups, [](const Group& gr) { return gr.members.empty(); });
  // A Hertz patch of one point is its ellipse: the reference is the point (ellipse centre).
  auto hertz_ellipse = [&](const Group& gr) {
    return gr.members.size() == 1 && w.points[gr.members.front()].model == NormalModel::hertz;
  };
  auto group_s = [&](const Group& gr) {
    return gr.has_ref && !hertz_ellipse(gr) ? gr.ref.band_s : g.points[gr.members.front()].band_s;
  };
  std::sort(groups.begin(), groups.end(),
            [&](const Group& x, const Group& y) { return group_s(x) < group_s(y); });
  const double sigma = outward_sign(g.side);
  r.patches.reserve(groups.size());
  for (const Group& gr : groups) {
    const int pi = static_cast<int>(r.patches.size());
    // Points inside the run: the loaded members and any unloaded point within the extent.
    int best = gr.members.front();
    for (int i = 0; i < np; ++i) {
      const bool member = std::find(gr.members.begin(), gr.members.end(), i) != gr.members.end();
      if (!member && !contains(gr, g.points[i].band_s)) continue;
      if (member) r.point_patch[i] = pi;
      if (g.points[i].separation < g.points[best].separation) best = i;
    }
    std::vector<int> members = gr.members;
    std::sort(members.begin(), members.end(),
              [&](int x, int y) { return g.points[x].band_s < g.points[y].band_s; });
    // The patch takes model, pressure shape and penetration from its least separated member.
    int lead = members.front();
    for (int k : members)
      if (g.points[k].separation < g.points[lead].separation) lead = k;
    const double penetration = parts[lead].penetration;
    const NormalModel model = parts[lead].model;
    ContactPatch patch = merge_parts(g, parts, members);
    patch.model = model;
    patch.penetration = penetration;
    patch.points = static_cast<int>(members.size());
    patch.point_index = best;
    if (hertz_ellipse(gr)) {
      set_ellipse_reference(g, g.points[lead], patch);
    } else if (gr.has_ref) {
      patch.band_s = gr.ref.band_s;
      patch.contact_angle = sigma * gr.ref.angle_side;
      patch.rolling_radius = gr.ref.radius;
      patch.wheel_u = gr.ref.wheel_u;
      patch.rail_u = gr.ref.rail_u;
      patch.s_start = gr.ref.s_start;
      patch.s_end = gr.ref.s_end;
      if (gr.ref.clipped) patch.status |= status::kProfileEdge;
    } else {  // no sampled overlap run: the geometric point is the reference
      const ContactPoint& cp = g.points[lead];
      patch.band_s = cp.band_s;
      patch.contact_angle = cp.contact_angle;
      patch.rolling_radius = cp.rolling_radius;
      patch.wheel_u = cp.wheel_u;
      patch.rail_u = cp.rail_u;
      patch.s_start = patch.strips.empty() ? cp.band_s - patch.semi_axis_b
                                           : patch.strips.front().s - 0.5 * patch.strips.front().width;
      patch.s_end = patch.strips.empty() ? cp.band_s + patch.semi_axis_b
                                         : patch.strips.back().s + 0.5 * patch.strips.back().width;
    }
    r.patches.push_back(std::move(patch));
  }
  if (r.patches.size() > 1) r.status |= status::kTwoPoint;
  return r;
}

void fill(const WheelContactGeometry& g, const Material& m, const NormalOptions& o, Workspace& w,
          double dz, WheelNormalResult& out) {
  run_weights(g, w, dz);
  if (fill_single_hertz(g, m, o, w, dz, out)) return;
  out = fill_general(g, m, o, w, dz);
}

void check_options(const NormalOptions& o) {
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

}  // namespace
}  // namespace detail

WheelNormalResult solve_normal_for_approach(const WheelContactGeometry& geometry,
                                            double vertical_approach, const Material& material,
                                            const NormalOptions& options) {
  detail::check_options(options);
  if (!std::isfinite(vertical_approach))
    return detail::lift_off(geometry, status::kInvalidInput);
  if (geometry.points.empty() || vertical_approach <= 0.0) {
    auto r = detail::lift_off(geometry, status::kConverged);
    r.vertical_approach = vertical_approach;
    return r;
  }
  detail::Workspace& w = detail::thread_workspace();
  detail::prepare(geometry, material, options, w);
  WheelNormalResult r;
  detail::fill(geometry, material, options, w, vertical_approach, r);
  r.status |= status::kConverged;
  return r;
}

WheelNormalResult solve_normal_for_load(const WheelContactGeometry& geometry, double vertical_load,
                                        const Material& material, const NormalOptions& options) {
  WheelNormalResult r;
  solve_normal_for_load(geometry, vertical_load, material, options, r);
  return r;
}

void solve_normal_for_load(const WheelContactGeometry& geometry, double vertical_load,
                           const Material& material, const NormalOptions& options,
                           WheelNormalResult& r) {
  detail::check_options(options);
  if (!std::isfinite(vertical_load)) {
    r = detail::lift_off(geometry, status::kInvalidInput);
    return;
  }
  if (geometry.points.empty() || vertical_load <= 0.0) {
    r = detail::lift_off(geometry, status::kConverged);
    return;
  }
  detail::Workspace& w = detail::thread_workspace();
  detail::prepare(geometry, material, options, w);

  // Hertz, one loaded point: closed form. N = W / cos(gamma) at the least separated point k;
  // exact when the resulting approach leaves every other point unloaded (dz <= h_j).
  {
    bool all_hertz = true;
    int k = 0;
    for (std::size_t i = 0; i < w.points.size(); ++i) {
      const detail::PointContext& p = w.points[i];
      all_hertz = all_hertz && p.model == NormalModel::hertz && p.hertz_valid;
      if (p.h < w.points[k].h) k = static_cast<int>(i);
    }
    if (all_hertz) {
      const detail::PointContext& pk = w.points[k];
      const double AB = pk.A0 + pk.B0;
      const double c =
          std::cbrt(3.0 * vertical_load / pk.cos_ref / (4.0 * material.contact_modulus() * AB));
      const double dz = pk.h + pk.hz.r * AB * c * c / pk.cos_ref;
      bool single = dz > pk.h;
      for (std::size_t i = 0; i < w.points.size(); ++i)
        single = single && (static_cast<int>(i) == k || dz <= w.points[i].h);
      if (single && detail::fill_single_hertz(geometry, material, options, w, dz, r) &&
          std::abs(r.vertical_load - vertical_load) <= 2.0 * options.tolerance * vertical_load) {
        r.iterations = 1;  // one evaluation, no iteration
        r.status |= status::kConverged;
        return;
      }
    }
  }

  // Load control in the variable W^(2/3): nearly linear in delta_z (Hertz: W ~ delta^(3/2)), so
  // Brent's inverse interpolation converges in a few steps; W is monotone in delta_z, which keeps
  // the bracket valid.
  const double target = std::cbrt(vertical_load * vertical_load);
  int evaluations = 0;
  double h_min = std::numeric_limits<double>::infinity();
  for (const auto& p : w.points) h_min = std::min(h_min, p.h);
  double x_last[2] = {h_min, h_min}, f_last[2] = {-target, -target};  // the two latest evaluations
  auto f = [&](double dz) {
    ++evaluations;
    const double W = detail::vertical_load(geometry, material, options, w, dz);
    const double fx = std::cbrt(W * W) - target;
    x_last[0] = x_last[1];
    f_last[0] = f_last[1];
    x_last[1] = dz;
    f_last[1] = fx;
    return fx;
  };
  // First guess: Hertz at the primary point (or 0.1 mm of approach).
  const detail::PointContext& p0 = w.points.front();
  double delta_n = 1e-4;
  if (p0.hertz_valid) {
    const double A = p0.A0, B = p0.B0;
    const double c = std::cbrt(3.0 * vertical_load / p0.cos_ref /
                               (4.0 * material.contact_modulus() * (A + B)));
    delta_n = p0.hz.r * (A + B) * c * c;
  }
  double lo = h_min, flo = -target;
  double hi = p0.h + delta_n / p0.cos_ref;
  if (!(hi > lo)) hi = lo + 1e-6;
  double fhi = f(hi);
  int expansions = 0;
  while (fhi < 0.0 && expansions < 80) {
    // Too little load: extrapolate W^(2/3) linearly from (h_min, 0) through the guess, 5 % beyond
    // (one step usually brackets the root), never further than doubling the approach.
    const double doubled = h_min + 2.0 * (hi - h_min);
    double next = h_min + 1.05 * (hi - h_min) * target / (fhi + target);
    if (!(next > hi) || !(next < doubled)) next = doubled;
    lo = hi;
    flo = fhi;
    hi = next;
    fhi = f(hi);
    ++expansions;
  }
  if (fhi < 0.0) {  // cannot carry the load within any sensible approach
    detail::fill(geometry, material, options, w, hi, r);
    r.iterations = evaluations;
    r.status |= status::kNotConverged;
    return;
  }
  const double f_tol = (2.0 / 3.0) * options.tolerance * target;
  // x tolerance far below what the load tolerance needs, relative to the bracket (approaches
  // span 1e-13 m at 1 nN to 1e-4 m at 150 kN), so that f_tol decides.
  const double x_tol = 1e-14 * (hi - h_min);
  // Brent to 1e-5 of the load, then one secant step through its two latest evaluations, confirmed
  // by the final fill (which evaluates the model anyway): from 1e-5 the superlinear step lands far
  // inside the tolerance, so Brent's own confirming evaluation is saved. A miss (the fill's load
  // outside the tolerance) falls back to Brent at the full tolerance.
  const double loose = std::max(f_tol, 1e-5 * target);
  auto root = brent_root(f, lo, hi, flo, fhi, x_tol, loose, options.max_iterations);
  double x = root.x;
  if (root.converged && std::abs(root.fx) > f_tol && f_last[1] != f_last[0]) {
    const double step = f_last[1] * (x_last[1] - x_last[0]) / (f_last[1] - f_last[0]);
    const double xs = x_last[1] - step;
    if (std::isfinite(xs) && xs > lo && xs < hi) x = xs;
  }
  detail::fill(geometry, material, options, w, x, r);
  auto within = [&](double factor) {
    return std::abs(r.vertical_load - vertical_load) <= factor * options.tolerance * vertical_load;
  };
  if (x != root.x && !within(1.0)) {
    root = brent_root(f, lo, hi, flo, fhi, x_tol, f_tol, options.max_iterations);
    detail::fill(geometry, material, options, w, root.x, r);
  }
  r.iterations = evaluations;
  r.status |= within(2.0) ? status::kConverged : status::kNotConverged;
}

}  // namespace railtab
