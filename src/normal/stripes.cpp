// SPDX-License-Identifier: Apache-2.0
// STRIPES (Ayasse & Chollet 2005) with the A- and the A&B-correction of Sichani et al. 2014 (FACTS 2.4).
//
// Patch: virtual interpenetration along the band; every strip follows its own contact angle (the
// patch is not planar, Enblom and Berg 2008 sec. 1.2). Strip half-length a_i = sqrt(v_i / A_ci) with the
// corrected longitudinal curvature (Sichani et al. 2014):
//   A-correction:    eps = n0^2 B0 / (r0 (A0 + B0)),        A_ci = (n_i/m_i)^2 B_i
//   A&B-correction:  eps = n0^2 / (r0 (1 + (n0/m0)^2)),     A_ci = (A_i + B_i)(n_i/m_i)^2/(1 + (n_i/m_i)^2)
// (m, n of Sichani et al. 2014 belong to the rolling and lateral directions; (n_i/m_i)^2 is the local Hertz
// (b/a)^2.) The lateral extent always comes from the real separation (FACTS 2.4.2).
// Pressure: parabolic along each strip (Kalker's simplified theory, Enblom and Berg 2008 sec. 1.2), proportional
// to the local virtual overlap (FACTS 2.4.4): p(x, s) = p_max (v(s) - A_c(s) x^2) / (eps delta0).
// Closure (StripesClosure):
//  - boussinesq (default): the amplitude C of p = C (v(s) - A_c(s) x^2) satisfies the contact
//    condition at the reference point (the geometric point of the contribution), as Kik-Piotrowski
//    do for their N: the Boussinesq displacement (1/(pi E*)) int int p/r of the assumed pressure
//    equals the true approach delta0, corrected by kappa = 32/(9 pi):
//        C = kappa pi E* delta0 / J,   J = sum_k A_k int int_strip (a_k^2 - x^2) / r dx dy.
//    kappa is the ratio of the centre displacements of a paraboloidal and a semi-ellipsoidal
//    pressure with the same force on the same ellipse, for ANY ellipticity: a Hertz ellipse with
//    the parabolic law displaces its centre by 32/(9 pi) times Hertz's approach; with kappa the
//    closure is exact on Hertz geometry (A-correction) and no constant depends on the rail case.
//    J per strip: along x in closed form, int_{-a}^{a} (a^2 - x^2)/sqrt(x^2+y^2) dx
//    = (2a^2 + y^2) asinh(a/|y|) - a sqrt(a^2 + y^2); for the strips near the reference point
//    (|y| < 6 widths) also along y, with the antiderivative F (boussinesq_sum.hpp).
//    Several rigid points in one run of rigid overlap: one strip set over the run and the contact
//    condition at the points, weighted by their run weights (stripes_run_patch).
//  - hertz_peak (FACTS 2.4.5): p_max = (4/3) p0_Hertz(A0, B0, delta0); also exact on Hertz
//    geometry, but on conformal treads B0 at the point says little about the patch.
//
// Negative or small B (FACTS 2.4.6): B enters only the local Hertz shapes (n_i/m_i) and the
// corrections, never the lateral extent. Default NegativeCurvature::shift with stripes_ab, as in
// Sichani et al.'s (2014) proposal: shifting keeps the B distribution's variation (no sharp changes, no smoothing
// that smears pressure peaks), and the A&B-correction stays finite as B -> 0 (A_c -> A + B), while
// the A-correction's A_c = (n/m)^2 B grows like A^(4/3) B^(-1/3) and makes strips collapse where B
// is small. The shift is B_i += max(0, B_floor - min B) over the band samples within
// curvature_window of the point's gap, B_floor = min_curvature_ratio A0; the window depends on the
// geometry only, so N(delta) stays continuous for the load control.
// clip_and_smooth (classic STRIPES): B_i = max(B_i, B_floor), then a moving average of half-width
// smoothing_half_width over the window.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "geometry/curvature_steps.hpp"
#include "normal/boussinesq_sum.hpp"
#include "normal/elliptic.hpp"
#include "normal/normal_internal.hpp"

