// SPDX-License-Identifier: Apache-2.0
// Kalker's creepage coefficients C11, C22, C23 of the linear theory of rolling contact, as functions
// of the ellipse ratio a/b (a along the rolling direction x, b lateral) and Poisson's ratio.
//
// Data: Table E.3 of Kalker, "Three-dimensional elastic bodies in rolling contact" (1990), as
// carried by CONTACT's m_hertz.f90 (`linrol`), columns nu = 0, 0.25, 0.5. usetab_table.f90 has the
// typo C23(a/b = 0.8, nu = 0.25) = 1.15; the monotone column shows 1.25 is right and is used here.
//
// Interpolation (smooth, unlike CONTACT's piecewise-linear one, because table derivatives matter):
// - in the ellipse ratio: monotone cubic Hermite (Fritsch-Butland / PCHIP) in g = min(a/b, b/a)
//   inside each branch (a <= b and a >= b); the node derivative at a/b = 1 is shared by both
//   branches (taken in kappa = a/b from the points 0.9, 1, 1/0.9), so C is C1 across a/b = 1;
// - in nu: CONTACT's quadratic Lagrange interpolation of 1/C through nu = 0, 0.25, 0.5;
// - outside the table (g < 0.1): Kalker's closed-form asymptotes, multiplied by the ratio
//   (table/asymptote at g = 0.1) raised to the power g/0.1, so C is continuous at g = 0.1 and tends
//   to the asymptote as g -> 0.
// Tabulated points are reproduced exactly (to rounding) at nu = 0, 0.25, 0.5.
//
// C33 (spin moment due to spin) is deliberately absent: it is not in CONTACT's table and no
// trustworthy source for it was found; FASTSIM needs only C11, C22, C23.
#pragma once

namespace railtab {

struct KalkerCoefficients {
  double c11 = 0.0;  // longitudinal creepage -> longitudinal force [-]
  double c22 = 0.0;  // lateral creepage -> lateral force [-]
  double c23 = 0.0;  // spin -> lateral force (and lateral creepage -> spin moment) [-]
};

// a_over_b > 0 (finite), 0 <= poisson_ratio <= 0.5; throws railtab::Error otherwise.
KalkerCoefficients kalker_coefficients(double a_over_b, double poisson_ratio);

namespace kalker_table {
inline constexpr int kRows = 10;                               // g = 0.1, 0.2, ..., 1.0
inline constexpr double kPoisson[3] = {0.0, 0.25, 0.5};        // table columns [-]
// kValues[branch][row][coefficient][nu column]: branch 0: a <= b, g = a/b; branch 1: a >= b,
// g = b/a; row r is g = 0.1 (r + 1); coefficient 0 = C11, 1 = C22, 2 = C23.
extern const double kValues[2][kRows][3][3];
// Closed-form asymptote for g = min(a/b, b/a) -> 0 (used below g = 0.1); branch as above.
KalkerCoefficients asymptote(int branch, double g, double poisson_ratio);
}  // namespace kalker_table

}  // namespace railtab
