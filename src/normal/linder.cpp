// SPDX-License-Identifier: Apache-2.0
// Linder (with Brauchli, 1997): virtual interpenetration with the constant fraction eps = 0.55 of
// the Hertzian approach (Sichani et al. 2014; FACTS 2.2). Planar patch (reference normal), semi-elliptic
// pressure along every strip, p(x, s) = C sqrt(L(s)^2 - x^2), L(s) = sqrt(v(s)/A(s)).
// Load closure: the true approach delta is Hertz's for the load at the point (Enblom and Berg 2008 sec. 1.2:
// "interpenetration depth taken as a given fraction of the Hertzian body approach"), so
// N(delta) = N_Hertz(A0, B0, delta), and C distributes N over the VI patch. Where Hertz cannot run
// (A0 or B0 <= 0) the Kik-Piotrowski Boussinesq closure replaces it (kFallbackModel).
// For FASTSIM every strip gets a local ellipse with the same lateral semi-axis, the patch
// half-width (Sichani et al. 2014, "Local ellipse assignment").
#include <algorithm>
#include <cmath>
#include <numbers>

#include "normal/normal_internal.hpp"

namespace railtab::detail {

PatchSums linder_patch(const WheelContactGeometry& g, const Material& m, const NormalOptions& o,
                       PointContext& p, Workspace& w, double dz, ContactPatch* out) {
  const Run run = find_run(g, p, w, dz, o);
  if (!run.loaded) return {};
  const int n = o.strips;
  const double width = (run.s_hi - run.s_lo) / n;
  const double s_ref = g.points[p.point].band_s;
  const double L_max = planar_strip_lengths(g, p, w, run, n, s_ref, o);
  double I1 = 0.0;  // semi-elliptic strips: area-weighted sum of pi/2 L^2 per strip
  for (int k = 0; k < n; ++k) I1 += 0.5 * std::numbers::pi * w.strip_len[k] * w.strip_len[k] * width;
  if (!(I1 > 0.0)) return {};
  const double delta = (dz - p.h) * p.cos_ref;
  double N;
  if (p.hertz_valid) {
    const double AB = p.A0 + p.B0;
    // Hertz's force scaled by the run weight (normal_internal.hpp, run_weights).
    const double delta_w = p.weight != 1.0 ? delta * std::cbrt(p.weight * p.weight) : delta;
    const double c = std::sqrt(delta_w / (p.hz.r * AB));
    N = 4.0 * m.contact_modulus() * AB * c * c * c / 3.0;
  } else {
    double I2 = 0.0;
    kp_integrals(w.strip_len.data(), w.strip_pos.data(), n, width, &I1, &I2);
    N = I2 > 0.0 ? std::numbers::pi * m.contact_modulus() * delta * I1 / I2 : 0.0;
  }
  const PatchSums sums{N, N * p.cos_ref};
  if (!out) return sums;
  const double C = N / I1;
  const double half_width = 0.5 * (run.s_hi - run.s_lo);
  out->pressure_shape = StripPressure::semi_elliptic;
  out->normal_force = N;
  out->max_pressure = C * L_max;
  out->semi_axis_a = L_max;
  out->semi_axis_b = half_width;
  if (!p.hertz_valid) out->status |= status::kFallbackModel;
  if (run.at_band_end) out->status |= status::kProfileEdge;
  out->strips.reserve(n);
  double area = 0.0;
  for (int k = 0; k < n; ++k) {
    const double L = w.strip_len[k];
    Strip st = band_strip(g, p, run.s_lo + (k + 0.5) * width, width, false);
    st.x_lead = L;
    st.x_trail = -L;
    st.pressure_peak = C * L;
    st.ellipse_a = L;
    st.ellipse_b = half_width;
    area += 2.0 * L * width;
    out->strips.push_back(st);
  }
  out->area = area;
  return sums;
}

}  // namespace railtab::detail
