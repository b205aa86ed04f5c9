// SPDX-License-Identifier: Apache-2.0
// Where one wear sample puts the wear on the outer wheel, elliptic (Hertz) against STRIPES, as the
// wheelset moves outwards in a curve: the diagnostic behind docs/simulation.md's direction check
// (seed 001: STRIPES relocates wear towards the flange). Disabled: it prints a table, it asserts
// nothing about the numbers. Run with
//   test_generator_simulate --gtest_also_run_disabled_tests --gtest_filter='*WearCentroidAcrossY*'
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "simulate/wear_accumulator.hpp"

namespace railtab {
namespace {

struct Location {
  double centroid = 0.0;      // depth-weighted u [m]
  double flange_side = 0.0;   // share of the worn area at u < 0 [-]
  double area_rate = 0.0;     // worn area per metre [m2/m]
};

Location locate(const WearAccumulator& acc, int wheel) {
  Location out;
  double sum = 0.0, moment = 0.0, flange = 0.0;
  for (std::size_t i = 0; i < acc.u().size(); ++i) {
    const double d = acc.depth(wheel)[i];
    sum += d;
    moment += d * acc.u()[i];
    if (acc.u()[i] < 0.0) flange += d;
  }
  if (sum > 0.0) {
    out.centroid = moment / sum;
    out.flange_side = flange / sum;
  }
  out.area_rate = acc.worn_area(wheel);
  return out;
}

TEST(WearLocation, DISABLED_WearCentroidAcrossY) {
  const Scene scene = load_scene(std::filesystem::path(RAILTAB_SOURCE_DIR) / "tables/sim/contact_1in30.toml");
  // R1500 at 120 km/h, the bogie run's leading wheelset: yaw -0.24 mrad, loads 81.6 / 74.4 kN
  // (inner / outer: excess cant), spin V / r0.
  vehicle::WheelsetMotion motion;
  motion.speed = 33.3333;
  motion.yaw = -0.24e-3;
  motion.curvature = 1.0 / 1500.0;
  motion.spin_speed = motion.speed / 0.46;
  const double load[vehicle::kWheels] = {81.6e3, 74.4e3};
  std::printf("   y [mm] | outer wheel centroid u [mm]: hertz  stripes-a  (diff) | share at u < 0: hertz  stripes-a\n");
  for (int k = 0; k <= 16; ++k) {
    const double y = -0.0005 * k;
    WearAccumulator hertz(scene, "hertz"), stripes(scene, "stripes-a");
    hertz.sample(y, load, motion, 1.0);
    stripes.sample(y, load, motion, 1.0);
    const Location h = locate(hertz, 1), s = locate(stripes, 1);
    std::printf("  %6.1f  |                         %+7.2f  %+7.2f  (%+6.2f) |          %5.1f %%   %5.1f %%\n", y * 1e3,
                h.centroid * 1e3, s.centroid * 1e3, (s.centroid - h.centroid) * 1e3, 100 * h.flange_side,
                100 * s.flange_side);
    EXPECT_EQ(hertz.failures() + stripes.failures(), 0) << "y = " << y;
  }
}

}  // namespace
}  // namespace railtab
