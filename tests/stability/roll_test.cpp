// SPDX-License-Identifier: Apache-2.0
// 8. Roll at the edges of the grid: roll +-0.01 and +-0.03 rad with y = +-10 mm, both wheels, every
// model: finite, bounded, repeatable, FASTSIM and wear finite (sweep()).
#include "stability_common.hpp"

namespace railtab::stability {
namespace {

TEST(Roll, GridCorners) {
  for (const Variant& v : all_variants())
    for (Side side : {Side::left, Side::right})
      for (double roll : {-0.03, -0.01, 0.01, 0.03}) {
        const auto s = sweep(s1002_uic60(), side, v, {-10e-3, 10e-3}, roll);
        for (const Sample& x : s) EXPECT_FALSE(x.geometry.points.empty()) << v.label;
      }
}

TEST(Roll, EquilibriumRollAtTheYEdgesIsFinite) {
  for (double y : {-10e-3, -7e-3, 7e-3, 10e-3}) {
    const double roll = s1002_uic60().equilibrium_roll(y);
    EXPECT_TRUE(std::isfinite(roll)) << y;
    EXPECT_LT(std::abs(roll), 0.05) << y;
  }
}

}  // namespace
}  // namespace railtab::stability
