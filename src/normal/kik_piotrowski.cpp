// SPDX-License-Identifier: Apache-2.0
// Kik-Piotrowski (Piotrowski & Kik, VSD 46 (2008) 27-48; FACTS 2.3, verified against the public
// implementation K1): virtual interpenetration with eps = 0.55, planar patch (reference normal),
// semi-elliptic pressure along every strip p(x, s) = C sqrt(L(s)^2 - x^2), L(s) = sqrt(v(s)/A(s)).
// Non-iterative load closure: the Boussinesq displacement of the assumed pressure at the reference
// point equals the true approach delta,
//   delta = (1/(pi E*)) int int p / r  =>  N = pi E* delta I1 / I2,
//   I1 = int int sqrt(L^2 - x^2),  I2 = int int sqrt(L^2 - x^2) / sqrt(x^2 + y^2).
// (FACTS writes the prefactor as pi E delta / (2 (1 - nu^2)), the same as pi E* delta.)
// Needs no positive curvature: this is also the fallback of Hertz where A or B <= 0.
// For FASTSIM one equivalent ellipse per patch that keeps the area and the length/width ratio of the
// patch (CONTACT's equiv_ellipse, FACTS 2.3): a = sqrt(S/pi) sqrt(L/W), b = sqrt(S/pi) sqrt(W/L).
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "normal/normal_internal.hpp"

