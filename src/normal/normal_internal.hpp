// SPDX-License-Identifier: Apache-2.0
// Internal machinery shared by the normal-contact models (not part of the public contract).
// One solve prepares a PointContext per contact point (geometry-only data: band domain, curvature
// treatment, reference Hertz coefficients); the load-control loop then evaluates every patch at
// trial vertical approaches without allocating. Per-band-sample data that needs trigonometry or a
// local Hertz shape is computed lazily, once per solve, only where a patch actually reaches.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "core/material.hpp"
#include "geometry/contact_geometry.hpp"
#include "normal/hertz.hpp"
#include "normal/normal_model.hpp"

namespace railtab::detail {

struct PointContext {
  int point = -1;              // index into WheelContactGeometry::points
  NormalModel model = NormalModel::hertz;  // model actually run here (after any fallback)
  double h = 0.0;              // vertical separation at rigid contact [m]
  double cos_ref = 1.0;        // cos of the reference contact angle [-]
  double A0 = 0.0;             // relative curvature, rolling direction, at the point [1/m]
  double B0 = 0.0;             // relative curvature, lateral, at the point (as given) [1/m]
  double B0t = 0.0;            // B0 after the negative-B treatment (STRIPES) [1/m]
  double r_ref = 0.0;          // rolling radius at the point [m]
  int i0 = -1;                 // band sample nearest to the point (-1: no usable band)
  int lo = 0;                  // first band sample belonging to this point
  int hi = -1;                 // last band sample belonging to this point
  double s_lo_split = std::numeric_limits<double>::quiet_NaN();  // planar models: where the run
  double s_hi_split = std::numeric_limits<double>::quiet_NaN();  //   ends at the split towards a
                               //   neighbouring point (continuous saddle, find_run; NaN: none) [m]
  double eps = 0.55;           // virtual penetration factor [-]
  double pmax_coef = 0.0;      // STRIPES: p_max = pmax_coef sqrt(delta0) [Pa/m^0.5]
  bool hertz_valid = false;    // A0 > 0 and B0 > 0
  HertzCoefficients hz{};      // Hertz coefficients at (A0, B0) when valid [-]
  StatusBits flags = 0;        // preparation flags (fallback, curvature treatment, ...)
  double weight = 1.0;         // Hertz, Linder: share of its own closure the point carries when
                               //   it shares an overlap run with others (run_weights) [-]
  int run_group = -1;          // points joined by positive saddle overlap share one id (run_weights)
  // STRIPES: points sharing a rigid overlap run are one patch (run_weights): one strip set over the
  // run, one closure at its lead (largest penetration). -1: alone; else the lead's index in points,
  // the run's members being order[grp_k0..grp_k1].
  int stripes_lead = -1;
  int grp_k0 = -1, grp_k1 = -1;
  double sweight = 1.0;        // STRIPES run member: its run weight (as Hertz's weight) [-]
  double sblend = 1.0;         // STRIPES run: share of the one-run patch against the per-point
                               //   patches (0 when the run joins, 1 once the saddle is deep) [-]
  // Band samples of this point whose per-sample data is ready in the Workspace (empty: lo > hi).
  // The domains [lo, hi] of the points are disjoint, so the points share the band-sized arrays.
  int cos_lo = 0, cos_hi = -1;  // Workspace::cos_angle ready on [cos_lo, cos_hi]
  int smp_lo = 0, smp_hi = -1;  // Workspace::A and q ready on [smp_lo, smp_hi]
  int aint_lo = 0, aint_hi = -1;  // Workspace::A_int: integral from aint_lo ready to aint_hi
};

// Per-sample data interpolated at an arc length (interp_sample).
struct SampleData {
  double cos_angle;  // cos of the sample's contact angle [-]
  double A;          // longitudinal curvature used for the strip length (corrected for STRIPES) [1/m]
  double q;          // STRIPES: local Hertz (b/a)^2 of the virtual ellipse [-]
};

// STRIPES closure reference: the contact condition is imposed at s with approach delta, weight w.
struct ClosureRef {
  double s = 0.0;       // band arc length of the reference point [m]
  double delta = 0.0;   // true normal approach there [m]
  double weight = 1.0;  // share of the contact condition [-]
  double hp = 0.0;      // hertz_peak closure: p_max / (eps delta) of the point [Pa/m]
};

struct Workspace {
  std::vector<PointContext> points;     // one per contact point
  struct HertzCache {                   // Hertz coefficients of the last (A, B) per point index
    double A = -1.0, B = -1.0;
    HertzCoefficients hz{};
  };
  std::vector<HertzCache> hertz_cache;
  // Band-sized, filled lazily once per solve on the intervals recorded in each PointContext
  // (structure of arrays: the strip loops read them without checks):
  std::vector<double> cos_angle;        // cos of the sample's contact angle [-]
  std::vector<double> A;                // SampleData::A per sample [1/m]
  std::vector<double> q;                // SampleData::q per sample [-]
  std::vector<double> B_treated;        // band-sized: lateral curvature after treatment [1/m]
  std::vector<double> v;                // band-sized: virtual overlap at the current approach [m]
  std::vector<double> cosb;             // band-sized scratch: cos of the band angle [-]
  std::vector<double> weight;           // band-sized scratch: overlap weight of the reference
  std::vector<double> strip_len;        // per-strip scratch: half-lengths [m]
  std::vector<double> strip_pos;        // per-strip scratch: lateral positions [m]
  std::vector<double> strip_A;          // per-strip scratch: corrected curvature A_c [1/m]
  std::vector<double> strip_v;          // per-strip scratch (STRIPES): overlap at the centre [m]
  std::vector<double> strip_c;          //   cos of the contact angle at the centre [-]
  std::vector<double> strip_F;          //   integral of A_c at the edges (strips + 1) [1]
  std::vector<ClosureRef> refs;         // STRIPES run closure references (one per point)
  std::vector<double> log_arg;          // STRIPES Boussinesq integral: logarithm arguments (4 per
  std::vector<double> log_coef;         //   strip, two references) and their coefficients [-], [m^3]
  std::vector<double> A_int;            // band-sized scratch: running integral of A over s [1]
  std::vector<double> A_grp;            // band-sized scratch: the same over a STRIPES run of points
  int grp_lead = -1, grp_ja = 0, grp_jb = 0;  // A_grp is the integral from grp_ja, ready up to
                                              //   grp_jb, for the run led by point grp_lead
                                              //   (-1: none; reset by every prepare)
  std::vector<int> order;               // points with a band sample, ascending band position
  std::vector<int> saddle;              // order[k]..order[k+1]: sample of the largest gap between
};

Workspace& thread_workspace();

// cos for the band angles (|x| <= pi/2 covers tread and flange): Taylor series to x^20 in
// Horner form, absolute error < 3e-15 there, several times cheaper than std::cos.
inline double band_cos(double x) {
  const double x2 = x * x;
  if (x2 < 0.125) {  // |x| < 0.354 (tread): to x^12, error < 3e-15
    double q = 1.0 / 479001600.0;
    q = q * x2 - 1.0 / 3628800.0;
    q = q * x2 + 1.0 / 40320.0;
    q = q * x2 - 1.0 / 720.0;
    q = q * x2 + 1.0 / 24.0;
    q = q * x2 - 0.5;
    return q * x2 + 1.0;
  }
  if (x2 > 2.4674011002723395) return std::cos(x);  // |x| > pi/2: not a band angle, be exact
  double r = 1.0 / 2432902008176640000.0;            // 1/20!
  r = r * x2 - 1.0 / 6402373705728000.0;             // 1/18!
  r = r * x2 + 1.0 / 20922789888000.0;               // 1/16!
  r = r * x2 - 1.0 / 87178291200.0;                  // 1/14!
  r = r * x2 + 1.0 / 479001600.0;                    // 1/12!
  r = r * x2 - 1.0 / 3628800.0;                      // 1/10!
  r = r * x2 + 1.0 / 40320.0;                        // 1/8!
  r = r * x2 - 1.0 / 720.0;                          // 1/6!
  r = r * x2 + 1.0 / 24.0;
  r = r * x2 - 0.5;
  return r * x2 + 1.0;
}

// Natural logarithm for positive normal x: exponent from the bits, mantissa in [sqrt(1/2), sqrt(2))
// by 2 atanh(u) with u = (m - 1)/(m + 1) to u^17 (error < 3e-16); std::log otherwise.
inline double fast_log(double x) {
  const auto bits = std::bit_cast<std::uint64_t>(x);
  const int biased = static_cast<int>((bits >> 52) & 0x7ff);
  if (x <= 0.0 || biased == 0 || biased == 0x7ff) return std::log(x);
  int e = biased - 1023;
  double m = std::bit_cast<double>((bits & 0x000fffffffffffffULL) | 0x3ff0000000000000ULL);
  if (m > 1.4142135623730951) {
    m *= 0.5;
    ++e;
  }
  const double u = (m - 1.0) / (m + 1.0), u2 = u * u;
  double r = 1.0 / 17.0;
  r = r * u2 + 1.0 / 15.0;
  r = r * u2 + 1.0 / 13.0;
  r = r * u2 + 1.0 / 11.0;
  r = r * u2 + 1.0 / 9.0;
  r = r * u2 + 1.0 / 7.0;
  r = r * u2 + 1.0 / 5.0;
  r = r * u2 + 1.0 / 3.0;
  r = r * u2 + 1.0;
  return e * 0.6931471805599453 + 2.0 * u * r;
}

#if defined(__SSE2__)
// fast_log on two lanes, bit for bit the same operations; lanes that are not positive normal
// numbers go through the scalar version.
inline __m128d fast_log_pd(__m128d x) {
  const __m128d ok = _mm_and_pd(_mm_cmpge_pd(x, _mm_set1_pd(0x1p-1022)),
                                _mm_cmple_pd(x, _mm_set1_pd(0x1.fffffffffffffp+1023)));
  if (_mm_movemask_pd(ok) != 3) {
    double t[2];
    _mm_storeu_pd(t, x);
    return _mm_set_pd(fast_log(t[1]), fast_log(t[0]));
  }
  const __m128i bits = _mm_castpd_si128(x);
  // Biased exponent as a double: 2^52 + e_biased from the bit pattern, minus 2^52 + 1023.
  const __m128i eb = _mm_or_si128(_mm_srli_epi64(bits, 52), _mm_set1_epi64x(0x4330000000000000LL));
  __m128d e = _mm_sub_pd(_mm_castsi128_pd(eb), _mm_set1_pd(4503599627370496.0 + 1023.0));
  __m128d m = _mm_castsi128_pd(_mm_or_si128(_mm_and_si128(bits, _mm_set1_epi64x(0x000fffffffffffffLL)),
                                            _mm_set1_epi64x(0x3ff0000000000000LL)));
  const __m128d big = _mm_cmpgt_pd(m, _mm_set1_pd(1.4142135623730951));
  m = _mm_or_pd(_mm_and_pd(big, _mm_mul_pd(m, _mm_set1_pd(0.5))), _mm_andnot_pd(big, m));
  e = _mm_add_pd(e, _mm_and_pd(big, _mm_set1_pd(1.0)));
  const __m128d one = _mm_set1_pd(1.0);
  const __m128d u = _mm_div_pd(_mm_sub_pd(m, one), _mm_add_pd(m, one));
  const __m128d u2 = _mm_mul_pd(u, u);
  __m128d r = _mm_set1_pd(1.0 / 17.0);
  r = _mm_add_pd(_mm_mul_pd(r, u2), _mm_set1_pd(1.0 / 15.0));
  r = _mm_add_pd(_mm_mul_pd(r, u2), _mm_set1_pd(1.0 / 13.0));
  r = _mm_add_pd(_mm_mul_pd(r, u2), _mm_set1_pd(1.0 / 11.0));
  r = _mm_add_pd(_mm_mul_pd(r, u2), _mm_set1_pd(1.0 / 9.0));
  r = _mm_add_pd(_mm_mul_pd(r, u2), _mm_set1_pd(1.0 / 7.0));
  r = _mm_add_pd(_mm_mul_pd(r, u2), _mm_set1_pd(1.0 / 5.0));
  r = _mm_add_pd(_mm_mul_pd(r, u2), _mm_set1_pd(1.0 / 3.0));
  r = _mm_add_pd(_mm_mul_pd(r, u2), one);
  return _mm_add_pd(_mm_mul_pd(e, _mm_set1_pd(0.6931471805599453)),
                    _mm_mul_pd(_mm_mul_pd(_mm_set1_pd(2.0), u), r));
}
#endif

// A run of positive virtual overlap around the point's sample.
struct Run {
  bool loaded = false;   // false: no overlap at the point (lift-off)
  double s_lo = 0.0;     // patch edges in band arc length [m]
  double s_hi = 0.0;
  double v_max = 0.0;    // largest sample overlap [m]
  bool at_band_end = false;  // the run was cut by the end of the band
  double vp = 0.0, hc = 0.0;  // planar models: overlap v(j) = vp - (gap_j - hc)
};

struct PatchSums {
  double normal = 0.0;    // sum of strip normal forces [N]
  double vertical = 0.0;  // projection on track z [N]
};

// Overlap-run weights of the point models (normal_model.cpp, run_weights). Hertz and Linder close
// the load per rigid point; where several points lie in one run of rigid overlap, point k carries
//   w_k = t_k + (1 - t_k) p_k / sum p,   t_k = p_k / d_k,
// of its own closure (its penetration scaled by w_k^(2/3): the force by w_k), with d_k its normal
// penetration and p_k = d_k - d_s its prominence above the highest saddle d_s (the overlap at the
// largest gap) joining it to a neighbour of the same run. Separate wells (d_s <= 0: t = 1) count
// fully; a ripple or a vanishing minimum (p -> 0) not at all; two equal minima share symmetrically.
// w is continuous when points appear, vanish, swap depth order or runs merge, so the load is
// continuous in the approach and in y (per-point closures alone: a vanishing point's share grows
// like B^-1/2).

// Hertz coefficients from the shape table plus one AGM (no root find): the same numbers as
// hertz_coefficients to ~1e-9 (hertz.cpp).
HertzCoefficients hertz_coefficients_fast(double A, double B);
// hertz_axis_ratio_fast(x[i]) in place for i < n, the same numbers (elliptic.cpp).
void hertz_axis_ratio_fast_n(double* x, int n);

// Shared preparation and evaluation (normal_model.cpp).
// Per-sample data on [j0, j1] (inside the point's band domain) made ready: cos only, or A and q
// (and, for STRIPES, the cos they need). The inline checks cost nothing once the range is ready.
void extend_cos(const WheelContactGeometry& g, PointContext& p, Workspace& w, int j0, int j1);
void extend_samples(const WheelContactGeometry& g, PointContext& p, Workspace& w, int j0, int j1,
                    const NormalOptions& o);
inline void ensure_cos(const WheelContactGeometry& g, PointContext& p, Workspace& w, int j0,
                       int j1) {
  if (j0 < p.cos_lo || j1 > p.cos_hi) extend_cos(g, p, w, j0, j1);
}
inline void ensure_samples(const WheelContactGeometry& g, PointContext& p, Workspace& w, int j0,
                           int j1, const NormalOptions& o) {
  if (j0 < p.smp_lo || j1 > p.smp_hi) extend_samples(g, p, w, j0, j1, o);
}
// STRIPES: Workspace::A_int, the running integral of A from smp_lo, made ready on the point's
// ready samples (the point's own patch; a run of points integrates over its run, stripes.cpp).
void point_A_integral(const WheelContactGeometry& g, PointContext& p, Workspace& w);
inline void ensure_point_A_integral(const WheelContactGeometry& g, PointContext& p, Workspace& w) {
  if (p.aint_lo != p.smp_lo || p.aint_hi != p.smp_hi) point_A_integral(g, p, w);
}
Run find_run(const WheelContactGeometry& g, PointContext& p, Workspace& w, double dz,
             const NormalOptions& o);
double interp_band(const WheelContactGeometry& g, double s, double BandSample::*field);

// Band segment [j, j + 1] and fraction t for arc length s, kept inside [lo, hi].
inline void locate_pos(int lo, int hi, double pos, int* j, double* t);
inline void locate(const WheelContactGeometry& g, int lo, int hi, double s, int* j, double* t) {
  locate_pos(lo, hi, (s - g.band.front().s) / g.band_step, j, t);
}
// locate with the band position pos = (s - s_0) / band_step given.
inline void locate_pos(int lo, int hi, double pos, int* j, double* t) {
  int i = static_cast<int>(std::floor(pos));
  const int jmax = std::max(lo, hi - 1);
  i = std::clamp(i, lo, jmax);
  *j = i;
  *t = (i + 1 <= hi) ? std::clamp(pos - i, 0.0, 1.0) : 0.0;
}
inline void locate(const WheelContactGeometry& g, double s, int* j, double* t) {
  locate(g, 0, static_cast<int>(g.band.size()) - 1, s, j, t);
}
// Linear interpolation of a band-sized array at segment j, fraction t (t == 0: sample j only).
inline double lerp_at(const double* x, int j, double t) {
  const double a = x[j];
  return t == 0.0 ? a : a + t * (x[j + 1] - a);
}
// Band samples touched by the strip centres s_lo + (k + 1/2) width, k = 0..n-1 (ascending s).
// The centres lie inside the run, hence inside the point's band domain.
inline void strip_sample_range(const WheelContactGeometry& g, double s_lo, double width, int n,
                               int* j0, int* j1) {
  double t;
  locate(g, s_lo + 0.5 * width, j0, &t);
  locate(g, s_lo + (n - 0.5) * width, j1, &t);
  if (t != 0.0) ++*j1;
}
// Linear interpolation of the workspace overlap v at arc length s (inside the run).
inline double interp_v(const WheelContactGeometry& g, const Workspace& w, double s) {
  int j;
  double t;
  locate(g, s, &j, &t);
  return std::max(lerp_at(w.v.data(), j, t), 0.0);
}
// Fills the strip fields that come from the band (position, angle, radius, u's) for strip s.
Strip band_strip(const WheelContactGeometry& g, const PointContext& p, double s, double width,
                 bool own_angle);

// Model evaluations at vertical approach dz: totals always, strips and patch fields when out.
// Strip half-lengths of a planar virtual-interpenetration run (Linder, Kik-Piotrowski): at each of
// the n strip centres of [run.s_lo, run.s_hi], L = sqrt(v / A) from the overlap v and the curvature
// A. Fills w.strip_len and w.strip_pos (lateral position from s_ref) and returns the largest L.
double planar_strip_lengths(const WheelContactGeometry& g, PointContext& p, Workspace& w,
                            const Run& run, int n, double s_ref, const NormalOptions& o);

PatchSums hertz_patch(const WheelContactGeometry& g, const Material& m, const NormalOptions& o,
                      PointContext& p, Workspace& w, double dz, ContactPatch* out);
PatchSums linder_patch(const WheelContactGeometry& g, const Material& m, const NormalOptions& o,
                       PointContext& p, Workspace& w, double dz, ContactPatch* out);
PatchSums kik_piotrowski_patch(const WheelContactGeometry& g, const Material& m,
                               const NormalOptions& o, PointContext& p, Workspace& w, double dz,
                               ContactPatch* out);
PatchSums stripes_patch(const WheelContactGeometry& g, const Material& m, const NormalOptions& o,
                        PointContext& p, Workspace& w, double dz, ContactPatch* out);
// STRIPES geometry-only preparation: negative-B treatment, epsilon and the pressure closure.
void prepare_stripes(const WheelContactGeometry& g, const Material& m, const NormalOptions& o,
                     PointContext& p, Workspace& w);

// Kik-Piotrowski Boussinesq closure (kik_piotrowski.cpp): for a patch with semi-elliptic strip
// pressure C sqrt(L_k^2 - x^2) on strips at lateral offsets y_k (from the reference point) of
// width w, returns I1 = sum int int sqrt(L^2-x^2) and I2 = sum int int sqrt(L^2-x^2)/r.
void kp_integrals(const double* L, const double* y, int n, double width, double* I1, double* I2);

// Model kinds and band positions, shared by the files of the layer.
inline bool is_stripes(NormalModel m) {
  return m == NormalModel::stripes_a || m == NormalModel::stripes_ab;
}
inline double band_position(const WheelContactGeometry& g, double s) {
  return (s - g.band.front().s) / g.band_step;
}

// The steps of a solve (normal_model.cpp unless named): prepare the points of a geometry; one
// point's patch at approach dz (dispatch to the model; out: the patch, or nullptr for the sums
// only); the summed vertical load at dz; the options check; the lift-off result.
void prepare(const WheelContactGeometry& g, const Material& m, const NormalOptions& o, Workspace& w);
PatchSums evaluate(const WheelContactGeometry& g, const Material& m, const NormalOptions& o,
                   PointContext& p, Workspace& w, double dz, ContactPatch* out);
double carried_load(const WheelContactGeometry& g, const Material& m, const NormalOptions& o,
                     Workspace& w, double dz);
void check_options(const NormalOptions& o);
WheelNormalResult lift_off(const WheelContactGeometry& g, StatusBits extra);
// Sets PointContext::weight of every point for approach dz (run_weights.cpp).
void run_weights(const WheelContactGeometry& g, Workspace& w, double dz);
// The wheel's patches at approach dz (patch_assembly.cpp); fill_single_hertz: the shortcut for one
// loaded Hertz point, false if it does not apply.
bool fill_single_hertz(const WheelContactGeometry& g, const Material& m, const NormalOptions& o,
                       Workspace& w, double dz, WheelNormalResult& out);
void fill(const WheelContactGeometry& g, const Material& m, const NormalOptions& o, Workspace& w,
          double dz, WheelNormalResult& out);

}  // namespace railtab::detail