namespace railtab::detail {

void prepare_stripes(const WheelContactGeometry& g, const Material& m, const NormalOptions& o,
                     PointContext& p, Workspace& w) {
  const double floor = o.min_curvature_ratio * p.A0;
  // Treatment window: contiguous samples around the point with gap <= gap(i0) + window.
  const double gap0 = g.band[p.i0].gap;
  int wlo = p.i0, whi = p.i0;
  while (wlo > p.lo && g.band[wlo - 1].gap <= gap0 + o.curvature_window) --wlo;
  while (whi < p.hi && g.band[whi + 1].gap <= gap0 + o.curvature_window) ++whi;
  // Lateral relative curvature per band sample, with the rail's curvature taken as the average
  // over the sample's cell [s - h/2, s + h/2] next to a radius transition of the rail (UIC60:
  // R300/R80 at |u| = 10.5 mm, R80/R13 at 26 mm). The point value jumped by the whole curvature
  // step whenever a transition crossed a sample, which made the strip quantities (the
  // A-correction's A_c ~ B^(1/3) near the floor most of all) jump along a y sweep. The transition
  // is located inside its cell from the change of the contact angle, -d angle/ds = k_r (s is the
  // rail arc length): fraction t of the cell [s_j, s_j+1] carries k_j, the rest k_j+1. Away from
  // transitions (and wherever the angles do not locate one) the sampled curvature is used as is.
  // The wheel's curvature steps too (S1002: the straight flange flank meets the flange-root arc, the
  // section joins of the tread); both are located by geometry/curvature_steps.hpp.
  const int nb = static_cast<int>(g.band.size());
  // One pass: sampled B on the domain, then the two samples next to each located transition
  // corrected towards their cell averages (raw, untreated B in w.B_treated[lo..hi]).
  double* Bw = w.B_treated.data();
  for (int j = p.lo; j <= p.hi; ++j)
    Bw[j] = 0.5 * (g.band[j].curvature_wheel + g.band[j].curvature_rail);
  auto correct = [&](int j, double t, double BandSample::*field) {  // transition in [j, j + 1]
    const double dk = g.band[j + 1].*field - g.band[j].*field;
    if (t < 0.5 && j >= p.lo) Bw[j] += 0.5 * (0.5 - t) * dk;
    if (t > 0.5 && j + 1 <= p.hi) Bw[j + 1] -= 0.5 * (t - 0.5) * dk;
  };
  {
    const BandSample* band = g.band.data();
    const int jend = std::min(p.hi, nb - 2);
    double kr0 = band[std::max(p.lo - 1, 0)].curvature_rail;
    double kw0 = band[std::max(p.lo - 1, 0)].curvature_wheel;
    for (int j = std::max(p.lo - 1, 0); j <= jend; ++j) {
      const double kr1 = band[j + 1].curvature_rail, kw1 = band[j + 1].curvature_wheel;
      // Cheap pre-test (both thresholds are >= 1 1/m): most cells hold no transition.
      if (std::abs(kr1 - kr0) > 1.0 || std::abs(kw1 - kw0) > 1.0) [[unlikely]] {
        // A step the samples do not locate (NaN) or that sits mid-cell (0.5) needs no correction.
        const double tr = rail_step_fraction(g, j), tw = wheel_step_fraction(g, j);
        if (std::isfinite(tr)) correct(j, tr, &BandSample::curvature_rail);
        if (std::isfinite(tw)) correct(j, tw, &BandSample::curvature_wheel);
      }
      kr0 = kr1;
      kw0 = kw1;
    }
  }
  const double B_raw_i0 = Bw[p.i0];
  auto B_at = [&](int j) { return Bw[j]; };
  double B_min = std::isfinite(p.B0) ? p.B0 : floor;
  for (int j = wlo; j <= whi; ++j) B_min = std::min(B_min, B_at(j));
  if (o.negative_curvature == NegativeCurvature::shift) {
    const double shift = std::max(0.0, floor - B_min);
    for (int j = p.lo; j <= p.hi; ++j) Bw[j] += shift;
    p.B0t = (std::isfinite(p.B0) ? p.B0 : floor) + shift;
    if (shift > 0.0) p.flags |= status::kCurvatureShifted;
  } else {
    for (int j = p.lo; j <= p.hi; ++j) Bw[j] = std::max(Bw[j], floor);
    if (B_min < floor) p.flags |= status::kCurvatureClipped;
    // Moving average inside the window (w.v as scratch: it is rewritten by every evaluation).
    const int half = std::max(1, static_cast<int>(std::lround(o.smoothing_half_width / g.band_step)));
    for (int j = wlo; j <= whi; ++j) {
      double sum = 0.0;
      int count = 0;
      for (int k = std::max(wlo, j - half); k <= std::min(whi, j + half); ++k) {
        sum += w.B_treated[k];
        ++count;
      }
      w.v[j] = sum / count;
    }
    for (int j = wlo; j <= whi; ++j) w.B_treated[j] = w.v[j];
    p.B0t = std::max(std::isfinite(p.B0) ? p.B0 : floor, floor) + (w.B_treated[p.i0] -
                                                                   std::max(B_raw_i0, floor));
    p.B0t = std::max(p.B0t, floor);
  }
  const double A0 = p.A0, B0 = p.B0t;
  const HertzCoefficients hz = hertz_coefficients_fast(A0, B0);
  const double m0 = hz.coef_a, n0 = hz.coef_b, r0 = hz.r;
  const double nm2 = (n0 / m0) * (n0 / m0);
  p.eps = p.model == NormalModel::stripes_a ? n0 * n0 * B0 / (r0 * (A0 + B0))
                                            : n0 * n0 / (r0 * (1.0 + nm2));
  p.pmax_coef = (4.0 / 3.0) * m.contact_modulus() * std::sqrt((A0 + B0) / (hz.K * hz.E));
}

namespace {

// Strips over [run.s_lo, run.s_hi] and the closure: p = scale (v - A_c x^2), the contact condition
// at s_ref with the true approach delta0 (see the file comment). The per-sample data (v, A, q, cos)
// is ready on [ja, jb], around the whole run, with A_int its running integral there (any offset).
PatchSums strips_and_closure(const WheelContactGeometry& g, const Material& m,
                             const NormalOptions& o, const PointContext& p, Workspace& w,
                             const Run& run, int ja, int jb, const double* A_int,
                             const ClosureRef* refs, int nrefs, ContactPatch* out) {
  const int n = o.strips;
  const double width = (run.s_hi - run.s_lo) / n;
  const bool boussinesq = o.stripes_closure == StripesClosure::boussinesq;
  const double* v_s = w.v.data();
  const double* A_s = w.A.data();
  const double* q_s = w.q.data();
  const double* c_s = w.cos_angle.data();
  // Corrected curvature of a strip: the mean of the (linearly interpolated) per-sample A_c over
  // the strip's width, not its value at the centre. A_c jumps where the lateral curvature of a
  // profile jumps (radius transitions, the straight flange flank meeting the flange-root arc: the
  // local Hertz shape changes by a factor of 3 or more across one band cell); taken at the strip
  // centres, the load then depended on which side of the jump each centre fell, and since the
  // strips slide with the patch edges, N(delta) had bumps (non-monotone: several approaches carry
  // the same load, the load control picked different ones from one y to the next). The mean moves
  // continuously as a jump sweeps through a strip.
  auto A_integral_pos = [&](double pos) {  // int A ds from a fixed origin at band position pos
    int j;
    double t;
    locate_pos(ja, jb, pos, &j, &t);
    const double a0 = A_s[j];
    if (t == 0.0) return A_int[j];
    return A_int[j] + t * g.band_step * (a0 + 0.5 * t * (A_s[j + 1] - a0));
  };
  // In passes with independent iterations (the divisions and roots of different strips overlap):
  // the samples at the strip centres and the integral at the strip edges, the strip curvatures
  // and half-lengths, then the volume sums in strip order.
  double* sv = w.strip_v.data();  // overlap at the strip centre
  double* sc = w.strip_c.data();  // cos of the contact angle at the strip centre
  double* sF = w.strip_F.data();  // integral of A at the strip edges (n + 1)
  double* sA = w.strip_A.data();
  double* sa = w.strip_len.data();
  // Band positions (s - s_0) / band_step of the centres (in sv) and edges (in sF), two per SSE2
  // division, then the samples there (locate_pos: as locate).
  const double s0 = g.band.front().s, step = g.band_step;
  const int last = static_cast<int>(g.band.size()) - 1;
  sF[0] = (run.s_lo - s0) / step;
  {
    int k = 0;
#if defined(__SSE2__)
    const __m128d vs0 = _mm_set1_pd(s0), vstep = _mm_set1_pd(step);
    for (; k + 1 < n; k += 2) {
      const __m128d sc2 = _mm_set_pd(run.s_lo + (k + 1 + 0.5) * width, run.s_lo + (k + 0.5) * width);
      const __m128d se2 = _mm_set_pd(run.s_lo + (k + 2) * width, run.s_lo + (k + 1) * width);
      _mm_storeu_pd(sv + k, _mm_div_pd(_mm_sub_pd(sc2, vs0), vstep));
      _mm_storeu_pd(sF + k + 1, _mm_div_pd(_mm_sub_pd(se2, vs0), vstep));
    }
#endif
    for (; k < n; ++k) {
      sv[k] = (run.s_lo + (k + 0.5) * width - s0) / step;
      sF[k + 1] = (run.s_lo + (k + 1) * width - s0) / step;
    }
  }
  sF[0] = A_integral_pos(sF[0]);
  for (int k = 0; k < n; ++k) {
    int j;
    double t;
    locate_pos(0, last, sv[k], &j, &t);
    sv[k] = std::max(lerp_at(v_s, j, t), 0.0);
    sc[k] = lerp_at(c_s, j, t);
    w.strip_pos[k] = lerp_at(q_s, j, t);
    sF[k + 1] = A_integral_pos(sF[k + 1]);
  }
  {
    int k = 0;
#if defined(__SSE2__)
    const __m128d vwidth = _mm_set1_pd(width), zero = _mm_setzero_pd();
    for (; k + 1 < n; k += 2) {
      const __m128d A =
          _mm_div_pd(_mm_sub_pd(_mm_loadu_pd(sF + k + 1), _mm_loadu_pd(sF + k)), vwidth);
      const __m128d a = _mm_and_pd(_mm_cmpgt_pd(A, zero),
                                   _mm_sqrt_pd(_mm_div_pd(_mm_loadu_pd(sv + k), A)));
      _mm_storeu_pd(sA + k, A);
      _mm_storeu_pd(sa + k, a);
    }
#endif
    for (; k < n; ++k) {
      const double A = (sF[k + 1] - sF[k]) / width;
      sA[k] = A;
      sa[k] = A > 0.0 ? std::sqrt(sv[k] / A) : 0.0;
    }
  }
  double volume = 0.0, volume_z = 0.0;  // sum v a w (4/3), its projection on track z
  for (int k = 0; k < n; ++k) {
    const double vol = (4.0 / 3.0) * sv[k] * sa[k] * width;  // parabola: int (1 - x^2/a^2) = 4/3 a
    volume += vol;
    volume_z += vol * sc[k];
  }
  // One amplitude for the patch. Boussinesq: the contact condition at the reference point(s),
  // sum_r w_r (u(s_r) - kappa delta_r) = 0 with u(s_r) = C J_r / (pi E*).
  double scale = 0.0;  // pressure per unit virtual overlap [Pa/m]
  if (boussinesq) {
    double J = 0.0, D = 0.0;
    // The references with a weight two at a time (their sums evaluated together), J and D summed
    // in reference order.
    int r = 0;
    while (r < nrefs) {
      if (!(refs[r].weight > 0.0)) {
        ++r;
        continue;
      }
      int r2 = r + 1;
      while (r2 < nrefs && !(refs[r2].weight > 0.0)) ++r2;
      BoussinesqSum b1(w.log_arg.data(), w.log_coef.data());
      b1.add_strips(w.strip_A.data(), w.strip_len.data(), n, run.s_lo, width, refs[r].s);
      if (r2 < nrefs) {
        BoussinesqSum b2(w.log_arg.data() + 4 * n, w.log_coef.data() + 4 * n);
        b2.add_strips(w.strip_A.data(), w.strip_len.data(), n, run.s_lo, width, refs[r2].s);
        double t1, t2;
        BoussinesqSum::total2(b1, b2, &t1, &t2);
        J += refs[r].weight * t1;
        D += refs[r].weight * refs[r].delta;
        J += refs[r2].weight * t2;
        D += refs[r2].weight * refs[r2].delta;
        r = r2 + 1;
      } else {
        J += refs[r].weight * b1.total();
        D += refs[r].weight * refs[r].delta;
        r = r2;
      }
    }
    constexpr double kappa = 32.0 / (9.0 * std::numbers::pi);
    if (J > 0.0) scale = kappa * std::numbers::pi * m.contact_modulus() * D / J;
  } else {
    double W = 0.0;
    for (int r = 0; r < nrefs; ++r) {
      scale += refs[r].weight * refs[r].hp;
      W += refs[r].weight;
    }
    scale = W > 0.0 ? scale / W : 0.0;
  }
  PatchSums sums{scale * volume, scale * volume_z};
  if (out) {
    double area = 0.0;
    out->strips.reserve(n);
    for (int k = 0; k < n; ++k) {
      const double s = run.s_lo + (k + 0.5) * width;
      const double a = w.strip_len[k];
      Strip st = band_strip(g, p, s, width, true);
      st.x_lead = a;
      st.x_trail = -a;
      st.pressure_peak = scale * interp_v(g, w, s);
      st.ellipse_a = a;
      st.ellipse_b = a * std::sqrt(w.strip_pos[k]);  // local virtual ellipse: b/a = n_i/m_i
      area += 2.0 * a * width;
      out->strips.push_back(st);
    }
    out->pressure_shape = StripPressure::parabolic;
    out->normal_force = sums.normal;
    out->area = area;
    out->max_pressure = scale * run.v_max;
    if (run.at_band_end) out->status |= status::kProfileEdge;
  }
  return sums;
}

// Samples [ja, jb] around [s_lo, s_hi] inside [lo, hi], covering the strip centres too.
void run_samples(const WheelContactGeometry& g, int lo, int hi, const Run& run, int n, int* ja,
                 int* jb) {
  const double width = (run.s_hi - run.s_lo) / n;
  int j0, j1;
  strip_sample_range(g, run.s_lo, width, n, &j0, &j1);
  double t;
  locate(g, lo, hi, run.s_lo, ja, &t);
  locate(g, lo, hi, run.s_hi, jb, &t);
  if (t != 0.0) ++*jb;
  *ja = std::min(*ja, j0);
  *jb = std::max(*jb, j1);
}

// STRIPES patch of the points order[grp_k0..grp_k1], which share one run of rigid overlap
// (run_weights): ONE strip set over the run, ONE amplitude. Per-point strip sets met inside the
// patch with different closures and overlaps, so the pressure stepped there (S1002/UIC60 at y = 0:
// the second rigid minimum, a 1.9 um ripple, built its own ~50 strips). Point k alone has the
// virtual overlap E_k cos g(s) - gap(s), virtual approach E_k = eps_k dz + (1 - eps_k) h_k
// (normal_model.cpp); the run takes E = sum w_k E_k / sum w_k with the points' run weights w_k
// (normal_internal.hpp: prominence above the saddle; 1 for separate wells, -> 0 for a vanishing
// minimum or ripple), continuous when minima vanish or swap depth order. The amplitude C satisfies
// the Boussinesq contact condition at the points in the weighted mean,
//   sum_k w_k (C J_k / (pi E*) - kappa delta_k) = 0,   J_k = the strips' J seen from point k,
// which is the single-point closure for one point and keeps the ripple from steering the patch.
// Positive parts of the overlap around the points (separate just after the rigid run joins) are
// spanned by the strips; strips between them carry nothing. Each sample keeps the local data (A_c,
// q) of the point whose band domain holds it.
PatchSums stripes_run_patch(const WheelContactGeometry& g, const Material& m,
                            const NormalOptions& o, PointContext& p, Workspace& w, double dz,
                            ContactPatch* out) {
  const int k0 = p.grp_k0, k1 = p.grp_k1;
  auto member = [&](int k) -> PointContext& { return w.points[w.order[k]]; };
  const int L = member(k0).lo, H = member(k1).hi;
  double E = 0.0, W = 0.0;  // weighted virtual approach, sum of the weights
  for (int k = k0; k <= k1; ++k) {
    const PointContext& q = member(k);
    E += q.sweight * (q.eps * dz + (1.0 - q.eps) * q.h);
    W += q.sweight;
  }
  if (!(W > 0.0)) return {};
  E /= W;
  // The members' domains are disjoint and ascending: sample j belongs to the first member whose
  // domain ends at or after j (the last member otherwise). Their ends are read once.
  constexpr int kMaxMembers = 8;
  const int nmem = k1 - k0 + 1;
  PointContext* mem_ptr[kMaxMembers];
  int mem_hi[kMaxMembers];
  if (nmem <= kMaxMembers) {
    for (int k = k0; k <= k1; ++k) {
      mem_ptr[k - k0] = &member(k);
      mem_hi[k - k0] = member(k).hi;
    }
  }
  auto owner = [&](int j) -> PointContext& {
    if (nmem <= kMaxMembers) [[likely]] {
      int k = 0;
      while (k + 1 < nmem && j > mem_hi[k]) ++k;
      return *mem_ptr[k];
    }
    for (int k = k0; k < k1; ++k)
      if (j <= member(k).hi) return member(k);
    return member(k1);
  };
  const BandSample* band = g.band.data();
  double* v = w.v.data();
  const double* c = w.cos_angle.data();
  // Fast path: samples [rlo, rhi] lie in one member's share of the run with its cos ready.
  int rlo = 1, rhi = 0;
  auto overlap = [&](int j) {
    if (j < rlo || j > rhi) [[unlikely]] {
      PointContext& q = owner(j);
      if (j < q.cos_lo || j > q.cos_hi) [[unlikely]]
        extend_cos(g, q, w, std::max(q.lo, j - 16), std::min(q.hi, j + 16));
      if (nmem <= kMaxMembers) {
        int k = 0;
        while (k + 1 < nmem && j > mem_hi[k]) ++k;
        const int seg_lo = k == 0 ? std::numeric_limits<int>::min() : mem_hi[k - 1] + 1;
        const int seg_hi = k + 1 == nmem ? std::numeric_limits<int>::max() : mem_hi[k];
        rlo = std::max(seg_lo, q.cos_lo);
        rhi = std::min(seg_hi, q.cos_hi);
      }
    }
    return v[j] = E * c[j] - band[j].gap;
  };
  // Runs of positive overlap around each member's point; the strips span their hull.
  const int last = static_cast<int>(g.band.size()) - 1;
  Run run;
  int scanned_lo = 1, scanned_hi = 0;  // samples already inside a found run
  int done_lo = 1, done_hi = 0;        // samples whose overlap v is already set (one interval)
  for (int k = k0; k <= k1; ++k) {
    const int i0 = member(k).i0;
    if (i0 < L || i0 > H || (i0 >= scanned_lo && i0 <= scanned_hi)) continue;
    const double v0 = overlap(i0);
    if (!(v0 > 0.0)) continue;
    double vmax = v0, s_lo, s_hi;
    bool edge = false;
    int a = i0, b = i0;
    for (;;) {
      if (a == L) {
        s_lo = band[a].s;
        edge = a == 0;
        break;
      }
      const double vn = overlap(a - 1);
      if (!(vn > 0.0)) {
        s_lo = band[a].s - g.band_step * v[a] / (v[a] - vn);
        break;
      }
      --a;
      vmax = std::max(vmax, vn);
    }
    for (;;) {
      if (b == H) {
        s_hi = band[b].s;
        edge = edge || b == last;
        break;
      }
      const double vn = overlap(b + 1);
      if (!(vn > 0.0)) {
        s_hi = band[b].s + g.band_step * v[b] / (v[b] - vn);
        break;
      }
      ++b;
      vmax = std::max(vmax, vn);
    }
    // v is set on the run [a, b] and on the samples just beyond it that ended the scan.
    const int c_lo = a == L ? a : a - 1, c_hi = b == H ? b : b + 1;
    if (done_lo > done_hi) {
      done_lo = c_lo;
      done_hi = c_hi;
    } else if (c_lo <= done_hi + 1 && c_hi >= done_lo - 1) {
      done_lo = std::min(done_lo, c_lo);
      done_hi = std::max(done_hi, c_hi);
    }
    if (!run.loaded) {
      run.loaded = true;
      run.s_lo = s_lo;
      run.s_hi = s_hi;
      scanned_lo = a;
      scanned_hi = b;
    } else {
      run.s_lo = std::min(run.s_lo, s_lo);
      run.s_hi = std::max(run.s_hi, s_hi);
      scanned_lo = std::min(scanned_lo, a);
      scanned_hi = std::max(scanned_hi, b);
    }
    run.v_max = std::max(run.v_max, vmax);
    run.at_band_end = run.at_band_end || edge;
  }
  if (!run.loaded || !(run.s_hi > run.s_lo)) return {};
  int ja, jb;
  run_samples(g, L, H, run, o.strips, &ja, &jb);
  // The overlap on all samples the strips read (between separate parts of the run too); the
  // samples the scans already set keep their (same) values.
  for (int j = ja; j <= jb; ++j) {
    if (j >= done_lo && j <= done_hi) {
      j = done_hi;
      continue;
    }
    overlap(j);
  }
  for (int k = k0; k <= k1; ++k) {
    PointContext& q = member(k);
    const int j0 = std::max(ja, q.lo), j1 = std::min(jb, q.hi);
    if (j0 <= j1) ensure_samples(g, q, w, j0, j1, o);
  }
  // Running integral of A from ja. The per-sample A is fixed once ready (once per solve), so the
  // integral from the same origin ja for the same run of points is the same sequence of sums as
  // before: kept across the load-control evaluations (prepare() invalidates it), extended only.
  double* A_int = w.A_grp.data();
  const double* A_s = w.A.data();
  const double half_h = 0.5 * g.band_step;
  int from = ja;
  if (w.grp_lead == p.point && w.grp_ja == ja) {
    from = std::min(std::max(w.grp_jb, ja), jb);
  } else {
    A_int[ja] = 0.0;
    w.grp_lead = p.point;
    w.grp_ja = ja;
    w.grp_jb = ja;
  }
  for (int j = from; j < jb; ++j) A_int[j + 1] = A_int[j] + half_h * (A_s[j] + A_s[j + 1]);
  w.grp_jb = std::max(w.grp_jb, jb);
  ClosureRef* refs = w.refs.data();
  int nrefs = 0;
  for (int k = k0; k <= k1; ++k) {
    const PointContext& q = member(k);
    const double d = (dz - q.h) * q.cos_ref;
    const double hp = d > 0.0 ? q.pmax_coef * std::sqrt(d) / (q.eps * d) : 0.0;
    refs[nrefs++] = {g.points[q.point].band_s, d, q.sweight, hp};
  }
  return strips_and_closure(g, m, o, p, w, run, ja, jb, A_int, refs, nrefs, out);
}

// The patch of point p alone (its band domain), one strip set and its own closure.
PatchSums stripes_point_patch(const WheelContactGeometry& g, const Material& m,
                              const NormalOptions& o, PointContext& p, Workspace& w, double dz,
                              ContactPatch* out) {
  const Run run = find_run(g, p, w, dz, o);
  if (!run.loaded) return {};
  const double delta0 = (dz - p.h) * p.cos_ref;
  // The per-sample data (and the running integral of A kept with it, extend_samples) must cover
  // the samples [ja, jb] around the whole run.
  int ja, jb;
  run_samples(g, p.lo, p.hi, run, o.strips, &ja, &jb);
  ensure_samples(g, p, w, ja, jb, o);
  ensure_point_A_integral(g, p, w);
  const ClosureRef ref{g.points[p.point].band_s, delta0, 1.0,
                       p.pmax_coef * std::sqrt(delta0) / (p.eps * delta0)};
  return strips_and_closure(g, m, o, p, w, run, ja, jb, w.A_int.data(), &ref, 1, out);
}

}  // namespace

PatchSums stripes_patch(const WheelContactGeometry& g, const Material& m,
                        const NormalOptions& o, PointContext& p, Workspace& w, double dz,
                        ContactPatch* out) {
  if (p.stripes_lead < 0) return stripes_point_patch(g, m, o, p, w, dz, out);
  // A point of a rigid overlap run of several: the run's force is
  //   sblend * (one-run patch) + (1 - sblend) * sum of the per-point patches,
  // the one-run part evaluated by the lead; each point adds its own per-point share. The patch
  // output is the one strip set of the run, its pressure scaled to the run's force (the per-point
  // share matters only right after the run joins: sblend = 1 once the saddle is deeper than the
  // smallest prominence).
  const double beta = p.sblend;
  auto scaled = [](PatchSums a, double f) { return PatchSums{a.normal * f, a.vertical * f}; };
  auto add = [](PatchSums a, PatchSums b) { return PatchSums{a.normal + b.normal, a.vertical + b.vertical}; };
  PatchSums own{};
  if (beta < 1.0) own = scaled(stripes_point_patch(g, m, o, p, w, dz, nullptr), 1.0 - beta);
  if (p.stripes_lead != p.point) return own;
  if (!out) {
    if (beta > 0.0) own = add(own, scaled(stripes_run_patch(g, m, o, p, w, dz, nullptr), beta));
    return own;
  }
  const PatchSums run = stripes_run_patch(g, m, o, p, w, dz, out);
  PatchSums total = scaled(run, beta);
  if (beta < 1.0) {
    for (int k = p.grp_k0; k <= p.grp_k1; ++k)
      total = add(total, scaled(stripes_point_patch(g, m, o, w.points[w.order[k]], w, dz, nullptr),
                                1.0 - beta));
  }
  if (beta < 1.0 && run.normal > 0.0) {
    const double f = total.normal / run.normal;
    for (Strip& st : out->strips) st.pressure_peak *= f;
    out->max_pressure *= f;
  }
  out->normal_force = total.normal;
  return add(own, scaled(run, beta));
}

}  // namespace railtab::detail
