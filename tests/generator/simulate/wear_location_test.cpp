// SPDX-License-Identifier: Apache-2.0
// Where one wear sample puts the wear on the outer wheel, elliptic (Hertz) against STRIPES, as the
// wheelset moves outwards in a curve: the diagnostic behind docs/validation/wear-cases.md's direction check
// (Enblom and Berg 2008: STRIPES relocates wear towards the flange). Disabled: it prints a table, it asserts
// nothing about the numbers. Run with
//   test_generator_simulate --gtest_also_run_disabled_tests --gtest_filter='*WearCentroidAcrossY*'
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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

// Half width of the band where the depth is at least half its peak [m] (FWHM / 2 for one peak).
double half_max_width(const WearAccumulator& acc, int wheel) {
  const std::vector<double>& d = acc.depth(wheel);
  double peak = 0.0;
  for (double v : d) peak = std::max(peak, v);
  double lo = 1.0, hi = -1.0;
  for (std::size_t i = 0; i < d.size(); ++i) {
    if (peak > 0.0 && d[i] >= 0.5 * peak) {
      lo = std::min(lo, acc.u()[i]);
      hi = std::max(hi, acc.u()[i]);
    }
  }
  return hi >= lo ? hi - lo + (acc.u()[1] - acc.u()[0]) : 0.0;
}

// The R600 runaway (docs/validation/wear-cases.md): one wear sample of the leading outer wheel at the
// step-0 state of the R600 run (circular part means from shared/step0/trajectory.csv: y -5.27 mm,
// yaw -0.045 mrad, right tread N 86.1 kN at 0.138 rad, left load 71.9 kN), with the KTH map as it
// is and with the seizure region moved out of reach (hardness x 10: seizure from 22 GPa; areas
// multiplied by 10 to undo the 1/H). Prints worn area, peak and width at half peak.
//   test_generator_simulate --gtest_also_run_disabled_tests --gtest_filter='*R600OuterWheelBand*'
TEST(WearLocation, DISABLED_R600OuterWheelBand) {
  Scene scene = load_scene(std::filesystem::path(RAILTAB_SOURCE_DIR) / "tables/sim/contact_1in30.toml");
  scene.wear.lubrication_factor = 11.0;
  vehicle::WheelsetMotion motion;
  motion.speed = 28.8889;
  motion.yaw = -0.045e-3;
  motion.curvature = 1.0 / 600.0;
  motion.spin_speed = motion.speed / 0.46;
  const double load[vehicle::kWheels] = {71.9e3, 86.1e3 * std::cos(0.138)};
  std::printf("map | post-processor | right wheel worn area [m2/m] | peak [m/m] at u [mm] | width at half peak [mm]\n");
  for (double h_factor : {1.0, 10.0}) {
    Scene s = scene;
    s.wear.hardness *= h_factor;
    for (const char* p : {"hertz", "stripes-a", "stripes-ab", "halfspace"}) {
      WearAccumulator acc(s, p);
      acc.sample(-5.27e-3, load, motion, 1.0);
      EXPECT_EQ(acc.failures(), 0) << p;
      std::size_t ipk = 0;
      for (std::size_t i = 0; i < acc.u().size(); ++i)
        if (acc.depth(1)[i] > acc.depth(1)[ipk]) ipk = i;
      std::printf("%s | %s | %.3e | %.3e at %+.1f | %.1f\n", h_factor == 1.0 ? "KTH" : "no seizure", p,
                  acc.worn_area(1) * h_factor, acc.depth(1)[ipk] * h_factor, acc.u()[ipk] * 1e3,
                  half_max_width(acc, 1) * 1e3);
    }
  }
}

}  // namespace
}  // namespace railtab
