// SPDX-License-Identifier: Apache-2.0
// 5. Extreme ellipticity (FACTS 8 row 6): Hertz-like synthetic geometry with B/A = 1e-3 (a patch
// 100x longer laterally... i.e. a/b -> 0) and 1e3 (a/b large). Every normal model, the Kalker
// coefficients and FASTSIM stay finite; |F| <= mu N.
#include "../normal/synthetic_geometry.hpp"
#include "stability_common.hpp"
#include "tangential/kalker_coefficients.hpp"

namespace railtab::stability {
namespace {

TEST(Ellipticity, KalkerCoefficientsFiniteAcrossSixDecades) {
  for (double r = 1e-3; r <= 1e3 * 1.0001; r *= std::sqrt(10.0)) {
    for (double nu : {0.0, 0.28, 0.5}) {
      const KalkerCoefficients c = kalker_coefficients(r, nu);
      EXPECT_TRUE(std::isfinite(c.c11) && c.c11 > 0.0) << r << " " << nu;
      EXPECT_TRUE(std::isfinite(c.c22) && c.c22 > 0.0) << r << " " << nu;
      EXPECT_TRUE(std::isfinite(c.c23) && c.c23 > 0.0) << r << " " << nu;
    }
  }
}

TEST(Ellipticity, ExtremeCurvatureRatios) {
  const double A = 1.0 / (2.0 * 0.46);
  for (double ratio : {1e-3, 1e3}) {
    const double B = ratio * A;
    // Band wide enough for the long lateral axis at B = 1e-3 A (0.2 m) and fine enough for the
    // narrow one at 1e3 A (b ~ 0.3 mm: 0.02 mm step).
    const double step = ratio < 1.0 ? 0.2e-3 : 0.02e-3;
    const double half = ratio < 1.0 ? 0.2 : 10e-3;
    const WheelContactGeometry g = test::hertz_band(A, B, step, half);
    for (const Variant& v : all_variants()) {
      const std::string where = v.label + " B/A " + std::to_string(ratio);
      const WheelNormalResult r = solve_normal_for_load(g, kLoad, Material{}, options_for(v));
      ASSERT_EQ(normal_violation(g, r), "") << where;
      EXPECT_TRUE(r.status & (status::kConverged | status::kNotConverged)) << where;
      EXPECT_FALSE(r.patches.empty()) << where;
      EXPECT_TRUE(bitwise_equal(r, solve_normal_for_load(g, kLoad, Material{}, options_for(v))));
      for (const ContactPatch& p : r.patches) {
        for (const Creepage& c : {Creepage{1e-3, 0.0, 0.0}, Creepage{0.0, 1e-3, 0.0},
                                  Creepage{0.0, 0.0, 1.0}, Creepage{0.3, -0.3, 5.0}}) {
          const CreepWear cw = creep_and_wear(g, p, c);
          EXPECT_EQ(creep_violation(p, cw, 0.3), "") << where << " creepage " << c.xi << " "
                                                     << c.eta << " " << c.phi;
        }
      }
    }
  }
}

}  // namespace
}  // namespace railtab::stability
