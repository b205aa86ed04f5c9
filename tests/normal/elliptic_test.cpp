// SPDX-License-Identifier: Apache-2.0
// Tests of the elliptic integrals and the Hertz ellipse shape (src/normal/elliptic.hpp).
#include "normal/elliptic.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/check.hpp"

namespace railtab {
namespace {

TEST(Elliptic, KnownValuesFacts12) {
  // FACTS 1.2: k = sqrt(0.75) (b/a = 0.5).
  const EllipticKE ke = complete_elliptic(std::sqrt(0.75));
  EXPECT_NEAR(ke.K, 2.156515647500, 1e-12);
  EXPECT_NEAR(ke.E, 1.211056027568, 1e-12);
  const EllipticKE c = complete_elliptic_complementary(0.5);
  EXPECT_NEAR(c.K, 2.156515647500, 1e-12);
  EXPECT_NEAR(c.E, 1.211056027568, 1e-12);
}

TEST(Elliptic, AgreesWithStdLibraryOverTheRange) {
  for (double k : {0.0, 1e-4, 0.1, 0.5, 0.9}) {
    const EllipticKE ke = complete_elliptic(k);
    EXPECT_NEAR(ke.K, std::comp_ellint_1(k), 1e-13 * std::comp_ellint_1(k)) << k;
    EXPECT_NEAR(ke.E, std::comp_ellint_2(k), 1e-13) << k;
  }
}

TEST(Elliptic, AccurateNearUnitModulus) {
  // 20-digit values from mpmath (ellipk/ellipe take m = k^2). libstdc++'s comp_ellint_2 is off by
  // 4e-13 at k = 0.99 and 1e-12 at 0.99999, hence the separate reference.
  const double ref[][3] = {{0.99, 3.3566005233611916666, 1.0284758090288040352},
                           {0.999, 4.4955963958421508984, 1.0039944099655077705},
                           {0.99999, 6.7962149844355380884, 1.0000629619736886369}};
  for (const auto& r : ref) {
    const EllipticKE ke = complete_elliptic(r[0]);
    EXPECT_NEAR(ke.K, r[1], 1e-11) << r[0];  // dK/dk ~ 1/(1 - k^2) amplifies the rounding of k
    EXPECT_NEAR(ke.E, r[2], 5e-14) << r[0];
  }
}

TEST(Elliptic, LimitsNearUnitModulus) {
  // K ~ ln(4/kc) + O(kc^2 ln kc), E -> 1 + kc^2/2 (ln(4/kc) - 1/2) for kc -> 0 (A&S 17.3.26/36).
  for (double kc : {1e-6, 1e-9, 1e-12}) {
    const EllipticKE ke = complete_elliptic_complementary(kc);
    EXPECT_NEAR(ke.K, std::log(4.0 / kc), 1e-9);
    EXPECT_NEAR(ke.E, 1.0 + 0.5 * kc * kc * (std::log(4.0 / kc) - 0.5), 1e-12);
    EXPECT_TRUE(std::isfinite(ke.K));
  }
}

TEST(Elliptic, RejectsInvalidModulus) {
  EXPECT_THROW(complete_elliptic(1.0), Error);
  EXPECT_THROW(complete_elliptic(std::nan("")), Error);
  EXPECT_THROW(hertz_shape(0.0), Error);
  EXPECT_THROW(hertz_shape(1.5), Error);
}

// Independent ratio (K - E)/(E/g^2 - K) from the standard library (modulus form).
double std_ratio(double g) {
  const double k = std::sqrt(1.0 - g * g);
  const double K = std::comp_ellint_1(k), E = std::comp_ellint_2(k);
  return (K - E) / (E / (g * g) - K);
}

TEST(HertzShape, SolvesTheShapeEquation) {
  for (double ratio : {1.0, 0.999999, 0.8, 0.5, 0.2, 0.05, 0.01, 1e-3, 1e-5}) {
    const HertzShape s = hertz_shape(ratio);
    // The library ratio cancels near 1 (K - E -> 0), so the check stops at 0.9999.
    if (ratio < 0.9999) {
      EXPECT_NEAR(std_ratio(s.g), ratio, 1e-10 * ratio) << ratio;
    }
    // m, n, r definitions of FACTS 1.3 from the standard library's K, E.
    const double K = std::comp_ellint_1(s.e), E = std::comp_ellint_2(s.e);
    EXPECT_NEAR(s.m, std::cbrt(2.0 * E / (std::numbers::pi * s.g * s.g)), 1e-9 * s.m);
    EXPECT_NEAR(s.n, std::cbrt(2.0 * E * s.g / std::numbers::pi), 1e-9);
    EXPECT_NEAR(s.r, 2.0 * K / (std::numbers::pi * s.m), 1e-9);
    EXPECT_NEAR(s.n / s.m, s.g, 1e-12);  // b/a = n/m
  }
  const HertzShape circle = hertz_shape(1.0);
  EXPECT_DOUBLE_EQ(circle.g, 1.0);
  EXPECT_NEAR(circle.m, 1.0, 1e-15);
  EXPECT_NEAR(circle.r, 1.0, 1e-15);
}

TEST(HertzShape, FactsTable13) {
  // FACTS 1.3 table, 4 decimals: ratio, g, e, K, E, m, n, r.
  const double table[][8] = {
      {0.80, 0.8618, 0.5072, 1.6897, 1.4643, 1.0787, 0.9296, 0.9972},
      {0.60, 0.7117, 0.7025, 1.8486, 1.3539, 1.1939, 0.8497, 0.9857},
      {0.50, 0.6306, 0.7761, 1.9521, 1.2972, 1.2758, 0.8045, 0.9741},
      {0.40, 0.5441, 0.8390, 2.0812, 1.2393, 1.3864, 0.7544, 0.9557},
      {0.30, 0.4504, 0.8928, 2.2507, 1.1804, 1.5472, 0.6969, 0.9261},
      {0.20, 0.3460, 0.9382, 2.4937, 1.1205, 1.8129, 0.6273, 0.8757},
      {0.15, 0.2876, 0.9578, 2.6679, 1.0903, 2.0323, 0.5844, 0.8357},
      {0.10, 0.2223, 0.9750, 2.9142, 1.0599, 2.3905, 0.5313, 0.7761},
      {0.05, 0.1443, 0.9895, 3.3342, 1.0296, 3.1570, 0.4556, 0.6723},
      {0.02, 0.0828, 0.9966, 3.8821, 1.0116, 4.5443, 0.3765, 0.5439},
      {0.01, 0.0550, 0.9985, 4.2895, 1.0057, 5.9607, 0.3277, 0.4581},
  };
  for (const auto& row : table) {
    const HertzShape s = hertz_shape(row[0]);
    const double got[8] = {s.ratio, s.g, s.e, s.K, s.E, s.m, s.n, s.r};
    for (int c = 1; c < 8; ++c) EXPECT_NEAR(got[c], row[c], 6e-5) << "ratio " << row[0] << " col " << c;
  }
}

TEST(HertzShape, FastAxisRatioMatchesRootFind) {
  double worst = 0.0;
  for (double x = -19.9; x < 0.0; x += 0.0137) {
    const double ratio = std::exp(x);
    const double exact = hertz_shape(ratio).g;
    worst = std::max(worst, std::abs(hertz_axis_ratio_fast(ratio) / exact - 1.0));
  }
  EXPECT_LT(worst, 1e-9);
  EXPECT_DOUBLE_EQ(hertz_axis_ratio_fast(1.0), 1.0);
  EXPECT_NEAR(hertz_axis_ratio_fast(1e-10), hertz_shape(1e-10).g, 1e-12);
}

}  // namespace
}  // namespace railtab
