// SPDX-License-Identifier: Apache-2.0
// Tests of Kalker's creepage coefficients (src/tangential/kalker_coefficients.hpp).
#include "tangential/kalker_coefficients.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/check.hpp"

namespace railtab {
namespace {

using kalker_table::kPoisson;
using kalker_table::kRows;
using kalker_table::kValues;

double coef(const KalkerCoefficients& c, int k) { return k == 0 ? c.c11 : (k == 1 ? c.c22 : c.c23); }
double ratio_of(int branch, int row) {
  const double g = 0.1 * (row + 1);
  return branch == 0 ? g : 1.0 / g;
}

TEST(KalkerCoefficients, ReproducesEveryTabulatedPoint) {
  for (int br = 0; br < 2; ++br)
    for (int r = 0; r < kRows; ++r)
      for (int col = 0; col < 3; ++col) {
        const KalkerCoefficients c = kalker_coefficients(ratio_of(br, r), kPoisson[col]);
        for (int k = 0; k < 3; ++k)
          EXPECT_NEAR(coef(c, k), kValues[br][r][k][col], 1e-9 * kValues[br][r][k][col])
              << "branch " << br << " g " << 0.1 * (r + 1) << " nu " << kPoisson[col] << " C"
              << (k == 0 ? "11" : k == 1 ? "22" : "23");
      }
}

TEST(KalkerCoefficients, SpotValuesAndTypoTrap) {
  // Values read off Kalker's Table E.3 (FACTS 3.4), not from kValues.
  EXPECT_NEAR(kalker_coefficients(1.0, 0.25).c11, 4.12, 1e-12);
  EXPECT_NEAR(kalker_coefficients(1.0, 0.25).c22, 3.67, 1e-12);
  EXPECT_NEAR(kalker_coefficients(1.0, 0.25).c23, 1.47, 1e-12);
  EXPECT_NEAR(kalker_coefficients(0.8, 0.25).c23, 1.25, 1e-12);  // usetab_table.f90 has 1.15
  EXPECT_NEAR(kalker_coefficients(1.0 / 0.1, 0.5).c22, 16.0, 1e-9);
  EXPECT_NEAR(kalker_coefficients(0.1, 0.0).c23, 0.334, 1e-12);
}

TEST(KalkerCoefficients, PoissonInterpolationMatchesDerivedNu03Values) {
  struct Row { double ratio, c11, c22, c23; };
  // FACTS 3.4, CONTACT's 1/C quadratic interpolation, rounded to 3-4 digits.
  const Row rows[] = {
      {0.1, 3.535, 2.522, 0.512},       {0.2, 3.585, 2.637, 0.635},
      {0.5, 3.813, 3.036, 0.953},       {0.8, 4.095, 3.456, 1.277},
      {1.0, 4.300, 3.729, 1.500},       {1.0 / 0.9, 4.399, 3.876, 1.623},
      {1.0 / 0.5, 5.275, 5.020, 2.682}, {1.0 / 0.3, 6.519, 6.596, 4.443},
      {1.0 / 0.1, 11.92, 13.33, 15.18},
  };
  for (const Row& r : rows) {
    const KalkerCoefficients c = kalker_coefficients(r.ratio, 0.3);
    EXPECT_NEAR(c.c11, r.c11, 6e-4 * r.c11) << "a/b " << r.ratio;
    EXPECT_NEAR(c.c22, r.c22, 6e-4 * r.c22) << "a/b " << r.ratio;
    EXPECT_NEAR(c.c23, r.c23, 6e-4 * r.c23) << "a/b " << r.ratio;
  }
}

TEST(KalkerCoefficients, ContinuousAcrossBranchesAndTableEnds) {
  for (double nu : {0.0, 0.25, 0.28, 0.3, 0.5}) {
    for (double x0 : {1.0, 0.1, 10.0}) {
      const KalkerCoefficients lo = kalker_coefficients(x0 * (1.0 - 1e-9), nu);
      const KalkerCoefficients hi = kalker_coefficients(x0 * (1.0 + 1e-9), nu);
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(coef(lo, k), coef(hi, k), 1e-7 * coef(hi, k)) << "a/b " << x0 << " nu " << nu;
    }
    // C1 across a/b = 1: one-sided difference quotients agree.
    const double h = 1e-5;
    const KalkerCoefficients c0 = kalker_coefficients(1.0, nu);
    const KalkerCoefficients cl = kalker_coefficients(1.0 - h, nu);
    const KalkerCoefficients cr = kalker_coefficients(1.0 + h, nu);
    for (int k = 0; k < 3; ++k) {
      const double dl = (coef(c0, k) - coef(cl, k)) / h, dr = (coef(cr, k) - coef(c0, k)) / h;
      EXPECT_NEAR(dl, dr, 1e-3 * std::abs(dr) + 1e-3) << "nu " << nu << " k " << k;
    }
  }
}

TEST(KalkerCoefficients, SmoothScanAndAsymptotes) {
  for (double nu : {0.0, 0.28, 0.5}) {
    KalkerCoefficients prev = kalker_coefficients(1e-3, nu);
    for (double lr = std::log(1e-3) + 0.001; lr < std::log(1e3); lr += 0.001) {
      const KalkerCoefficients c = kalker_coefficients(std::exp(lr), nu);
      for (int k = 0; k < 3; ++k) {
        ASSERT_TRUE(std::isfinite(coef(c, k)) && coef(c, k) > 0.0);
        // 0.1 % step in a/b: no coefficient changes by more than 0.2 %.
        EXPECT_LT(std::abs(coef(c, k) / coef(prev, k) - 1.0), 2e-3) << "a/b " << std::exp(lr);
      }
      prev = c;
    }
    // Far outside the table the blend has faded: the asymptote itself.
    for (int br = 0; br < 2; ++br) {
      const double g = 1e-4;
      const KalkerCoefficients c = kalker_coefficients(br == 0 ? g : 1.0 / g, nu);
      const KalkerCoefficients a = kalker_table::asymptote(br, g, nu);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(coef(c, k), coef(a, k), 2e-4 * coef(a, k));
    }
  }
}

TEST(KalkerCoefficients, RejectsBadInput) {
  EXPECT_THROW(kalker_coefficients(0.0, 0.3), Error);
  EXPECT_THROW(kalker_coefficients(std::nan(""), 0.3), Error);
  EXPECT_THROW(kalker_coefficients(1.0, 0.6), Error);
}

}  // namespace
}  // namespace railtab
