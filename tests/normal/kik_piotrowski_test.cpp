// SPDX-License-Identifier: Apache-2.0
// Tests of the Kik-Piotrowski model (src/normal/kik_piotrowski.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "normal/normal_model.hpp"
#include "synthetic_geometry.hpp"

namespace railtab {
namespace {

// On a circular Hertz geometry (A = B) KP's VI patch is a circle of radius R = sqrt(eps d/A) with the
// Hertzian pressure shape, for which the Boussinesq centre displacement is known in closed form:
// d = pi R p0/(2 E*)  =>  N = (4/3) E* d R (Johnson, Contact Mechanics, eq. 3.41 with p0 = 3N/(2 pi R^2)).
TEST(KikPiotrowski, BoussinesqClosureOnACircle) {
  const Material steel{};
  const double A = 0.5 / 0.46;
  const auto g = test::hertz_band(A, A, 0.01e-3);
  NormalOptions o;
  o.model = NormalModel::kik_piotrowski;
  o.strips = 60;
  for (double d : {20e-6, 80e-6}) {
    const auto r = solve_normal_for_approach(g, d, steel, o);
    const double R = std::sqrt(0.55 * d / A);
    const double N = 4.0 / 3.0 * steel.contact_modulus() * d * R;
    EXPECT_NEAR(r.patches[0].normal_force / N, 1.0, 5e-3) << d;
    // Equivalent ellipse of a circle: the circle.
    EXPECT_NEAR(r.patches[0].semi_axis_a / R, 1.0, 5e-3);
    EXPECT_NEAR(r.patches[0].semi_axis_b / R, 1.0, 5e-3);
    EXPECT_NEAR(r.patches[0].max_pressure / (1.5 * N / (std::numbers::pi * R * R)), 1.0, 5e-3);
  }
}

}  // namespace
}  // namespace railtab
