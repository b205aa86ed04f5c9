// SPDX-License-Identifier: Apache-2.0
// Tests of Linder's model (src/normal/linder.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "normal/hertz.hpp"
#include "normal/normal_model.hpp"
#include "synthetic_geometry.hpp"

namespace railtab {
namespace {

// Seed 000: on a Hertzian geometry Linder's patch has a = sqrt(0.55 d/A0), b = sqrt(0.55 d/B0) with
// d the Hertz approach; the load-approach law is Hertz's.
TEST(Linder, HertzianGeometry) {
  const Material steel{};
  const double A = 0.5 / 0.46, B = 0.5 * (0.1 + 1 / 0.3);
  const auto g = test::hertz_band(A, B, 0.01e-3);
  const HertzContact h = hertz_for_force(A, B, 78e3, steel);
  NormalOptions o;
  o.model = NormalModel::linder;
  const auto r = solve_normal_for_load(g, 78e3, steel, o);
  const ContactPatch& p = r.patches[0];
  EXPECT_NEAR(r.vertical_approach / h.approach, 1.0, 1e-7);
  EXPECT_NEAR(p.semi_axis_a / std::sqrt(0.55 * h.approach / A), 1.0, 2e-3);
  EXPECT_NEAR(p.semi_axis_b / std::sqrt(0.55 * h.approach / B), 1.0, 2e-3);
  for (const Strip& s : p.strips) EXPECT_DOUBLE_EQ(s.ellipse_b, p.semi_axis_b);
  // Identical to Hertz only for A = B (Sichani et al. 2014): here the axis ratio is sqrt(B/A), not m/n.
  EXPECT_NEAR(p.semi_axis_a / p.semi_axis_b, std::sqrt(B / A), 2e-3);
  EXPECT_GT(std::abs(p.semi_axis_a / p.semi_axis_b - h.a / h.b), 0.05);
}

}  // namespace
}  // namespace railtab
