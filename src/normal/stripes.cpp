// STRIPES (Ayasse & Chollet 2005) with the A- and the A&B-correction of seed 000 (FACTS 2.4).
//
// Patch: virtual interpenetration along the band; every strip follows its own contact angle (the
// patch is not planar, seed 001 sec. 1.2). Strip half-length a_i = sqrt(v_i / A_ci) with the
// corrected longitudinal curvature (seed 000):
//   A-correction:    eps = n0^2 B0 / (r0 (A0 + B0)),        A_ci = (n_i/m_i)^2 B_i
//   A&B-correction:  eps = n0^2 / (r0 (1 + (n0/m0)^2)),     A_ci = (A_i + B_i)(n_i/m_i)^2/(1 + (n_i/m_i)^2)
// (m, n of seed 000 belong to the rolling and lateral directions; (n_i/m_i)^2 is the local Hertz
// (b/a)^2.) The lateral extent always comes from the real separation (FACTS 2.4.2).
// Pressure: parabolic along each strip (Kalker's simplified theory, seed 001 sec. 1.2), proportional
// to the local virtual overlap (FACTS 2.4.4): p(x, s) = p_max (v(s) - A_c(s) x^2) / (eps delta0).
// Closure (FACTS 2.4.5): p_max = (4/3) p0_Hertz(A0, B0, delta0); with the A-correction on a Hertz
// geometry this reproduces Hertz's load-approach law exactly.
//
// Negative or small B (FACTS 2.4.6): B enters only the local Hertz shapes (n_i/m_i) and the
// corrections, never the lateral extent. Default NegativeCurvature::shift with stripes_ab, as in
// seed 000's proposal: shifting keeps the B distribution's variation (no sharp changes, no smoothing
// that smears pressure peaks), and the A&B-correction stays finite as B -> 0 (A_c -> A + B), while
// the A-correction's A_c = (n/m)^2 B grows like A^(4/3) B^(-1/3) and makes strips collapse where B
// is small. The shift is B_i += max(0, B_floor - min B) over the band samples within
// curvature_window of the point's gap, B_floor = min_curvature_ratio A0; the window depends on the
// geometry only, so N(delta) stays continuous for the load control.
// clip_and_smooth (classic STRIPES): B_i = max(B_i, B_floor), then a moving average of half-width
// smoothing_half_width over the window.
#include <algorithm>
#include <cmath>
#include <numbers>

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
  auto B_at = [&](int j) { return 0.5 * (g.band[j].curvature_wheel + g.band[j].curvature_rail); };
  double B_min = std::isfinite(p.B0) ? p.B0 : floor;
  for (int j = wlo; j <= whi; ++j) B_min = std::min(B_min, B_at(j));
  if (o.negative_curvature == NegativeCurvature::shift) {
    const double shift = std::max(0.0, floor - B_min);
    for (int j = p.lo; j <= p.hi; ++j) w.B_treated[j] = B_at(j) + shift;
    p.B0t = (std::isfinite(p.B0) ? p.B0 : floor) + shift;
    if (shift > 0.0) p.flags |= status::kCurvatureShifted;
  } else {
    for (int j = p.lo; j <= p.hi; ++j) w.B_treated[j] = std::max(B_at(j), floor);
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
                                                                   std::max(B_at(p.i0), floor));
    p.B0t = std::max(p.B0t, floor);
  }
  const double A0 = p.A0, B0 = p.B0t;
  const HertzCoefficients hz = hertz_coefficients(A0, B0);
  const double m0 = hz.coef_a, n0 = hz.coef_b, r0 = hz.r;
  const double nm2 = (n0 / m0) * (n0 / m0);
  p.eps = p.model == NormalModel::stripes_a ? n0 * n0 * B0 / (r0 * (A0 + B0))
                                            : n0 * n0 / (r0 * (1.0 + nm2));
  p.pmax_coef = (4.0 / 3.0) * m.contact_modulus() * std::sqrt((A0 + B0) / (hz.K * hz.E));
}

PatchSums stripes_patch(const WheelContactGeometry& g, const Material& /*m*/,
                        const NormalOptions& o, PointContext& p, Workspace& w, double dz,
                        ContactPatch* out) {
  const Run run = find_run(g, p, w, dz, o);
  if (!run.loaded) return {};
  const double delta0 = (dz - p.h) * p.cos_ref;
  const double p_max = p.pmax_coef * std::sqrt(delta0);
  const double scale = p_max / (p.eps * delta0);  // pressure per unit virtual overlap [Pa/m]
  const int n = o.strips;
  const double width = (run.s_hi - run.s_lo) / n;
  PatchSums sums;
  double area = 0.0;
  if (out) out->strips.reserve(n);
  for (int k = 0; k < n; ++k) {
    const double s = run.s_lo + (k + 0.5) * width;
    const double v = interp_v(g, w, s);
    const SampleData d = interp_sample(g, p, w, s, o);
    const double a = d.A > 0.0 ? std::sqrt(v / d.A) : 0.0;
    const double pk = scale * v;
    const double Nk = (4.0 / 3.0) * pk * a * width;  // parabola: int p0 (1 - x^2/a^2) = 4/3 p0 a
    sums.normal += Nk;
    sums.vertical += Nk * d.cos_angle;
    if (out) {
      Strip st = band_strip(g, p, s, width, true);
      st.x_lead = a;
      st.x_trail = -a;
      st.pressure_peak = pk;
      st.ellipse_a = a;
      st.ellipse_b = a * std::sqrt(d.q);  // local virtual ellipse: b/a = n_i/m_i
      area += 2.0 * a * width;
      out->strips.push_back(st);
    }
  }
  if (out) {
    out->pressure_shape = StripPressure::parabolic;
    out->normal_force = sums.normal;
    out->area = area;
    out->max_pressure = scale * run.v_max;
    if (run.at_band_end) out->status |= status::kProfileEdge;
  }
  return sums;
}

}  // namespace railtab::detail
