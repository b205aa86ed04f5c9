// SPDX-License-Identifier: Apache-2.0
// railtab conicity's computation (generator/charts/conicity.hpp): a cone wheel on a knife-edge rail
// through the contact solver, unrolled (Klingel's closed form: the cone's slope) and at its
// equilibrium roll (the roll's shift of the contacts, in closed form too); S1002/UIC60 symmetric
// about y = 0; a table's geometry part read back; the JSON and files the command writes.
#include "charts/conicity.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>

#include "charts/conicity_chart.hpp"
#include "core/check.hpp"
#include "generator/test_tables.hpp"
#include "geometry/synthetic_profiles.hpp"
#include "profile/standard/s1002.hpp"
#include "profile/standard/uic60.hpp"

namespace railtab {
namespace {

// A knife edge: a circular crown of 1 mm radius, the gauge measured 0.1 mm below its top.
constexpr double kCrown = 1e-3;

ContactGeometrySolver cone_on_knife_edge(double conicity) {
  ProfilePtr wheel = std::make_shared<testing::ConeWheel>(conicity);
  ProfilePtr rail = std::make_shared<testing::CircleRail>(kCrown, 0.9 * kCrown);
  TrackGeometry track;
  track.gauge_measuring_depth = 0.1e-3;
  return ContactGeometrySolver(wheel, rail, wheel, rail, track, WheelsetGeometry{});
}

TEST(Conicity, ConeOnKnifeEdgeUnrolledGivesTheConeSlope) {
  for (double c : {0.05, 0.2}) {
    ConicitySweep sweep;
    sweep.equilibrium_roll = false;
    sweep.y_max = 0.0105;
    sweep.y_step = 0.1e-3;
    const ConicityCurve curve =
        compute_conicity(lateral_functions_from_solver(cone_on_knife_edge(c), "cone", "cone", sweep),
                         default_conicity_amplitudes());
    EXPECT_NEAR(curve.centre, 0.0, 1e-12);
    ASSERT_EQ(curve.points.size(), 10u);
    for (const ConicityPoint& p : curve.points) {
      EXPECT_NEAR(p.conicity, c, 1e-8 * c) << "c " << c << " amplitude " << p.amplitude;
      EXPECT_NEAR(p.conicity_regression, c, 1e-8 * c) << "c " << c << " amplitude " << p.amplitude;
      EXPECT_NEAR(p.roll_parameter, 0.0, 1e-15);
      EXPECT_NEAR(p.contact_angle_parameter, 0.0, 1e-9);  // both contact angles are the cone's
      const double e0 = curve.functions.e0, r0 = curve.functions.r0;
      EXPECT_NEAR(p.wavelength, 2.0 * std::numbers::pi * std::sqrt(e0 * r0 / c), 1e-6);
    }
  }
}

// Rolled to keep both wheels on the rails, the cone's contacts shift by r phi along the axle
// (phi = Delta r / 2e): Delta r = 2 c (y + R phi) with R = r0 + crown radius (the crown's centre
// acts as the knife edge), so tan gamma_e = c e / (e - c R) at every amplitude, both methods; the
// roll parameter is that same slope (roll = Delta r / 2e), and the contact angles turn with the
// roll: Delta tan gamma = 2 (1 + c^2) phi, epsilon = (1 + c^2) tan gamma_e.
TEST(Conicity, ConeOnKnifeEdgeAtEquilibriumRollInClosedForm) {
  const double c = 0.05;
  ConicitySweep sweep;
  sweep.y_max = 0.0105;
  sweep.y_step = 0.1e-3;
  const ConicityCurve curve =
      compute_conicity(lateral_functions_from_solver(cone_on_knife_edge(c), "cone", "cone", sweep),
                       default_conicity_amplitudes());
  const double e = curve.functions.e0, radius = curve.functions.r0 + kCrown;
  const double expected = c * e / (e - c * radius);
  EXPECT_GT(expected, 1.03 * c);  // the effect is 3 %: the test tells it from the unrolled slope
  for (const ConicityPoint& p : curve.points) {
    EXPECT_NEAR(p.conicity, expected, 2e-4 * expected) << p.amplitude;
    EXPECT_NEAR(p.conicity_regression, expected, 2e-4 * expected) << p.amplitude;
    EXPECT_NEAR(p.roll_parameter, expected, 2e-3 * expected) << p.amplitude;
    EXPECT_NEAR(p.contact_angle_parameter, (1.0 + c * c) * expected, 5e-3 * expected) << p.amplitude;
  }
}

// S1002 on UIC60 is symmetric: centre 0, Delta r odd, the conicity of the tread lies between the
// published bounds (docs/validation/conicity.md) and climbs where flange contact starts.
TEST(Conicity, S1002OnUic60IsSymmetricAndClimbsAtTheFlange) {
  const ContactGeometrySolver solver(make_s1002_profile(), make_uic60_profile(), make_s1002_profile(),
                                     make_uic60_profile(), TrackGeometry{}, WheelsetGeometry{});
  ConicitySweep sweep;
  sweep.y_max = 0.009;
  sweep.y_step = 0.1e-3;
  const LateralFunctions f = lateral_functions_from_solver(solver, "s1002", "s1002", sweep);
  for (std::size_t i = 0; i < f.y.size(); ++i) {
    EXPECT_NEAR(f.delta_r[i], -f.delta_r[f.y.size() - 1 - i], 1e-12) << f.y[i];
  }
  const ConicityCurve curve = compute_conicity(f, {0.002, 0.004, 0.008});
  EXPECT_NEAR(curve.centre, 0.0, 1e-9);
  EXPECT_GT(curve.points[0].conicity, 0.05);
  EXPECT_LT(curve.points[0].conicity, 0.4);
  EXPECT_GT(curve.points[2].conicity, curve.points[1].conicity);  // flange contact beyond ~7 mm
}

// A table's geometry part: the primary slot is the one with the smaller separation, empty slots
// (no `converged` bit) are skipped, the right wheel's track-frame angle turns into its side angle.
TEST(Conicity, TableGeometryPartIsReadPerPrimarySlot) {
  const double c = 0.1;
  Table t;
  t.set_attribute("scene_name", "cone");
  t.set_attribute("scene", "[wheelset]\nback_to_back = 1.36\nflange_back_position = -0.07\n");
  t.set_attribute("fixed_axes", R"({"roll":0.0,"load":78500.0})");
  TableAxis y{"y", "m", "lateral", {}, false};
  for (int i = -20; i <= 20; ++i) y.values.push_back(i * 0.5e-3);
  t.axes.push_back(y);
  t.axes.push_back(TableAxis{"slot", "1", "slot", {0.0, 1.0}, true});
  const std::size_t n = y.values.size();
  for (const char* wheel : {"left", "right"}) {
    const double sigma = std::string(wheel) == "left" ? 1.0 : -1.0;
    TableGroup g;
    g.path = std::string(wheel) + "/geometry";
    auto dataset = [&](const std::string& name) {
      TableDataset d;
      d.name = name;
      d.axes = {"y", "slot"};
      d.shape = {n, 2};
      d.values.assign(2 * n, 0.0);
      return d;
    };
    TableDataset radius = dataset("rolling_radius"), angle = dataset("contact_angle"),
                 separation = dataset("separation"), wheel_y = dataset("wheel_y"), status = dataset("status");
    status.values.clear();
    status.is_status = true;
    status.status.assign(2 * n, 0);
    for (std::size_t i = 0; i < n; ++i) {
      const double yy = y.values[i];
      // Slot 0: the cone; slot 1: a decoy with a larger separation (or empty, status 0).
      radius.values[2 * i] = 0.46 + sigma * c * yy;
      angle.values[2 * i] = sigma * 0.1;
      wheel_y.values[2 * i] = -sigma * yy;
      status.status[2 * i] = status::kConverged;
      radius.values[2 * i + 1] = 0.9;
      separation.values[2 * i + 1] = 1e-4;
      status.status[2 * i + 1] = i % 2 ? status::kConverged : 0u;
    }
    g.datasets = {radius, angle, separation, wheel_y, status};
    t.groups.push_back(g);
  }
  const LateralFunctions f = lateral_functions_from_table(t, "cone.h5");
  EXPECT_EQ(f.name, "cone");
  EXPECT_EQ(f.roll_mode, "fixed 0 rad");
  ASSERT_EQ(f.y.size(), n);
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_NEAR(f.delta_r[i], 2.0 * c * f.y[i], 1e-15);
    EXPECT_NEAR(f.angle_right[i], 0.1, 1e-15);
  }
  EXPECT_NEAR(f.e0, 0.75, 1e-12);
  EXPECT_NEAR(f.r0, 0.46, 1e-12);
  const ConicityCurve curve = compute_conicity(f, {0.003, 0.009});
  EXPECT_NEAR(curve.points[0].conicity, c, 1e-9);
  EXPECT_NEAR(curve.points[1].conicity, c, 1e-9);
  // A roll axis without the node 0 is refused, naming the file.
  t.axes.push_back(TableAxis{"roll", "rad", "roll", {0.001, 0.002}, false});
  try {
    lateral_functions_from_table(t, "cone.h5");
    FAIL() << "no throw";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cone.h5"), std::string::npos) << e.what();
  }
}

TEST(Conicity, RefusesBadAmplitudes) {
  LateralFunctions f;
  for (int i = -10; i <= 10; ++i) {
    f.y.push_back(i * 1e-3);
    f.roll.push_back(0.0);
    f.delta_r.push_back(0.2 * i * 1e-3);
    f.delta_tan_gamma.push_back(0.0);
  }
  EXPECT_THROW(compute_conicity(f, {}), Error);
  EXPECT_THROW(compute_conicity(f, {0.002, -0.001}), Error);
  EXPECT_THROW(compute_conicity(f, {std::nan("")}), Error);
  // Beyond the samples: NaN, reported as null in JSON.
  const ConicityCurve curve = compute_conicity(f, {0.002, 0.02});
  EXPECT_TRUE(std::isnan(curve.points[1].conicity));
  const nlohmann::json j = conicity_json(curve);
  EXPECT_TRUE(j["equivalent_conicity"][1].is_null());
  EXPECT_NEAR(j["equivalent_conicity"][0].get<double>(), 0.1, 1e-12);
}

TEST(Conicity, WritesJsonCsvAndChart) {
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) GTEST_SKIP() << "gnuplot not installed";
  testing::TempDir dir("conicity_files");
  ConicitySweep sweep;
  sweep.equilibrium_roll = false;
  sweep.y_max = 0.006;
  sweep.y_step = 0.2e-3;
  const ConicityCurve a =
      compute_conicity(lateral_functions_from_solver(cone_on_knife_edge(0.05), "cone \"a\"", "cone", sweep), {0.002, 0.005});
  const ConicityCurve b =
      compute_conicity(lateral_functions_from_solver(cone_on_knife_edge(0.1), "cone b", "cone", sweep), {0.002, 0.005});
  const ConicityFiles files = write_conicity_outputs(dir.path(), a, b);
  for (const char* name : {"conicity.csv", "conicity_functions.csv", "conicity_compare.csv",
                           "conicity_compare_functions.csv", "conicity.json", "conicity.gp", "conicity.png"}) {
    EXPECT_TRUE(std::filesystem::is_regular_file(dir / name)) << name;
  }
  EXPECT_EQ(files.written.size(), 7u);
  std::ifstream in(dir / "conicity.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  ASSERT_EQ(j["amplitude_m"].size(), 2u);
  EXPECT_NEAR(j["amplitude_m"][1].get<double>(), 0.005, 1e-15);
  EXPECT_NEAR(j["equivalent_conicity"][0].get<double>(), 0.05, 1e-8);
  EXPECT_NEAR(j["compare"]["equivalent_conicity"][1].get<double>(), 0.1, 1e-8);
  EXPECT_EQ(j["pair"], "cone \"a\"");
}

}  // namespace
}  // namespace railtab
