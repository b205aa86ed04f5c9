// SPDX-License-Identifier: Apache-2.0
// Kalker's creepage coefficients C11, C22, C23 of the linear theory (kalker_coefficients.hpp).
#include "tangential/kalker_coefficients.hpp"

#include <cmath>
#include <numbers>

#include "core/check.hpp"

namespace railtab {

namespace kalker_table {

// clang-format off
const double kValues[2][kRows][3][3] = {
  {  // a <= b, g = a/b:     C11 (nu 0, .25, .5)   C22                  C23
    {{2.51, 3.31, 4.85}, {2.51, 2.52, 2.53}, {0.334, 0.473, 0.731}},  // 0.1
    {{2.59, 3.37, 4.81}, {2.59, 2.63, 2.66}, {0.483, 0.603, 0.809}},  // 0.2
    {{2.68, 3.44, 4.80}, {2.68, 2.75, 2.81}, {0.607, 0.715, 0.889}},  // 0.3
    {{2.78, 3.53, 4.82}, {2.78, 2.88, 2.98}, {0.720, 0.823, 0.977}},  // 0.4
    {{2.88, 3.62, 4.83}, {2.88, 3.01, 3.14}, {0.827, 0.929, 1.07}},   // 0.5
    {{2.98, 3.72, 4.91}, {2.98, 3.14, 3.31}, {0.930, 1.03, 1.18}},    // 0.6
    {{3.09, 3.81, 4.97}, {3.09, 3.28, 3.48}, {1.03, 1.14, 1.29}},     // 0.7
    {{3.19, 3.91, 5.05}, {3.19, 3.41, 3.65}, {1.13, 1.25, 1.40}},     // 0.8 (1.25, not 1.15)
    {{3.29, 4.01, 5.12}, {3.29, 3.54, 3.82}, {1.23, 1.36, 1.51}},     // 0.9
    {{3.40, 4.12, 5.20}, {3.40, 3.67, 3.98}, {1.33, 1.47, 1.63}},     // 1.0
  },
  {  // a >= b, g = b/a
    {{10.7, 11.7, 12.9}, {10.7, 12.8, 16.0}, {12.2, 14.6, 18.0}},     // 0.1
    {{6.96, 7.78, 8.82}, {6.96, 8.14, 9.79}, {5.72, 6.63, 7.89}},     // 0.2
    {{5.57, 6.34, 7.34}, {5.57, 6.40, 7.51}, {3.79, 4.32, 5.01}},     // 0.3
    {{4.84, 5.57, 6.57}, {4.84, 5.48, 6.31}, {2.88, 3.24, 3.70}},     // 0.4
    {{4.37, 5.10, 6.11}, {4.37, 4.90, 5.56}, {2.35, 2.62, 2.96}},     // 0.5
    {{4.06, 4.78, 5.80}, {4.06, 4.50, 5.04}, {2.01, 2.23, 2.50}},     // 0.6
    {{3.82, 4.54, 5.58}, {3.82, 4.21, 4.67}, {1.76, 1.95, 2.18}},     // 0.7
    {{3.65, 4.36, 5.42}, {3.65, 3.99, 4.39}, {1.58, 1.75, 1.94}},     // 0.8
    {{3.51, 4.22, 5.30}, {3.51, 3.81, 4.16}, {1.44, 1.59, 1.77}},     // 0.9
    {{3.40, 4.12, 5.20}, {3.40, 3.67, 3.98}, {1.33, 1.47, 1.63}},     // 1.0
  },
};
// clang-format on

KalkerCoefficients asymptote(int branch, double g, double nu) {
  constexpr double pi = std::numbers::pi;
  KalkerCoefficients c;
  if (branch == 0) {  // a << b: narrow strip across the rolling direction
    c.c11 = pi * pi / (4.0 * (1.0 - nu));
    c.c22 = pi * pi / 4.0;
    c.c23 = pi * std::sqrt(g) / (3.0 * (1.0 - nu)) * (1.0 + nu * (std::log(16.0 / g) - 5.0));
  } else {  // a >> b: long narrow patch
    const double lam = std::log(16.0 / (g * g));
    const double c3 = 3.0 - std::log(4.0);
    c.c11 = 2.0 * pi / ((lam - 2.0 * nu) * g) * (1.0 + c3 / (lam - 2.0 * nu));
    const double d22 = (1.0 - nu) * lam + 2.0 * nu;
    c.c22 = 2.0 * pi / g * (1.0 + (1.0 - nu) * c3 / d22) / d22;
    c.c23 = 2.0 * pi / (3.0 * std::pow(g, 1.5) * ((1.0 - nu) * lam - 2.0 + 4.0 * nu));
  }
  return c;
}

}  // namespace kalker_table

namespace {

using kalker_table::kRows;
using kalker_table::kValues;
constexpr double kStep = 0.1;  // row spacing in g [-]

// Fritsch-Butland weighted harmonic mean of two neighbouring slopes (PCHIP interior rule).
double pchip_slope(double h0, double d0, double h1, double d1) {
  if (d0 * d1 <= 0.0) return 0.0;
  const double w1 = 2.0 * h1 + h0;
  const double w2 = h1 + 2.0 * h0;
  return (w1 + w2) / (w1 / d0 + w2 / d1);
}

// One-sided three-point end slope with PCHIP's shape safeguards.
double pchip_end_slope(double h0, double d0, double h1, double d1) {
  double d = ((2.0 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
  if (d * d0 <= 0.0) return 0.0;
  if (d0 * d1 <= 0.0 && std::abs(d) > 3.0 * std::abs(d0)) return 3.0 * d0;
  return d;
}

// Node derivatives dC/dg, same layout as kValues. Built once.
struct Slopes {
  double d[2][kRows][3][3];
  Slopes() {
    for (int br = 0; br < 2; ++br)
      for (int k = 0; k < 3; ++k)
        for (int col = 0; col < 3; ++col) {
          auto v = [&](int r) { return kValues[br][r][k][col]; };
          d[br][0][k][col] =
              pchip_end_slope(kStep, (v(1) - v(0)) / kStep, kStep, (v(2) - v(1)) / kStep);
          for (int r = 1; r < kRows - 1; ++r)
            d[br][r][k][col] =
                pchip_slope(kStep, (v(r) - v(r - 1)) / kStep, kStep, (v(r + 1) - v(r)) / kStep);
        }
    // a/b = 1 is an interior node in kappa = a/b: neighbours kappa = 0.9 (branch 0) and 1/0.9
    // (branch 1). dC/dg = dC/dkappa on branch 0 and -dC/dkappa on branch 1 (g = 1/kappa).
    for (int k = 0; k < 3; ++k)
      for (int col = 0; col < 3; ++col) {
        const double c1 = kValues[0][kRows - 1][k][col];
        const double h0 = 0.1, h1 = 1.0 / 0.9 - 1.0;
        const double s0 = (c1 - kValues[0][kRows - 2][k][col]) / h0;
        const double s1 = (kValues[1][kRows - 2][k][col] - c1) / h1;
        const double dk = pchip_slope(h0, s0, h1, s1);
        d[0][kRows - 1][k][col] = dk;
        d[1][kRows - 1][k][col] = -dk;
      }
  }
};

const Slopes& slopes() {
  static const Slopes s;
  return s;
}

// Quadratic Lagrange weights through nu = 0, 0.25, 0.5.
void poisson_weights(double nu, double w[3]) {
  w[0] = 8.0 * (nu - 0.25) * (nu - 0.5);
  w[1] = -16.0 * nu * (nu - 0.5);
  w[2] = 8.0 * nu * (nu - 0.25);
}

// Table value at g in [0.1, 1] of one branch, interpolated in g (per column) and in nu (1/C).
KalkerCoefficients table_value(int br, double g, double nu) {
  const Slopes& s = slopes();
  int r = static_cast<int>(std::floor(g / kStep + 1e-12)) - 1;  // interval [g_r, g_r+1]
  if (r < 0) r = 0;
  if (r > kRows - 2) r = kRows - 2;
  const double t = (g - kStep * (r + 1)) / kStep;
  const double t2 = t * t, t3 = t2 * t;
  const double h00 = 2 * t3 - 3 * t2 + 1, h10 = t3 - 2 * t2 + t, h01 = -2 * t3 + 3 * t2,
               h11 = t3 - t2;
  double w[3];
  poisson_weights(nu, w);
  double out[3];
  for (int k = 0; k < 3; ++k) {
    double inv = 0.0;
    for (int col = 0; col < 3; ++col) {
      const double c = h00 * kValues[br][r][k][col] + h10 * kStep * s.d[br][r][k][col] +
                       h01 * kValues[br][r + 1][k][col] + h11 * kStep * s.d[br][r + 1][k][col];
      inv += w[col] / c;
    }
    out[k] = 1.0 / inv;
  }
  return {out[0], out[1], out[2]};
}

}  // namespace

KalkerCoefficients kalker_coefficients(double a_over_b, double poisson_ratio) {
  RAILTAB_CHECK(std::isfinite(a_over_b) && a_over_b > 0.0,
                "kalker_coefficients: ellipse ratio a/b = {} must be finite and positive", a_over_b);
  RAILTAB_CHECK(poisson_ratio >= 0.0 && poisson_ratio <= 0.5,
                "kalker_coefficients: Poisson's ratio {} outside [0, 0.5]", poisson_ratio);
  const int br = a_over_b <= 1.0 ? 0 : 1;
  const double g = br == 0 ? a_over_b : 1.0 / a_over_b;
  constexpr double g_min = 0.1;
  if (g >= g_min) return table_value(br, g, poisson_ratio);
  // Below the table: asymptote scaled by (table/asymptote at g_min)^(g/g_min).
  const KalkerCoefficients t0 = table_value(br, g_min, poisson_ratio);
  const KalkerCoefficients a0 = kalker_table::asymptote(br, g_min, poisson_ratio);
  const KalkerCoefficients a = kalker_table::asymptote(br, g, poisson_ratio);
  const double w = g / g_min;
  return {a.c11 * std::pow(t0.c11 / a0.c11, w), a.c22 * std::pow(t0.c22 / a0.c22, w),
          a.c23 * std::pow(t0.c23 / a0.c23, w)};
}

}  // namespace railtab
