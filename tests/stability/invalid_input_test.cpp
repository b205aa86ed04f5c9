// SPDX-License-Identifier: Apache-2.0
// 9. NaN and infinite inputs: a railtab::Error naming the input, or a kInvalidInput flag; never a
// crash or a silent NaN in the output.
#include <limits>

#include "core/check.hpp"
#include "stability_common.hpp"
#include "tangential/kalker_coefficients.hpp"
#include "error_message.hpp"

namespace railtab::stability {
namespace {

const double kBad[] = {std::numeric_limits<double>::quiet_NaN(),
                       std::numeric_limits<double>::infinity(),
                       -std::numeric_limits<double>::infinity()};

TEST(InvalidInput, StateYAndRollThrowNamingTheInput) {
  const ContactGeometrySolver& solver = s1002_uic60();
  for (double bad : kBad) {
    for (Side side : {Side::left, Side::right}) {
      const std::string ey = test::error_message([&] { solver.solve_wheel(side, WheelsetState{bad, 0.0}); });
      EXPECT_NE(ey.find(" y "), std::string::npos) << ey;
      const std::string er = test::error_message([&] { solver.solve_wheel(side, WheelsetState{0.0, bad}); });
      EXPECT_NE(er.find("roll"), std::string::npos) << er;
    }
    const std::string ee = test::error_message([&] { solver.equilibrium_roll(bad); });
    EXPECT_FALSE(ee.empty()) << "equilibrium_roll(" << bad << ") did not throw";
  }
}

TEST(InvalidInput, LoadAndApproachGiveInvalidInputFlag) {
  const WheelContactGeometry g = s1002_uic60().solve_wheel(Side::left, WheelsetState{0.0, 0.0});
  for (const Variant& v : all_variants()) {
    for (double bad : kBad) {
      const WheelNormalResult r = solve_normal_for_load(g, bad, Material{}, options_for(v));
      EXPECT_TRUE(r.status & status::kInvalidInput) << v.label << " load " << bad;
      EXPECT_TRUE(r.patches.empty()) << v.label;
      EXPECT_EQ(normal_violation(g, r), "") << v.label;
      const WheelNormalResult a = solve_normal_for_approach(g, bad, Material{}, options_for(v));
      EXPECT_TRUE(a.status & status::kInvalidInput) << v.label << " approach " << bad;
      EXPECT_TRUE(a.patches.empty()) << v.label;
    }
  }
}

TEST(InvalidInput, CreepageAndFrictionThrowNamingTheInput) {
  const WheelContactGeometry g = s1002_uic60().solve_wheel(Side::left, WheelsetState{0.0, 0.0});
  for (const Variant& v : all_variants()) {
    const WheelNormalResult r = solve_normal_for_load(g, kLoad, Material{}, options_for(v));
    ASSERT_FALSE(r.patches.empty());
    const ContactPatch& p = r.patches.front();
    for (double bad : kBad) {
      for (int k = 0; k < 3; ++k) {
        Creepage c{1e-3, 1e-3, 0.1};
        (k == 0 ? c.xi : k == 1 ? c.eta : c.phi) = bad;
        const std::string e = test::error_message([&] { creep_and_wear(g, p, c); });
        EXPECT_NE(e.find("creepage"), std::string::npos) << v.label << ": '" << e << "'";
      }
      const std::string em = test::error_message([&] { creep_and_wear(g, p, Creepage{1e-3, 0.0, 0.0}, bad); });
      EXPECT_NE(em.find("friction"), std::string::npos) << v.label << ": '" << em << "'";
    }
  }
  for (double bad : kBad) {
    EXPECT_THROW(kalker_coefficients(bad, 0.3), Error);
    EXPECT_THROW(kalker_coefficients(1.0, bad), Error);
  }
}

}  // namespace
}  // namespace railtab::stability
