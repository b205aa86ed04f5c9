// SPDX-License-Identifier: Apache-2.0
// angle_cos_sin (lookup/src/creep_map.hpp), the cosine and sine of a contact angle every query
// path uses to recover N from the vertical share: its Taylor polynomials against the library's
// std::cos and std::sin over every contact angle and beyond, and the library itself outside.
#include "creep_map.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cstdio>
#include <cmath>
#include <limits>
#include <random>

namespace railtab::lookup::detail {
namespace {

// Within 4 ulp of the library's value: the sine in ulp of its value; the cosine in ulp of 1 (a
// cosine near pi / 2 is a difference of O(1) terms, so its error is absolute) and, for contact
// angles (|angle| <= pi / 2) where it is at least 0.25, in ulp of its value too.
TEST(AngleCosSin, WithinFourUlpOfTheLibraryOverEveryContactAngle) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> angle(-2.0, 2.0);
  double worst_cos = 0.0, worst_sin = 0.0;
  for (int k = 0; k < 200000; ++k) {
    const double a = k < 3 ? (k == 0 ? 0.0 : k == 1 ? 2.0 : -1e-300) : angle(rng);
    double c, s;
    angle_cos_sin(a, c, s);
    const double cr = std::cos(a), sr = std::sin(a);
    const double ec = std::abs(c - cr) / DBL_EPSILON;
    const double es = std::abs(s - sr) / (DBL_EPSILON * std::max(std::abs(sr), 1e-300));
    const double ec_relative = std::abs(cr) >= 0.25 && std::abs(a) <= M_PI / 2 ? std::abs(c - cr) / (DBL_EPSILON * std::abs(cr)) : 0.0;
    worst_cos = std::max({worst_cos, ec, ec_relative});
    worst_sin = std::max(worst_sin, es);
    ASSERT_LE(ec, 4.0) << "cos at " << a;
    ASSERT_LE(ec_relative, 4.0) << "cos at " << a;
    ASSERT_LE(es, 4.0) << "sin at " << a;
  }
  std::printf("angle_cos_sin against std::cos / std::sin: worst %.2f / %.2f ulp\n", worst_cos, worst_sin);
}

TEST(AngleCosSin, OutsideTheRangeIsTheLibrarys) {
  for (double a : {2.0000001, -3.0, 10.0, 1e6}) {
    double c, s;
    angle_cos_sin(a, c, s);
    EXPECT_EQ(c, std::cos(a)) << a;
    EXPECT_EQ(s, std::sin(a)) << a;
  }
  double c, s;
  angle_cos_sin(std::numeric_limits<double>::quiet_NaN(), c, s);
  EXPECT_TRUE(std::isnan(c) && std::isnan(s));
}

}  // namespace
}  // namespace railtab::lookup::detail
