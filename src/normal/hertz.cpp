// SPDX-License-Identifier: Apache-2.0
// Hertz contact of two identical elastic bodies (hertz.hpp): semi-axes, approach, pressure.
#include "normal/hertz.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/check.hpp"
#include "normal/normal_internal.hpp"

namespace railtab {
namespace {

void check_curvatures(double A, double B) {
  RAILTAB_CHECK(std::isfinite(A) && std::isfinite(B) && A > 0.0 && B > 0.0,
                "Hertz needs positive relative curvatures, got A = {} 1/m, B = {} 1/m", A, B);
}

// c of FACTS 1.3 for a given force: c^3 = 3 N (1 - nu^2) / (2 E (A + B)) = 3 N / (4 E* (A + B)).
HertzContact finish(double A, double B, double c, const HertzCoefficients& k,
                    const HertzShape& shape, const Material& material) {
  HertzContact h;
  h.shape = shape;
  h.coef_a = k.coef_a;
  h.coef_b = k.coef_b;
  h.a = k.coef_a * c;
  h.b = k.coef_b * c;
  h.approach = k.r * (A + B) * c * c;
  h.normal_force = 4.0 * material.contact_modulus() * (A + B) * c * c * c / 3.0;
  h.area = std::numbers::pi * h.a * h.b;
  h.p0 = h.area > 0.0 ? 1.5 * h.normal_force / h.area : 0.0;
  return h;
}

HertzShape shape_for(double A, double B) { return hertz_shape(std::min(A, B) / std::max(A, B)); }

HertzCoefficients coefficients_from(double A, double B, const HertzShape& s) {
  // The long axis lies along the smaller curvature (FACTS 1.2).
  return A <= B ? HertzCoefficients{s.m, s.n, s.r, s.K, s.E}
                : HertzCoefficients{s.n, s.m, s.r, s.K, s.E};
}

}  // namespace

double HertzContact::pressure(double x, double y) const {
  if (a <= 0.0 || b <= 0.0) return 0.0;
  const double q = 1.0 - (x / a) * (x / a) - (y / b) * (y / b);
  return q > 0.0 ? p0 * std::sqrt(q) : 0.0;
}

HertzCoefficients hertz_coefficients(double A, double B) {
  check_curvatures(A, B);
  return coefficients_from(A, B, shape_for(A, B));
}

namespace detail {
HertzCoefficients hertz_coefficients_fast(double A, double B) {
  check_curvatures(A, B);
  const double ratio = std::min(A, B) / std::max(A, B);
  const double g = hertz_axis_ratio_fast(ratio);  // table, relative error < 1e-9
  const EllipticKE ke = complete_elliptic_complementary(g);
  const double m = std::cbrt(2.0 * ke.E / (std::numbers::pi * g * g));
  const double n = std::cbrt(2.0 * ke.E * g / std::numbers::pi);
  const double r = 2.0 * ke.K / (std::numbers::pi * m);
  return A <= B ? HertzCoefficients{m, n, r, ke.K, ke.E} : HertzCoefficients{n, m, r, ke.K, ke.E};
}
}  // namespace detail

HertzContact hertz_for_force(double A, double B, double normal_force, const Material& material) {
  check_curvatures(A, B);
  RAILTAB_CHECK(std::isfinite(normal_force) && normal_force >= 0.0,
                "hertz_for_force: normal force {} N must be finite and >= 0", normal_force);
  const HertzShape s = shape_for(A, B);
  const double c = std::cbrt(3.0 * normal_force / (4.0 * material.contact_modulus() * (A + B)));
  return finish(A, B, c, coefficients_from(A, B, s), s, material);
}

HertzContact hertz_for_approach(double A, double B, double approach, const Material& material) {
  check_curvatures(A, B);
  RAILTAB_CHECK(std::isfinite(approach) && approach >= 0.0,
                "hertz_for_approach: approach {} m must be finite and >= 0", approach);
  const HertzShape s = shape_for(A, B);
  const double c = std::sqrt(approach / (s.r * (A + B)));
  return finish(A, B, c, coefficients_from(A, B, s), s, material);
}

}  // namespace railtab

// ---- Hertz as a normal-contact model (normal_model.hpp) ----------------------------------------

namespace railtab::detail {

PatchSums hertz_patch(const WheelContactGeometry& g, const Material& m, const NormalOptions& o,
                      PointContext& p, Workspace& /*w*/, double dz, ContactPatch* out) {
  // Coefficients were found once per solve (prepare); here only the closed forms of FACTS 1.3.
  double delta = (dz - p.h) * p.cos_ref;
  if (p.weight != 1.0) delta *= std::cbrt(p.weight * p.weight);  // force scaled by the run weight
  const double AB = p.A0 + p.B0;
  const double c = std::sqrt(delta / (p.hz.r * AB));
  const double N = 4.0 * m.contact_modulus() * AB * c * c * c / 3.0;
  PatchSums sums{N, N * p.cos_ref};
  if (!out || !(N > 0.0)) return sums;
  const double a = p.hz.coef_a * c, b = p.hz.coef_b * c;
  const double p0 = 1.5 * N / (std::numbers::pi * a * b);
  out->pressure_shape = StripPressure::semi_elliptic;
  out->normal_force = N;
  out->area = std::numbers::pi * a * b;
  out->max_pressure = p0;
  out->semi_axis_a = a;
  out->semi_axis_b = b;
  if (!o.hertz_strips) return sums;
  const int n = o.strips;
  const double width = 2.0 * b / n;
  const double s0 = g.points[p.point].band_s;
  out->strips.reserve(n);
  for (int k = 0; k < n; ++k) {
    const double y = -b + (k + 0.5) * width;
    const double f = std::sqrt(std::max(0.0, 1.0 - (y / b) * (y / b)));
    Strip st = band_strip(g, p, s0 + y, width, false);
    st.x_lead = a * f;
    st.x_trail = -a * f;
    st.pressure_peak = p0 * f;
    st.ellipse_a = a;
    st.ellipse_b = b;
    out->strips.push_back(st);
  }
  return sums;
}

}  // namespace railtab::detail
