// SPDX-License-Identifier: Apache-2.0
// The exact half-space wear post-processor (simulate/halfspace_wheel_wear.hpp): plausibility on
// tangent track against the elliptic one, zero wear without creepage, worn area kept when the
// element wear is mapped onto the wheel profile. The disabled Table3PatchWear test prints the
// single-patch comparison of docs/validation/wear-cases.md (Enblom and Berg 2008 Table 3 states):
//   test_generator_simulate --gtest_also_run_disabled_tests --gtest_filter='Table3PatchWear*'
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>

#include "core/check.hpp"
#include "simulate/bogie_run.hpp"
#include "simulate/halfspace_wheel_wear.hpp"
#include "simulate/wear_accumulator.hpp"

namespace railtab {
namespace {

Scene contact_scene() {
  return load_scene(std::filesystem::path(RAILTAB_SOURCE_DIR) / "tables/sim/contact_1in30.toml");
}

struct Distribution {
  double area = 0.0;         // worn area per metre [m2/m]
  double centroid = 0.0;     // depth-weighted u [m]
  double flange_side = 0.0;  // share at u < 0 [-]
};

Distribution describe(const WearAccumulator& acc, int wheel) {
  Distribution d;
  double sum = 0.0, moment = 0.0, flange = 0.0;
  for (std::size_t i = 0; i < acc.u().size(); ++i) {
    const double v = acc.depth(wheel)[i];
    sum += v;
    moment += v * acc.u()[i];
    if (acc.u()[i] < 0.0) flange += v;
  }
  if (sum > 0.0) {
    d.centroid = moment / sum;
    d.flange_side = flange / sum;
  }
  d.area = acc.worn_area(wheel);
  return d;
}

// Tangent track, 120 km/h, 78 kN per wheel (Enblom and Berg 2008 Table 3's tangent load), wheelset 1 mm to
// the left, spin V / r0: tread contact (one patch per wheel); the yaw sets the lateral creepage.
vehicle::WheelsetMotion tangent_motion(double yaw = 1.0e-3) {
  vehicle::WheelsetMotion m;
  m.speed = 33.3333;
  m.yaw = yaw;
  m.spin_speed = m.speed / 0.46;
  return m;
}

// Half-space against elliptic (Hertz + FASTSIM) on tangent track. Near full slip (8 mrad yaw:
// the slip is then set by the creepage, not by the contact model's elasticity) the worn areas
// must agree within a factor 2 and the wear sit at the same place. In partial slip (1 mrad) the
// half-space wear must be the SMALLER one: FASTSIM's slip grows towards the trailing edge more
// than the exact solution's (Enblom and Berg 2008 section 4.1: CONTACT's "maximum sliding velocity at the
// rear edge ... is smaller"); measured 0.26 (DISABLED_RatioToEllipticAgainstYaw prints the
// ratio against yaw).
TEST(HalfspaceWear, TangentWearIsNonNegativeNearTheEllipticInFullSlipAndBelowItInPartialSlip) {
  const Scene scene = contact_scene();
  const double load[vehicle::kWheels] = {78e3, 78e3};
  const double y = 0.001;
  for (double yaw : {8e-3, 1e-3}) {
    WearAccumulator elliptic(scene, "hertz"), exact(scene, "halfspace");
    EXPECT_NE(elliptic.sample(y, load, tangent_motion(yaw), 1.0) & status::kConverged, 0u);
    exact.sample(y, load, tangent_motion(yaw), 1.0);
    ASSERT_EQ(exact.failures(), 0);
    ASSERT_EQ(elliptic.failures(), 0);
    for (int w = 0; w < vehicle::kWheels; ++w) {
      for (double d : exact.depth(w)) ASSERT_GE(d, 0.0);
      const Distribution e = describe(elliptic, w), h = describe(exact, w);
      std::printf("yaw %.0f mrad, wheel %d: worn area per metre elliptic %.4e, half-space %.4e m2/m (ratio %.3f); "
                  "centroid u %+.2f / %+.2f mm\n",
                  yaw * 1e3, w, e.area, h.area, h.area / e.area, e.centroid * 1e3, h.centroid * 1e3);
      ASSERT_GT(e.area, 0.0);
      ASSERT_GT(h.area, 0.0);
      if (yaw > 4e-3) {
        EXPECT_GT(h.area, 0.5 * e.area) << "wheel " << w;
        EXPECT_LT(h.area, 2.0 * e.area) << "wheel " << w;
      } else {
        EXPECT_LT(h.area, e.area) << "wheel " << w;
      }
      // Same tread contact: the wear sits at the same place of the profile within 3 mm.
      EXPECT_NEAR(h.centroid, e.centroid, 3e-3) << "wheel " << w;
      EXPECT_EQ(exact.clipped_area(w), 0.0);
    }
  }
}

// Diagnostic (prints, asserts only that nothing fails): worn area half-space / elliptic on
// tangent track as the yaw (lateral creepage) grows from partial to full slip.
TEST(HalfspaceWear, DISABLED_RatioToEllipticAgainstYaw) {
  const Scene scene = contact_scene();
  const double load[vehicle::kWheels] = {78e3, 78e3};
  std::printf("yaw [mrad] | right wheel worn area per metre: elliptic, half-space [m2/m], ratio | stripes-a ratio\n");
  for (double yaw : {0.5e-3, 1e-3, 2e-3, 4e-3, 8e-3}) {
    const vehicle::WheelsetMotion m = tangent_motion(yaw);
    WearAccumulator elliptic(scene, "hertz"), exact(scene, "halfspace"), stripes(scene, "stripes-a");
    elliptic.sample(0.001, load, m, 1.0);
    exact.sample(0.001, load, m, 1.0);
    stripes.sample(0.001, load, m, 1.0);
    EXPECT_EQ(exact.failures(), 0);
    const double e = elliptic.worn_area(1), h = exact.worn_area(1), st = stripes.worn_area(1);
    std::printf("%5.1f | %.3e %.3e %.3f | %.3f\n", yaw * 1e3, e, h, h / e, st / e);
  }
}

TEST(HalfspaceWear, ZeroCreepageGivesZeroWearAndCreepageGivesSome) {
  const Scene scene = contact_scene();
  const ContactGeometrySolver solver = make_geometry_solver(scene);
  const WheelContactGeometry geometry = solver.solve({0.0, solver.equilibrium_roll(0.0)}).wheels[1];
  HalfspaceWheelWear wear(scene);
  std::vector<StripWear> strips;
  wear.wheel_wear_at(geometry, 78e3, Creepage{0.0, 0.0, 0.0}, 33.3, strips);
  ASSERT_FALSE(wear.last_result().patches.empty());
  EXPECT_GT(wear.last_result().patches[0].normal.normal_force, 0.0);
  EXPECT_TRUE(strips.empty()) << strips.size() << " strips with wear at zero creepage";

  // Full slip in the rolling direction: wear, and the profile mapping keeps the worn area
  // (sum of depth x dy per pass over the circumference = sum of radial rate x width in u).
  const StatusBits bits = wear.wheel_wear_at(geometry, 78e3, Creepage{0.01, 0.0, 0.0}, 33.3, strips);
  EXPECT_NE(bits & status::kFullSlip, 0u);
  ASSERT_FALSE(strips.empty());
  const halfspace::HalfspacePatch& patch = wear.last_result().patches[0];
  std::vector<double> element_depth;
  const double section = halfspace::archard_wear_per_pass(patch, 33.3, wear_options(scene), element_depth);
  double mapped = 0.0;
  for (const StripWear& s : strips) {
    EXPECT_GE(s.depth_rate, 0.0);
    mapped += s.depth_rate * s.width_u;
  }
  ASSERT_GT(section, 0.0);
  EXPECT_NEAR(mapped, section / (2.0 * std::numbers::pi * patch.rolling_radius), 1e-9 * mapped);
  // The right wheel's tread contact near u = 0 (running circle), not elsewhere on the profile.
  for (const StripWear& s : strips) EXPECT_LT(std::abs(s.wheel_u), 0.02) << s.wheel_u;
}

TEST(HalfspaceWear, BadSpeedIsNamed) {
  const Scene scene = contact_scene();
  const ContactGeometrySolver solver = make_geometry_solver(scene);
  const WheelContactGeometry geometry = solver.solve({0.0, solver.equilibrium_roll(0.0)}).wheels[0];
  HalfspaceWheelWear wear(scene);
  std::vector<StripWear> strips;
  try {
    wear.wheel_wear_at(geometry, 78e3, Creepage{0.01, 0.0, 0.0}, 0.0, strips);
    FAIL() << "no error for speed 0";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("speed"), std::string::npos) << e.what();
  }
}

TEST(HalfspaceWear, SampledHalfspaceSeesEveryKthSampleWithKTimesItsDistance) {
  const Scene scene = contact_scene();
  WearPostProcessing wear(scene, {"hertz", "halfspace"}, {"leading"}, WearGrid{}, 3);
  WheelsetSample sample;
  sample.wheelset = 0;
  sample.y_relative = 0.001;
  sample.load[0] = sample.load[1] = 78e3;
  sample.motion = tangent_motion();
  sample.distance = 2.9;
  for (int i = 0; i < 7; ++i) wear.sample(sample);
  EXPECT_EQ(wear.accumulator(0, 0).samples(), 7);
  EXPECT_EQ(wear.accumulator(1, 0).samples(), 3);  // samples 1, 4 and 7
  EXPECT_DOUBLE_EQ(wear.accumulator(0, 0).distance(), 7 * 2.9);
  EXPECT_DOUBLE_EQ(wear.accumulator(1, 0).distance(), 9 * 2.9);
  EXPECT_EQ(wear.accumulator(1, 0).failures(), 0);
  // The wear solves' status is kept for summary.json: converged tread contacts, none flagged.
  EXPECT_NE(wear.accumulator(1, 0).status_seen() & status::kConverged, 0u);
  EXPECT_EQ(wear.accumulator(1, 0).status_seen() & status::kNotConverged, 0u);
  EXPECT_EQ(wear.accumulator(1, 0).not_converged(), 0);
  EXPECT_THROW(WearPostProcessing(scene, {"halfspace"}, {"leading"}, WearGrid{}, 0), Error);
}

// Seed 001 Table 3: the leading outer wheel in quasi-static curving, S1002 on UIC60 1:30.
// Displacement towards the flange of the outer (right) wheel in a left curve = y < 0. The paper
// gives no creepages: here yaw 0 (our bogie's leading wheelset runs nearly radial in flange
// contact: -0.05 mrad in R600, docs/validation/wear-cases.md), spin V / r0 (r0 = 0.46 m, nominal radius),
// the curvature's own spin and the rolling-radius difference from vehicle::creepage; mu 0.3, the
// contact scene's wear map (dry / 5.5).
struct Table3Case {
  const char* name;
  double radius, load, speed_kmh, displacement;
  const char* paper_area;      // Table 3 contact area elliptic / CONTACT / STRIPES [mm2]
  const char* paper_pressure;  // Table 3 maximum pressure, the same order [MPa]
};

// Table 3's load is the normal force (its Table 6: normal 98.8 kN for R600's 99 kN); the
// post-processors take the vertical force. Vertical = load x cos(g) with g the half-space patch's
// reference angle (one fixed-point round from the rigid point's angle), so that the half-space
// patch carries N = load and the others, whose patches sit within 0.5 mm of it, nearly so.
double vertical_for_normal(const Scene& scene, const WheelContactGeometry& g, double normal, const Creepage& creepage) {
  HalfspaceWheelWear exact(scene);
  std::vector<StripWear> strips;
  double vertical = normal * std::cos(g.points.at(0).contact_angle);
  for (int round = 0; round < 3; ++round) {
    exact.wheel_wear_at(g, vertical, creepage, 20.0, strips);
    if (exact.last_result().patches.size() != 1) break;  // several patches: keep the rigid point's angle
    vertical = normal * std::cos(exact.last_result().patches[0].contact_angle);
  }
  return vertical;
}

TEST(Table3PatchWear, DISABLED_AgainstHalfspace) {
  const Scene scene = contact_scene();
  const Table3Case cases[] = {{"Tangent", 0.0, 78e3, 120.0, 0.0, "135 / 130 / 125", "867 / 929 / 1229"},
                              {"R600", 600.0, 99e3, 120.0, 5.9e-3, "74 / 51 / 70", "1994 / 3242 / 2995"},
                              {"R400", 400.0, 98e3, 93.0, 6.3e-3, "72 / 59 / 84", "2038 / 2694 / 2417"},
                              {"R300", 300.0, 101e3, 80.0, 6.5e-3, "77 / 77 / 155 (two-point)", "2132 / 3114 / 1782"}};
  const char* processors[] = {"hertz", "stripes-a", "stripes-ab", "kik-piotrowski"};
  std::printf("| case | post-processor | worn area / half-space | L1(depth - half-space) / half-space area | "
              "centroid u [mm] (half-space) | share u < 0 | patches |\n|---|---|---|---|---|---|---|\n");
  for (const Table3Case& c : cases) {
    vehicle::WheelsetMotion motion;
    motion.speed = c.speed_kmh / 3.6;
    motion.curvature = c.radius > 0.0 ? 1.0 / c.radius : 0.0;
    motion.spin_speed = motion.speed / 0.46;
    const ContactGeometrySolver solver = make_geometry_solver(scene);
    const WheelContactGeometry g = solver.solve({-c.displacement, solver.equilibrium_roll(-c.displacement)}).wheels[1];
    ASSERT_FALSE(g.points.empty()) << c.name;
    const double load[vehicle::kWheels] = {0.0, vertical_for_normal(scene, g, c.load, Creepage{})};  // outer wheel
    WearAccumulator exact(scene, "halfspace");
    const std::uint32_t bits = exact.sample(-c.displacement, load, motion, 1.0);
    ASSERT_EQ(exact.failures(), 0) << c.name;
    const Distribution h = describe(exact, 1);
    ASSERT_GT(h.area, 0.0) << c.name;
    std::printf("| %s | halfspace | 1 (%.3e m2/m) | 0 | %+.2f | %.1f %% | flags 0x%x |\n", c.name, h.area,
                h.centroid * 1e3, 100 * h.flange_side, bits);
    for (const char* p : processors) {
      WearAccumulator acc(scene, p);
      acc.sample(-c.displacement, load, motion, 1.0);
      ASSERT_EQ(acc.failures(), 0) << c.name << " " << p;
      const Distribution d = describe(acc, 1);
      double l1 = 0.0;
      for (std::size_t i = 0; i < acc.u().size(); ++i) l1 += std::abs(acc.depth(1)[i] - exact.depth(1)[i]);
      l1 *= acc.u()[1] - acc.u()[0];
      std::printf("| %s | %s | %.2f | %.2f | %+.2f (%+.2f) | %.1f %% | |\n", c.name, p, d.area / h.area, l1 / h.area,
                  d.centroid * 1e3, (d.centroid - h.centroid) * 1e3, 100 * d.flange_side);
    }
  }
  // The half-space patches of the same states beside Table 3's contact columns.
  std::printf("\n| case | half-space patch: wheel u [mm], contact angle [deg], N [kN], area [mm2], p_max [MPa], "
              "fx, fy [kN], flags | Table 3 area E / C / S [mm2] | p_max E / C / S [MPa] |\n|---|---|---|---|\n");
  const ContactGeometrySolver solver = make_geometry_solver(scene);
  for (const Table3Case& c : cases) {
    vehicle::WheelsetMotion motion;
    motion.speed = c.speed_kmh / 3.6;
    motion.curvature = c.radius > 0.0 ? 1.0 / c.radius : 0.0;
    motion.spin_speed = motion.speed / 0.46;
    const double y = -c.displacement;
    const WheelContactGeometry g = solver.solve({y, solver.equilibrium_roll(y)}).wheels[1];
    HalfspaceWheelWear exact(scene);
    std::vector<StripWear> strips;
    exact.wheel_wear(g, 1, vertical_for_normal(scene, g, c.load, Creepage{}), motion, strips);
    std::printf("| %s |", c.name);
    for (const halfspace::HalfspacePatch& hp : exact.last_result().patches) {
      std::printf(" %+.1f, %.1f, %.1f, %.0f, %.0f, %+.1f, %+.1f, 0x%x;", hp.wheel_u * 1e3,
                  hp.contact_angle * 180 / std::numbers::pi, hp.normal.normal_force * 1e-3, hp.normal.area * 1e6,
                  hp.normal.max_pressure * 1e-6, hp.tangential.fx * 1e-3, hp.tangential.fy * 1e-3, hp.status);
    }
    std::printf(" | %s | %s |\n", c.paper_area, c.paper_pressure);
  }
}

}  // namespace
}  // namespace railtab
