// SPDX-License-Identifier: Apache-2.0
// The band machinery shared by the virtual-interpenetration models: per-sample cos, A and q made
// ready lazily, overlap runs along the gap band, strips (normal_internal.hpp).

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

namespace railtab::detail {

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
  grow(&p.cos_lo, &p.cos_hi, j0, j1, [&](int j) { c[j] = band_cos(band[j].contact_angle_side); });
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
  // Only the point's own samples are made ready (the arrays are shared between the domains); a
  // run ending at a continuous split (find_run) reads the samples beyond from the band.
  ensure_samples(g, p, w, std::max(j0, p.lo), std::min(j1, p.hi), o);
  const double* vw = w.v.data();
  const double* Aw = w.A.data();
  auto v_at = [&](int j) {
    return j >= p.lo && j <= p.hi ? vw[j] : run.vp - (g.band[j].gap - run.hc);
  };
  auto A_at = [&](int j) {  // as compute_sample (planar): A from the local rolling radius
    if (j >= p.lo && j <= p.hi) return Aw[j];
    const double r = g.band[j].rolling_radius > 0.0 ? g.band[j].rolling_radius : p.r_ref;
    return p.A0 * (p.r_ref > 0.0 ? p.r_ref / r : 1.0);
  };
  double L_max = 0.0;
  for (int k = 0; k < n; ++k) {
    const double s = run.s_lo + (k + 0.5) * width;
    int j;
    double t;
    locate(g, s, &j, &t);
    double v, A;
    if (j >= p.lo && (t == 0.0 ? j : j + 1) <= p.hi) {
      v = std::max(lerp_at(vw, j, t), 0.0);
      A = lerp_at(Aw, j, t);
    } else {
      v = std::max(t == 0.0 ? v_at(j) : v_at(j) + t * (v_at(j + 1) - v_at(j)), 0.0);
      A = t == 0.0 ? A_at(j) : A_at(j) + t * (A_at(j + 1) - A_at(j));
    }
    const double L = A > 0.0 ? std::sqrt(v / A) : 0.0;
    w.strip_len[k] = L;
    w.strip_pos[k] = s - s_ref;
    L_max = std::max(L_max, L);
  }
  return L_max;
}

namespace {

// Planar models: a run that still overlaps at a split of the band domains (normal_model.cpp) ends
// at the continuous saddle s_lo_split / s_hi_split (or where its overlap, evaluated from the band
// beyond the domain, reaches zero first), not at the domain's last sample: a sample-bound end
// made the area jump by a cell of overlap whenever the saddle passed a sample. The samples beyond
// the domain belong to the neighbouring point (shared workspace arrays): read, never written.
void planar_split_ends(const WheelContactGeometry& g, const PointContext& p, const Workspace& w,
                       Run* run) {
  const BandSample* band = g.band.data();
  const double step = g.band_step;
  const int nb = static_cast<int>(g.band.size());
  auto ov = [&](int j) { return run->vp - (band[j].gap - run->hc); };
  if (std::isfinite(p.s_hi_split)) {
    double end = p.s_hi_split;
    if (run->s_hi == band[p.hi].s && w.v[p.hi] > 0.0) {  // reached the domain end overlapping
      int j = p.hi;
      double vj = w.v[p.hi];
      while (j + 1 < nb && band[j].s < end) {
        const double vn = ov(j + 1);
        if (!(vn > 0.0)) {
          end = std::min(end, band[j].s + step * vj / (vj - vn));
          break;
        }
        ++j;
        vj = vn;
      }
    } else {
      end = std::min(end, run->s_hi);
    }
    run->s_hi = end;
  }
  if (std::isfinite(p.s_lo_split)) {
    double start = p.s_lo_split;
    if (run->s_lo == band[p.lo].s && w.v[p.lo] > 0.0) {
      int j = p.lo;
      double vj = w.v[p.lo];
      while (j > 0 && band[j].s > start) {
        const double vn = ov(j - 1);
        if (!(vn > 0.0)) {
          start = std::max(start, band[j].s - step * vj / (vj - vn));
          break;
        }
        --j;
        vj = vn;
      }
    } else {
      start = std::max(start, run->s_lo);
    }
    run->s_lo = start;
  }
  if (!(run->s_hi > run->s_lo)) run->loaded = false;
}

}  // namespace

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
    Run run = scan_run(g, p.i0, p.lo, p.hi, [&](int j) { return v[j] = vp - (band[j].gap - hc); });
    run.vp = vp;
    run.hc = hc;
    if (run.loaded) planar_split_ends(g, p, w, &run);
    return run;
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
    st.contact_angle = own_angle ? outward_sign(g.side) * lerp(a.contact_angle_side, b.contact_angle_side)
                                 : cp.contact_angle;
  } else {
    st.wheel_u = cp.wheel_u + (s - cp.band_s);
    st.rail_u = cp.rail_u + (s - cp.band_s);
    st.rolling_radius = cp.rolling_radius;
    st.contact_angle = cp.contact_angle;
  }
  return st;
}

}  // namespace railtab::detail