namespace railtab::detail {
namespace {

// Gauss-Legendre nodes/weights on [0, 1].
template <int N>
struct Gauss {
  std::array<double, N> x, w;
  Gauss() {
    for (int i = 0; i < N; ++i) {  // Newton on P_N from the Chebyshev-like start (Numerical Recipes)
      double z = std::cos(std::numbers::pi * (i + 0.75) / (N + 0.5)), dp = 1.0;
      for (int it = 0; it < 100; ++it) {
        double p1 = 1.0, p2 = 0.0;
        for (int j = 1; j <= N; ++j) {
          const double p3 = p2;
          p2 = p1;
          p1 = ((2.0 * j - 1.0) * z * p2 - (j - 1.0) * p3) / j;
        }
        dp = N * (z * p1 - p2) / (z * z - 1.0);
        const double dz = p1 / dp;
        z -= dz;
        if (std::abs(dz) < 1e-16) break;
      }
      x[i] = 0.5 * (1.0 - z);
      w[i] = 1.0 / ((1.0 - z * z) * dp * dp);  // = 2/((1-z^2) P'^2) scaled to [0, 1]
    }
  }
};

// Quadrature rules with the node functions precomputed (they do not depend on the strip).
struct FarRule {  // x = L sin(theta), theta = (pi/2) t, 8 nodes: weight (pi/2) w cos^2, sin^2
  std::array<double, 8> w, s2;
  FarRule() {
    Gauss<8> g;
    for (int i = 0; i < 8; ++i) {
      const double th = 0.5 * std::numbers::pi * g.x[i];
      const double st = std::sin(th), ct = std::cos(th);
      w[i] = 0.5 * std::numbers::pi * g.w[i] * ct * ct;
      s2[i] = st * st;
    }
  }
};
struct NearRule {  // theta = (pi/2) t^2, 16 nodes: weight pi t w cos^2, sin
  std::array<double, 16> w, s;
  NearRule() {
    Gauss<16> g;
    for (int i = 0; i < 16; ++i) {
      const double t = g.x[i];
      const double th = 0.5 * std::numbers::pi * t * t;
      w[i] = g.w[i] * std::cos(th) * std::cos(th) * std::numbers::pi * t;
      s[i] = std::sin(th);
    }
  }
};
const FarRule& far_rule() {
  static const FarRule r;
  return r;
}
const NearRule& near_rule() {
  static const NearRule r;
  return r;
}

// asinh(y2/x) - asinh(y1/x) for x > 0, y1 < y2, as one logarithm: with R = sqrt(x^2 + y^2),
// asinh(y/x) = ln((y + R)/x); for y < 0, y + R = x^2/(R - y) avoids the cancellation.
inline double asinh_difference(double x, double y1, double y2) {
  const double x2 = x * x;
  const double r1 = std::sqrt(x2 + y1 * y1), r2 = std::sqrt(x2 + y2 * y2);
  const double u2 = y2 >= 0.0 ? y2 + r2 : x2 / (r2 - y2);
  const double u1 = y1 >= 0.0 ? y1 + r1 : x2 / (r1 - y1);
  return std::log(u2 / u1);
}

}  // namespace

void kp_integrals(const double* L, const double* y, int n, double width, double* I1, double* I2) {
  const FarRule& fr = far_rule();
  const NearRule& nr = near_rule();
  const double half_pi = 0.5 * std::numbers::pi;
  double s1 = 0.0, s2 = 0.0;
  for (int k = 0; k < n; ++k) {
    const double Lk = L[k];
    if (!(Lk > 0.0)) continue;
    const double L2 = Lk * Lk;
    s1 += half_pi * L2 * width;
    const double y1 = y[k] - 0.5 * width, y2 = y[k] + 0.5 * width;
    if (std::abs(y[k]) >= 6.0 * width) {
      // Far strip: midpoint in y; x = L sin(theta) makes the x integrand smooth.
      const double yy = y[k] * y[k];
      double acc = 0.0;
      for (int i = 0; i < 8; ++i) acc += fr.w[i] / std::sqrt(L2 * fr.s2[i] + yy);
      s2 += width * 2.0 * L2 * acc;
    } else {
      // Near strip: the y integral in closed form, int dy/sqrt(x^2+y^2) = asinh(y/|x|), leaves a
      // logarithmic singularity at x = 0, tamed by theta = (pi/2) t^2.
      double acc = 0.0;
      for (int i = 0; i < 16; ++i) acc += nr.w[i] * asinh_difference(Lk * nr.s[i], y1, y2);
      s2 += 2.0 * L2 * acc;
    }
  }
  *I1 = s1;
  *I2 = s2;
}

PatchSums kik_piotrowski_patch(const WheelContactGeometry& g, const Material& m,
                               const NormalOptions& o, PointContext& p, Workspace& w, double dz,
                               ContactPatch* out) {
  const Run run = find_run(g, p, w, dz, o);
  if (!run.loaded) return {};
  const int n = o.strips;
  const double width = (run.s_hi - run.s_lo) / n;
  const double s_ref = g.points[p.point].band_s;
  const double L_max = planar_strip_lengths(g, p, w, run, n, s_ref, o);
  double I1 = 0.0, I2 = 0.0;
  kp_integrals(w.strip_len.data(), w.strip_pos.data(), n, width, &I1, &I2);
  if (!(I1 > 0.0) || !(I2 > 0.0)) return {};
  const double delta = (dz - p.h) * p.cos_ref;
  const double N = std::numbers::pi * m.contact_modulus() * delta * I1 / I2;
  const PatchSums sums{N, N * p.cos_ref};
  if (!out) return sums;
  const double C = N / I1;
  double area = 0.0;
  for (int k = 0; k < n; ++k) area += 2.0 * w.strip_len[k] * width;
  const double length = 2.0 * L_max, patch_width = run.s_hi - run.s_lo;
  const double a_eq = std::sqrt(area / std::numbers::pi) * std::sqrt(length / patch_width);
  const double b_eq = std::sqrt(area / std::numbers::pi) * std::sqrt(patch_width / length);
  out->pressure_shape = StripPressure::semi_elliptic;
  out->normal_force = N;
  out->area = area;
  out->max_pressure = C * L_max;
  out->semi_axis_a = a_eq;
  out->semi_axis_b = b_eq;
  if (run.at_band_end) out->status |= status::kProfileEdge;
  out->strips.reserve(n);
  for (int k = 0; k < n; ++k) {
    const double L = w.strip_len[k];
    Strip st = band_strip(g, p, run.s_lo + (k + 0.5) * width, width, false);
    st.x_lead = L;
    st.x_trail = -L;
    st.pressure_peak = C * L;
    st.ellipse_a = a_eq;
    st.ellipse_b = b_eq;
    out->strips.push_back(st);
  }
  return sums;
}

}  // namespace railtab::detail
