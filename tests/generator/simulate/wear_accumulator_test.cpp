// SPDX-License-Identifier: Apache-2.0
// Wear post-processing of a simulation (generator/simulate/wear_accumulator.hpp) and the profile update
// (generator/simulate/worn_profile.hpp, generator/charts/wear_chart.hpp).
#include "simulate/wear_accumulator.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numeric>
#include <string>

#include "charts/wear_chart.hpp"
#include "core/check.hpp"
#include "error_message.hpp"
#include "profile/formats/profile_io.hpp"
#include "profile/standard/s1002.hpp"
#include "simulate/worn_profile.hpp"

namespace railtab::wear_accumulator_test {  // own namespace: unity builds compile several test files as one
namespace {

const Scene& stripes_scene() {
  static const Scene scene = load_scene(std::filesystem::path(RAILTAB_SOURCE_DIR) / "tables/default_stripes.toml");
  return scene;
}

// A tread state with creepage on both wheels: 2 mm to the left (rolling radii differ from r0, so
// xi != 0 at Omega = V/r0) and a yaw of 2 mrad (eta about -0.002).
constexpr double kY = 0.002;
constexpr double kLoad[vehicle::kWheels] = {78.5e3, 78.5e3};
vehicle::WheelsetMotion tread_motion() {
  vehicle::WheelsetMotion m;
  m.speed = 20.0;
  m.yaw = 2e-3;
  m.spin_speed = m.speed / 0.46;
  return m;
}

double area_of(const std::vector<double>& depth, double step) {
  return step * std::accumulate(depth.begin(), depth.end(), 0.0);
}

std::filesystem::path temp_dir(const std::string& name) {
  const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
  const auto dir = std::filesystem::temp_directory_path() / ("railtab_wear_" + name + "_" + std::to_string(stamp));
  std::filesystem::create_directories(dir);
  return dir;
}

// The chain the accumulator runs, by hand: wear rate [m2/m] and the wheel_u / half-extent of the
// patches of wheel `w`.
struct HandWear {
  double wear_rate = 0.0;
  std::vector<double> patch_u;
};
HandWear wear_by_hand(const Scene& scene, int w) {
  const ContactGeometrySolver solver = make_geometry_solver(scene);
  const WheelsetContactGeometry geometry = solver.solve({kY, solver.equilibrium_roll(kY)});
  const WheelContactGeometry& wheel = geometry.wheels[static_cast<std::size_t>(w)];
  const WheelNormalResult normal = solve_normal_for_load(wheel, kLoad[w], scene.material, scene.normal);
  CreepConditions conditions = creep_conditions(scene);
  const vehicle::WheelsetMotion motion = tread_motion();
  conditions.speed = motion.speed;
  const double q0 = scene.wheelset.back_to_back / 2.0 - scene.wheelset.flange_back_position;
  HandWear out;
  FastsimWorkspace workspace;
  WearDistribution distribution;
  for (const ContactPatch& patch : normal.patches) {
    vehicle::SlotContact slot;
    slot.loaded = true;
    slot.contact_angle = patch.contact_angle;
    slot.rolling_radius = patch.rolling_radius;
    slot.wheel_u = patch.wheel_u;
    const vehicle::SlotCreepage c = vehicle::creepage(motion, w, slot, q0);
    fastsim_contact(wheel, patch, {c.xi, c.eta, c.phi}, conditions, scene.material, fastsim_options(scene), workspace);
    out.wear_rate += archard_wear(workspace, wear_options(scene), distribution).wear_rate;
    out.patch_u.push_back(patch.wheel_u);
  }
  return out;
}

TEST(WearAccumulator, WornAreaIsArchardWearRateTimesDistance) {
  for (NormalModel model : {NormalModel::stripes_ab, NormalModel::hertz}) {
    Scene scene = stripes_scene();
    scene.normal.model = model;
    WearAccumulator acc(scene);
    const double distance = 137.0;
    acc.sample(kY, kLoad, tread_motion(), distance);
    EXPECT_EQ(acc.failures(), 0);
    for (int w = 0; w < vehicle::kWheels; ++w) {
      const HandWear hand = wear_by_hand(scene, w);
      ASSERT_EQ(hand.patch_u.size(), 1u) << to_string(model) << " wheel " << w << ": meant to be tread only";
      ASSERT_GT(hand.wear_rate, 0.0) << to_string(model) << " wheel " << w;
      EXPECT_NEAR(acc.worn_area(w), hand.wear_rate * distance, 1e-9 * hand.wear_rate * distance)
          << to_string(model) << " wheel " << w;
      EXPECT_EQ(acc.clipped_area(w), 0.0);
      // The depth-weighted centre of the wear lies near the patch reference: a tread patch is
      // 10-20 mm wide, and wear (weighted by slip) and reference (weighted by interpenetration)
      // differ by the slip distribution only (measured 0.04-1.05 mm here).
      const auto& d = acc.depth(w);
      double moment = 0.0, sum = 0.0;
      for (std::size_t i = 0; i < d.size(); ++i) {
        moment += acc.u()[i] * d[i];
        sum += d[i];
      }
      EXPECT_NEAR(moment / sum, hand.patch_u[0], 2e-3) << to_string(model) << " wheel " << w;
    }
  }
}

TEST(WearAccumulator, SamplesAddAndScaleScales) {
  const Scene& scene = stripes_scene();
  WearAccumulator one(scene), two(scene);
  one.sample(kY, kLoad, tread_motion(), 50.0);
  two.sample(kY, kLoad, tread_motion(), 50.0);
  two.sample(kY, kLoad, tread_motion(), 150.0);
  EXPECT_EQ(two.samples(), 2);
  EXPECT_DOUBLE_EQ(two.distance(), 200.0);
  for (int w = 0; w < vehicle::kWheels; ++w) {
    ASSERT_GT(one.worn_area(w), 0.0);
    EXPECT_NEAR(two.worn_area(w), 4.0 * one.worn_area(w), 1e-12 * two.worn_area(w));
    for (std::size_t i = 0; i < one.depth(w).size(); ++i) {
      EXPECT_NEAR(two.depth(w)[i], 4.0 * one.depth(w)[i], 1e-12 * two.depth(w)[i]) << "bin " << i;
    }
  }
  const double before = two.worn_area(0);
  two.scale(0.25);
  EXPECT_NEAR(two.worn_area(0), 0.25 * before, 1e-15 * before);
  EXPECT_DOUBLE_EQ(two.distance(), 200.0);  // scale() multiplies the depth only
  EXPECT_THROW(two.scale(-1.0), Error);
}

TEST(WearAccumulator, NoLoadNoWear) {
  const Scene& scene = stripes_scene();
  WearAccumulator acc(scene);
  const double none[vehicle::kWheels] = {0.0, 0.0};
  const std::uint32_t bits = acc.sample(kY, none, tread_motion(), 100.0);
  EXPECT_TRUE(bits & status::kLiftOff);
  EXPECT_EQ(acc.worn_area(0), 0.0);
  EXPECT_EQ(acc.worn_area(1), 0.0);
  EXPECT_EQ(acc.failures(), 0);
  // One wheel unloaded: only the other one wears.
  const double left_only[vehicle::kWheels] = {78.5e3, 0.0};
  acc.sample(kY, left_only, tread_motion(), 100.0);
  EXPECT_GT(acc.worn_area(0), 0.0);
  EXPECT_EQ(acc.worn_area(1), 0.0);
}

TEST(WearAccumulator, FailingSolveIsCountedNotThrown) {
  WearAccumulator acc(stripes_scene());
  std::uint32_t bits = 0;
  EXPECT_NO_THROW(bits = acc.sample(std::nan(""), kLoad, tread_motion(), 100.0));
  EXPECT_TRUE(bits & status::kFailed);
  EXPECT_EQ(acc.failures(), 2);
  EXPECT_EQ(acc.worn_area(0) + acc.worn_area(1), 0.0);
  // Bad arguments are the caller's error.
  EXPECT_THROW(acc.sample(kY, kLoad, tread_motion(), -1.0), Error);
  vehicle::WheelsetMotion standing = tread_motion();
  standing.speed = 0.0;
  EXPECT_THROW(acc.sample(kY, kLoad, standing, 1.0), Error);
  EXPECT_THROW(WearAccumulator(stripes_scene(), WearGrid{0.0, 0.001, 0.0003}), Error);  // not whole steps
}

// (y, psi, ...) -> (-y, -psi, ...) mirrors the track about its centreline: the left wheel's wear
// at one state is the right wheel's at the other, bin by bin. This checks the orientation of
// wheel u on the right wheel (the elliptic strips run along s, towards -u there) on a flange state
// whose spin makes the wear inside each patch lopsided.
TEST(WearAccumulator, MirroredStateSwapsTheWheels) {
  for (NormalModel model : {NormalModel::hertz, NormalModel::stripes_ab}) {
    Scene scene = stripes_scene();
    scene.normal.model = model;
    vehicle::WheelsetMotion motion = tread_motion();
    motion.yaw = 4e-3;
    motion.curvature = 1.0 / 600.0;
    motion.lateral_velocity = 0.01;
    vehicle::WheelsetMotion mirrored = motion;
    mirrored.yaw = -motion.yaw;
    mirrored.curvature = -motion.curvature;
    mirrored.lateral_velocity = -motion.lateral_velocity;
    const double y = 0.0075, load[vehicle::kWheels] = {90e3, 60e3}, swapped[vehicle::kWheels] = {60e3, 90e3};
    WearAccumulator a(scene), b(scene);
    a.sample(y, load, motion, 100.0);
    b.sample(-y, swapped, mirrored, 100.0);
    for (int w = 0; w < vehicle::kWheels; ++w) {
      const auto& da = a.depth(w);
      const auto& db = b.depth(1 - w);
      const double peak = *std::max_element(da.begin(), da.end());
      ASSERT_GT(peak, 0.0);
      double worst = 0.0;
      for (std::size_t i = 0; i < da.size(); ++i) worst = std::max(worst, std::abs(da[i] - db[i]));
      EXPECT_LT(worst, 1e-6 * peak) << to_string(model) << " wheel " << w;
      std::printf("%-10s wheel %d: peak %.4g m, mirror mismatch %.3g m\n", to_string(model), w, peak, worst);
    }
  }
}


// A Hertz flange patch (left wheel, 7.5 mm towards its flange) wears the wheel profile over the
// ellipse's lateral extent projected on u, 2 b cos(beta), not over 2 b.
TEST(WearAccumulator, EllipticWearCoversTheProjectedEllipse) {
  Scene scene = stripes_scene();
  scene.normal.model = NormalModel::hertz;
  const double y = 0.0075, load[vehicle::kWheels] = {90e3, 60e3};
  const ContactGeometrySolver solver = make_geometry_solver(scene);
  const WheelsetContactGeometry geometry = solver.solve({y, solver.equilibrium_roll(y)});
  const WheelNormalResult normal = solve_normal_for_load(geometry.wheels[0], load[0], scene.material, scene.normal);
  ASSERT_EQ(normal.patches.size(), 1u);
  const ContactPatch& flange = normal.patches[0];
  const double beta = flange.contact_angle - geometry.wheels[0].wheel_roll;
  ASSERT_GT(beta, 0.8) << "meant to be a flange contact";

  WearAccumulator acc(scene);
  acc.sample(y, load, tread_motion(), 100.0);
  const WearGrid grid;
  double covered = 0.0;
  for (std::size_t i = 0; i < acc.u().size(); ++i) {
    if (acc.depth(0)[i] > 0.0) covered += grid.step;
  }
  std::printf("flange: 2b %.3f mm, beta %.3f rad, 2b cos(beta) %.3f mm, worn width %.3f mm\n", 2e3 * flange.semi_axis_b,
              beta, 2e3 * flange.semi_axis_b * std::cos(beta), 1e3 * covered);
  EXPECT_NEAR(covered, 2.0 * flange.semi_axis_b * std::cos(beta), 2.0 * grid.step)
      << "2b = " << 2.0 * flange.semi_axis_b << " m, beta = " << beta << " rad";
}

// Radial wear across the left wheel after a prescribed sinusoidal run on tangent track (as Knothe
// and Le-The's comparison in Enblom and Berg 2008: y = A sin(2 pi x / L), kinematic yaw psi = dy/dx, wheel
// speed V / r0), per 1000 km, Hertz+FASTSIM against STRIPES. Printed and drawn, not asserted:
//   RAILTAB_CHART_DIR=docs/img test_generator --gtest_also_run_disabled_tests
//     --gtest_filter='*SinusoidalRunChart*'
TEST(WearAccumulator, DISABLED_SinusoidalRunChart) {
  const char* env = std::getenv("RAILTAB_CHART_DIR");
  const std::filesystem::path dir = env ? std::filesystem::path(env) : temp_dir("chart");
  const double amplitude = 0.003, wavelength = 15.0, speed = 20.0;
  const int n = 60;  // samples per wavelength
  std::vector<WearSeries> series;
  for (NormalModel model : {NormalModel::hertz, NormalModel::stripes_a, NormalModel::stripes_ab}) {
    Scene scene = stripes_scene();
    scene.normal.model = model;
    WearAccumulator acc(scene);
    for (int i = 0; i < n; ++i) {
      const double k = 2.0 * M_PI / wavelength, x = (i + 0.5) * wavelength / n;
      vehicle::WheelsetMotion m;
      m.speed = speed;
      m.spin_speed = speed / scene.wheelset.nominal_radius;
      m.yaw = amplitude * k * std::cos(k * x);
      m.lateral_velocity = speed * m.yaw;
      m.yaw_rate = -speed * amplitude * k * k * std::sin(k * x);
      acc.sample(amplitude * std::sin(k * x), kLoad, m, wavelength / n);
    }
    acc.scale(1e6 / acc.distance());  // per 1000 km
    const auto& d = acc.depth(0);
    const auto peak = std::max_element(d.begin(), d.end());
    const double peak_u = acc.u()[static_cast<std::size_t>(peak - d.begin())];
    std::printf("%-11s left wheel per 1000 km: worn area %.3f mm2, peak depth %.4f mm at u = %.1f mm, failures %d\n",
                to_string(model), acc.worn_area(0) * 1e6, *peak * 1e3, peak_u * 1e3, acc.failures());
    series.push_back({to_string(model), acc.u(), d, model != NormalModel::hertz});
  }
  const auto png = dir / "wear-sinusoidal.png";
  draw_wear_chart(series, png,
                  "S1002/UIC60 1:40, sinusoidal run y = 3 mm sin(2 pi x / 15 m), 20 m/s, 78.5 kN: "
                  "left wheel, per 1000 km");
  std::printf("chart: %s\n", png.string().c_str());
}

// A narrow wear peak and a step on a uniform grid.
struct Synthetic {
  std::vector<double> u, depth;
  double step = 0.0002;
};
Synthetic synthetic_depth() {
  Synthetic s;
  for (int i = 0; i < 646; ++i) {  // centres -69 .. +60 mm: the S1002 profile nodes
    const double u = -0.069 + i * s.step;
    s.u.push_back(u);
    s.depth.push_back(1e-4 * std::exp(-0.5 * std::pow((u - 0.004) / 0.002, 2)) +  // tread: 0.1 mm
                      (u > -0.032 && u < -0.028 ? 3e-5 : 0.0) +                      // flange root box
                      (i == 0 ? 2e-5 : 0.0));                                        // at the grid end
  }
  return s;
}

TEST(WornProfile, SmoothingKeepsTheAreaAndLowersThePeak) {
  const Synthetic s = synthetic_depth();
  const std::vector<double> smooth = smooth_depth(s.u, s.depth, 0.005);
  const double area = area_of(s.depth, s.step);
  EXPECT_NEAR(area_of(smooth, s.step), area, 1e-12 * area);
  EXPECT_LT(*std::max_element(smooth.begin(), smooth.end()), *std::max_element(s.depth.begin(), s.depth.end()));
  for (double d : smooth) EXPECT_GE(d, 0.0);
  // Symmetric kernel: the centre of the tread bump stays where it was.
  double m0 = 0.0, m1 = 0.0;
  for (std::size_t i = 0; i < s.u.size(); ++i) {
    if (s.u[i] > -0.01) {
      m0 += smooth[i];
      m1 += smooth[i] * s.u[i];
    }
  }
  EXPECT_NEAR(m1 / m0, 0.004, 1e-6);
  EXPECT_EQ(smooth_depth(s.u, s.depth, 0.0), s.depth);
}

TEST(WornProfile, RoundTripThroughTheProfileReader) {
  const Synthetic s = synthetic_depth();
  const ProfilePtr wheel = make_s1002_profile();
  const auto dir = temp_dir("roundtrip");
  const auto file = dir / "worn.txt";
  write_worn_profile(*wheel, s.u, s.depth, 0.003, file);
  EXPECT_FALSE(std::filesystem::exists(file.string() + ".tmp"));
  const ProfilePtr worn = read_profile(file, ProfileKind::wheel);
  const std::vector<double> smooth = smooth_depth(s.u, s.depth, 0.003);
  EXPECT_DOUBLE_EQ(worn->u_min(), wheel->u_min());
  EXPECT_DOUBLE_EQ(worn->u_max(), wheel->u_max());
  int checked = 0;
  for (std::size_t i = 0; i < s.u.size(); ++i) {
    if (s.u[i] < -0.066 || s.u[i] > 0.057) continue;  // away from the ends
    EXPECT_NEAR(worn->eval(s.u[i]).z - wheel->eval(s.u[i]).z, smooth[i], 1e-9) << "u = " << s.u[i];
    ++checked;
  }
  EXPECT_GT(checked, 500);
  // The SIMPACK copy beside it holds the same profile (17 digits instead of the 9 decimals in mm
  // of the two-column file).
  const ProfilePtr simpack = read_profile(dir / "worn.prw", ProfileKind::wheel);
  EXPECT_DOUBLE_EQ(simpack->u_max(), wheel->u_max());
  for (double x = -0.06; x < 0.055; x += 0.001) EXPECT_NEAR(simpack->eval(x).z, worn->eval(x).z, 1e-11) << "u = " << x;
  std::filesystem::remove_all(dir);
}

// One step of the profile-evolution loop: wear accumulated on the new wheel, scaled to a
// visible depth, written as the next wheel profile, and a scene naming that file runs the next
// step. Its rolling radius at the worn spot is smaller by the smoothed depth.
TEST(WornProfile, WornWheelFeedsTheNextStep) {
  Scene scene = stripes_scene();
  WearAccumulator acc(scene);
  acc.sample(kY, kLoad, tread_motion(), 100.0);
  const auto& d = acc.depth(0);
  acc.scale(0.3e-3 / *std::max_element(d.begin(), d.end()));  // 0.3 mm peak
  const auto dir = temp_dir("step");
  const auto file = dir / "wheel_step1.txt";
  write_worn_profile(*make_s1002_profile(), acc.u(), acc.depth(0), 0.002, file);

  Scene next = scene;
  next.wheel.name = file.string();
  next.wheel.file = file;
  WearAccumulator step(next);
  step.sample(kY, kLoad, tread_motion(), 100.0);
  EXPECT_EQ(step.failures(), 0);
  EXPECT_GT(step.worn_area(0), 0.0);
  const ProfilePtr worn = read_profile(file, ProfileKind::wheel);
  const std::vector<double> smooth = smooth_depth(acc.u(), acc.depth(0), 0.002);
  const auto peak = static_cast<std::size_t>(std::max_element(smooth.begin(), smooth.end()) - smooth.begin());
  const double u = acc.u()[peak];
  EXPECT_GT(smooth[peak], 0.1e-3);
  EXPECT_NEAR(worn->eval(u).z - make_s1002_profile()->eval(u).z, smooth[peak], 1e-6);  // between nodes: spline
  std::filesystem::remove_all(dir);
}

TEST(WornProfile, BadInputThrowsNamingTheFile) {
  Synthetic s = synthetic_depth();
  const ProfilePtr wheel = make_s1002_profile();
  const auto dir = temp_dir("bad");
  const auto file = dir / "worn_nan.txt";
  s.depth[100] = std::nan("");
  std::string message = test::error_message([&] { write_worn_profile(*wheel, s.u, s.depth, 0.003, file); });
  EXPECT_NE(message.find("worn_nan.txt"), std::string::npos) << message;
  EXPECT_FALSE(std::filesystem::exists(file));
  s.depth[100] = 0.0;
  const auto unwritable = dir / "no_such_dir" / "worn.txt";
  message = test::error_message([&] { write_worn_profile(*wheel, s.u, s.depth, 0.003, unwritable); });
  EXPECT_NE(message.find(unwritable.string()), std::string::npos) << message;
  std::filesystem::remove_all(dir);
}

TEST(WearChart, DrawsThePng) {
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) GTEST_SKIP() << "gnuplot not installed";
  const Synthetic s = synthetic_depth();
  const auto dir = temp_dir("chart");
  draw_wear_chart({{"raw", s.u, s.depth, false}, {"smoothed", s.u, smooth_depth(s.u, s.depth, 0.003), true}},
                  dir / "wear.png", "synthetic wear");
  EXPECT_GT(std::filesystem::file_size(dir / "wear.png"), 1000u);
  EXPECT_TRUE(std::filesystem::exists(dir / "wear.csv"));
  EXPECT_THROW(draw_wear_chart({}, dir / "empty.png", "x"), Error);
  std::filesystem::remove_all(dir);
}

// Cost of one sample (both wheels), printed, not asserted:
//   test_generator --gtest_also_run_disabled_tests --gtest_filter='*SampleCost*'
TEST(WearAccumulator, DISABLED_SampleCost) {
  const int n = 200;
  {
    // The geometry alone (equilibrium roll + both wheels), which every sample pays first.
    const ContactGeometrySolver solver = make_geometry_solver(stripes_scene());
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < n; ++i) {
      const double y = kY * (i % 20) / 20.0;
      (void)solver.solve({y, solver.equilibrium_roll(y)});
    }
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("%-11s %8.1f us per sample (equilibrium roll + geometry of both wheels)\n", "geometry", 1e6 * s / n);
  }
  for (NormalModel model : {NormalModel::hertz, NormalModel::stripes_a, NormalModel::stripes_ab}) {
    Scene scene = stripes_scene();
    scene.normal.model = model;
    WearAccumulator acc(scene);
    acc.sample(kY, kLoad, tread_motion(), 1.0);  // warm-up: workspaces grow once
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < n; ++i) acc.sample(kY * (i % 20) / 20.0, kLoad, tread_motion(), 1.0);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("%-11s %8.1f us per sample (both wheels), %d samples, %d failures\n", to_string(model),
                1e6 * s / n, n, acc.failures());
  }
}

}  // namespace
}  // namespace railtab::wear_accumulator_test
