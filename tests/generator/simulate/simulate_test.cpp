// SPDX-License-Identifier: Apache-2.0
// railtab simulate: a small Hertz table generated here (a second or so), a wheelset and a bogie
// run over it through LookupContactModel, the wear post-processors fed the same states, the direct
// model against the table at a grid node, and the simulation scene's located errors.
#include <gtest/gtest.h>
#include <unistd.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "core/check.hpp"
#include "error_message.hpp"
#include "scene/scene.hpp"
#include "scene/simulation_scene.hpp"
#include "simulate/bogie_run.hpp"
#include "simulate/direct_contact_model.hpp"
#include "simulate/lookup_contact_model.hpp"
#include "simulate/simulation_run.hpp"
#include "simulate/wear_accumulator.hpp"
#include "simulate/worn_profile.hpp"
#include "generate/generate.hpp"
#include "table/interrupt.hpp"
#include "table/storage_precision.hpp"
#include "vehicle/wheelset_model.hpp"

namespace railtab {
namespace {

namespace fs = std::filesystem;

// S1002 / UIC60 1:40, Hertz, loads around the default wheelset's 39 kN static wheel load. The
// creepage grid is wide enough for the runs below (checked: no query out of range).
constexpr const char* kSceneText = R"(
[scene]
name = "simulate-test"
[profiles]
wheel = "s1002"
rail = "uic60"
[contact]
normal_model = "hertz"
friction = 0.3
speed = 20.0
[grid]
y = { start = -0.010, stop = 0.010, step = 0.001 }
equilibrium_roll = true
load = [20e3, 40e3, 60e3]
xi = [-0.02, -0.004, -0.001, 0.0, 0.001, 0.004, 0.02]
eta = [-0.02, -0.004, -0.001, 0.0, 0.001, 0.004, 0.02]
phi = [-2.0, -0.5, 0.0, 0.5, 2.0]
)";

class SimulateTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::temp_directory_path() / ("railtab_simulate_test_" + std::to_string(::getpid())));
    fs::create_directories(*dir_);
    std::ofstream(*dir_ / "scene.toml") << kSceneText;
    GenerateOptions g;
    g.scene = *dir_ / "scene.toml";
    g.output = *dir_ / "table.h5";
    g.threads = 2;
    generate_table(g);
  }
  static void TearDownTestSuite() {
    std::error_code ec;
    fs::remove_all(*dir_, ec);
    delete dir_;
  }
  static Scene scene() { return load_scene(*dir_ / "scene.toml"); }
  static lookup::Table table() { return lookup::Table::load((*dir_ / "table.h5").string()); }

  // Runs `seconds` on tangent track without irregularity at 20 m/s from lateral offset y0 and
  // checks every step: finite, within the flange play, creep forces within mu N per slot.
  static double run_tangent(LookupContactModel& contact, double y0, double seconds) {
    const vehicle::TrackLayout track({vehicle::TrackSection{1000.0, 0.0, 0.0, 0.0, 0.0}}, vehicle::Irregularity{});
    vehicle::WheelsetState initial;
    initial.y = y0;
    vehicle::WheelsetSimulation sim(vehicle::WheelsetParameters{}, track, contact, 20.0, 0.5e-3, initial);
    const double mu = 0.3;
    double max_abs_y = 0.0;
    while (sim.time() < seconds) {
      sim.step();
      const vehicle::ContactSnapshot& s = sim.snapshot();
      EXPECT_TRUE(std::isfinite(sim.state().y) && std::isfinite(sim.state().yaw)) << "t = " << sim.time();
      EXPECT_LT(std::abs(sim.state().y), 0.012) << "t = " << sim.time();  // beyond the flange play
      for (int w = 0; w < vehicle::kWheels; ++w) {
        for (int k = 0; k < vehicle::kContactSlots; ++k) {
          const vehicle::SlotContact& c = s.contacts[w].slot[k];
          if (!c.loaded) continue;
          const double f = std::hypot(s.forces[w][k].fx, s.forces[w][k].fy);
          EXPECT_LE(f, mu * c.normal_force * (1.0 + 1e-9)) << "t = " << sim.time() << " wheel " << w << " slot " << k;
        }
      }
      if (::testing::Test::HasFailure()) break;  // one message, not thousands
      max_abs_y = std::max(max_abs_y, std::abs(sim.state().y));
    }
    return max_abs_y;
  }

  static fs::path* dir_;
};
fs::path* SimulateTest::dir_ = nullptr;

TEST_F(SimulateTest, CentredWheelsetStaysCentredOnPerfectTangentTrack) {
  LookupContactModel contact(table());
  const double max_abs_y = run_tangent(contact, 0.0, 3.0);
  std::printf("centred start, 3 s at 20 m/s: max |y| = %.3e m\n", max_abs_y);
  // Left and right are mirror images in the table, so nothing pushes the wheelset sideways: what
  // is left is round-off. 1 um is a thousandth of the tread's creep-dominated range.
  EXPECT_LT(max_abs_y, 1e-6);
  EXPECT_EQ(contact.counts().out_of_range, 0u);
  EXPECT_EQ(contact.counts().invalid_input, 0u);
  EXPECT_GT(contact.counts().queries, 0u);
}

TEST_F(SimulateTest, OffsetWheelsetStaysBoundedAndFinite) {
  LookupContactModel contact(table());
  const double max_abs_y = run_tangent(contact, 0.004, 3.0);
  std::printf("start at y = 4 mm, 3 s at 20 m/s: max |y| = %.3e m, out of range %llu of %llu queries\n", max_abs_y,
              static_cast<unsigned long long>(contact.counts().out_of_range),
              static_cast<unsigned long long>(contact.counts().queries));
  EXPECT_EQ(contact.counts().invalid_input, 0u);
}

TEST_F(SimulateTest, OutOfRangeQueriesAreCountedPerAxis) {
  LookupContactModel contact(table());
  vehicle::WheelContacts contacts[vehicle::kWheels];
  contact.normal(0.0, 0.0, {40e3, 40e3}, contacts);
  EXPECT_EQ(contact.counts().out_of_range, 0u);
  contact.normal(0.02, 0.0, {40e3, 90e3}, contacts);  // y beyond 10 mm, right load beyond 60 kN
  EXPECT_EQ(contact.counts().out_of_range, 2u);
  EXPECT_EQ(contact.counts().outside_axis[0], 2u);  // y, both wheels
  EXPECT_EQ(contact.counts().outside_axis[1], 1u);  // load, right wheel
  contact.normal(std::nan(""), 0.0, {40e3, 40e3}, contacts);
  EXPECT_EQ(contact.counts().invalid_input, 2u);
}

// The lookup and the direct model at a grid node (y, yaw, loads and creepages on nodes) agree to
// the table's storage rounding; returns the number of loaded slots compared.
int expect_lookup_matches_direct(LookupContactModel& lookup_model, DirectContactModel& direct_model, double y,
                                 double yaw, const double (&load)[vehicle::kWheels]) {
  vehicle::WheelContacts a[vehicle::kWheels], b[vehicle::kWheels];
  lookup_model.normal(y, yaw, load, a);
  direct_model.normal(y, yaw, load, b);
  vehicle::SlotCreepage creepage[vehicle::kWheels][vehicle::kContactSlots];
  for (auto& wheel : creepage) {
    wheel[0] = {0.001, -0.004, 0.5};  // creepage nodes
    wheel[1] = {-0.02, 0.004, -2.0};
  }
  vehicle::SlotForces fa[vehicle::kWheels][vehicle::kContactSlots], fb[vehicle::kWheels][vehicle::kContactSlots];
  lookup_model.creep(creepage, fa);
  direct_model.creep(creepage, fb);
  int loaded = 0;
  for (int w = 0; w < vehicle::kWheels; ++w) {
    for (int k = 0; k < vehicle::kContactSlots; ++k) {
      const vehicle::SlotContact& ca = a[w].slot[k];
      const vehicle::SlotContact& cb = b[w].slot[k];
      SCOPED_TRACE(testing::Message() << "y = " << y << " yaw = " << yaw << " wheel " << w << " slot " << k);
      EXPECT_EQ(ca.loaded, cb.loaded);
      if (!ca.loaded || !cb.loaded) continue;
      ++loaded;
      const double n = cb.normal_force;
      // The creep part (forces and the per-creepage N) is stored as float32 rounded to 20
      // significant bits (format 2.2, table/storage_precision.hpp): each value within 2^-20 of
      // itself, a force built from F / (mu N) and N within 4 x 2^-20 of N. Geometry is float64.
      const double stored = 1e-9 * n + 4.0 * kStoredRounding * n;
      EXPECT_NEAR(ca.normal_force, n, stored);
      EXPECT_NEAR(ca.contact_angle, cb.contact_angle, 1e-9);
      EXPECT_NEAR(ca.rolling_radius, cb.rolling_radius, 1e-12);
      EXPECT_NEAR(ca.wheel_u, cb.wheel_u, 1e-12);
      EXPECT_NEAR(fa[w][k].fx, fb[w][k].fx, stored);
      EXPECT_NEAR(fa[w][k].fy, fb[w][k].fy, stored);
      EXPECT_NEAR(fa[w][k].mz, fb[w][k].mz, stored);
    }
  }
  return loaded;
}

TEST_F(SimulateTest, LookupAndDirectAgreeAtAGridNode) {
  LookupContactModel lookup_model(table());
  DirectContactModel direct_model(scene());
  const double load[vehicle::kWheels] = {40e3, 60e3};  // load nodes
  for (double y : {0.0, 0.003, -0.007}) {               // y nodes, tread and flange contact
    EXPECT_GE(expect_lookup_matches_direct(lookup_model, direct_model, y, 0.0, load), 2) << "y = " << y;
  }
  EXPECT_EQ(direct_model.failures(), 0u);
}

// A table with a yaw axis is read at the wheelset's yaw: the lookup model at a yaw node is the
// direct model at that yaw, which differs measurably from yaw 0 in flange contact; a yaw-free
// table answers the same at any yaw and counts nothing. Without the yaw in the lookup State the
// lookup would return the yaw-0 answer and miss the direct model's.
TEST_F(SimulateTest, YawTableIsReadAtTheWheelsetYaw) {
  const fs::path dir = *dir_ / "yaw";
  fs::create_directories(dir);
  std::string text = kSceneText;
  const std::string creep_grid = text.substr(text.find("xi = "));
  text.replace(text.find("xi = "), creep_grid.size(),
               "yaw = [-0.01, 0.0, 0.01]\n"
               "xi = [-0.02, 0.0, 0.001]\neta = [-0.004, 0.0, 0.004]\nphi = [-2.0, 0.0, 0.5]\n");
  std::ofstream(dir / "scene.toml") << text;
  GenerateOptions g;
  g.scene = dir / "scene.toml";
  g.output = dir / "table.h5";
  g.threads = 2;
  generate_table(g);
  LookupContactModel yaw_lookup(lookup::Table::load(g.output.string()));
  DirectContactModel yaw_direct(load_scene(g.scene));
  ASSERT_TRUE(yaw_lookup.has_yaw_axis());
  EXPECT_TRUE(yaw_lookup.table().yaw_even());  // a symmetric list: stored over yaw >= 0, read at |yaw|
  ASSERT_TRUE(yaw_direct.has_yaw_axis());

  const double load[vehicle::kWheels] = {40e3, 60e3};
  double largest_angle_change = 0.0, largest_force_change = 0.0;
  for (double y : {0.0, 0.007, -0.008}) {
    for (double yaw : {0.01, -0.01}) {
      EXPECT_GE(expect_lookup_matches_direct(yaw_lookup, yaw_direct, y, yaw, load), 2) << "y = " << y;
      vehicle::WheelContacts at_yaw[vehicle::kWheels], at_zero[vehicle::kWheels];
      yaw_lookup.normal(y, yaw, load, at_yaw);
      yaw_lookup.normal(y, 0.0, load, at_zero);
      for (int w = 0; w < vehicle::kWheels; ++w) {
        for (int k = 0; k < vehicle::kContactSlots; ++k) {
          const vehicle::SlotContact& a = at_yaw[w].slot[k];
          const vehicle::SlotContact& b = at_zero[w].slot[k];
          if (!a.loaded || !b.loaded) continue;
          largest_angle_change = std::max(largest_angle_change, std::abs(a.contact_angle - b.contact_angle));
          largest_force_change = std::max(largest_force_change, std::abs(a.normal_force - b.normal_force) / b.normal_force);
        }
      }
    }
  }
  std::printf("yaw +-10 mrad against 0: contact angle up to %.3e rad, normal force up to %.3e relative\n",
              largest_angle_change, largest_force_change);
  // Far above the storage rounding (float64 geometry, 4 x 2^-20 for N): yaw reached the table.
  EXPECT_GT(largest_angle_change, 1e-4);
  EXPECT_GT(largest_force_change, 100.0 * kStoredRounding);
  EXPECT_EQ(yaw_lookup.counts().out_of_range, 0u);

  // Beyond the axis: clamped to the last node and counted against yaw.
  vehicle::WheelContacts beyond[vehicle::kWheels], last[vehicle::kWheels];
  yaw_lookup.normal(0.007, 0.02, load, beyond);
  EXPECT_EQ(yaw_lookup.counts().outside_axis[5], 2u);  // yaw, both wheels
  yaw_lookup.normal(0.007, 0.01, load, last);
  EXPECT_EQ(beyond[0].slot[1].normal_force, last[0].slot[1].normal_force);

  // The yaw-free table: yaw 0 is the only yaw it has, so any yaw gives the same answer, unflagged.
  LookupContactModel plain(table());
  EXPECT_FALSE(plain.has_yaw_axis());
  vehicle::WheelContacts p0[vehicle::kWheels], p1[vehicle::kWheels];
  plain.normal(0.007, 0.0, load, p0);
  plain.normal(0.007, 0.01, load, p1);
  for (int w = 0; w < vehicle::kWheels; ++w) {
    for (int k = 0; k < vehicle::kContactSlots; ++k) {
      EXPECT_EQ(p0[w].slot[k].normal_force, p1[w].slot[k].normal_force);
      EXPECT_EQ(p0[w].slot[k].contact_angle, p1[w].slot[k].contact_angle);
    }
  }
  EXPECT_EQ(plain.counts().out_of_range, 0u);
}

// A bogie with wheel loads inside the test table's 20-60 kN: (1500 + 20620 / 4 + 3000 / 2) g / 2
// = 40.0 kN.
constexpr const char* kLightVehicle = "[vehicle]\nbody_mass = 20620.0\n";

// The whole loop on a short route: two wear steps (table, run, wear, worn profile, next table),
// two post-processors: step 0 is one shared dynamics run, step 1 one run per post-processor on
// its own worn wheel.
TEST_F(SimulateTest, RunWritesEveryStepAndTheWornProfileFeedsTheNextStep) {
  std::ofstream(*dir_ / "sim.toml") << "[simulation]\nname = \"short\"\ncontact_scene = \"scene.toml\"\n"
                                        "wear_post_processors = [\"hertz\", \"stripes-a\"]\n"
                                        "positions = [\"leading\", \"trailing\"]\n"
                                        "speed = 20.0\nwear_steps = 2\nrunning_distance = 1.0e6\n"
                                        "profile_smoothing = 0.004\n"
                                     << kLightVehicle
                                     << "[route]\n[[route.section]]\nkind = \"tangent\"\nlength = 20.0\n"
                                        "[[route.section]]\nkind = \"transition\"\nlength = 20.0\n"
                                        "[[route.section]]\nkind = \"circular\"\nlength = 20.0\nradius = 1000.0\n";
  const SimulationScene sim = load_simulation_scene(*dir_ / "sim.toml");
  EXPECT_EQ(sim.dynamics_model, "hertz");  // the default, as Gensys
  SimulationOptions options;
  options.out = *dir_ / "out";
  options.threads = 2;
  const SimulationSummary summary = run_simulation(sim, options);
  ASSERT_EQ(summary.models.size(), 2u);
  ASSERT_EQ(summary.runs.size(), 3u);  // shared step 0, then one per post-processor
  EXPECT_EQ(summary.runs[0].label, "shared");
  for (const ModelSummary& m : summary.models) {
    SCOPED_TRACE(m.model);
    ASSERT_EQ(m.steps.size(), 2u);
    EXPECT_EQ(m.steps[0].runs.at(0).label, "shared");
    EXPECT_EQ(m.steps[1].runs.at(0).label, m.model);
    for (const StepSummary& step : m.steps) {
      SCOPED_TRACE(testing::Message() << "step " << step.step);
      EXPECT_GT(step.worn_area, 0.0);
      EXPECT_TRUE(std::isfinite(step.worn_area));
      EXPECT_EQ(step.wear_failures, 0);
      const RunSummary& r = step.runs.at(0);
      EXPECT_NEAR(r.distance, 60.0 - 2 * sim.vehicle.wheelset.semi_wheelbase, 0.02);
      EXPECT_EQ(r.out_of_range, 0u);
      EXPECT_LT(r.max_creep_force_ratio, 1.0 + 1e-9);
      EXPECT_GT(r.wear_samples, 15);
    }
    EXPECT_NEAR(m.steps[1].cumulative_worn_area, m.steps[0].worn_area + m.steps[1].worn_area,
                1e-12 * m.steps[1].cumulative_worn_area);
    EXPECT_GE(m.flange_side_share, 0.0);
    EXPECT_LE(m.flange_side_share, 1.0);
  }
  // The same dynamics, a different wear model: different wear.
  EXPECT_NE(summary.models[0].steps[0].worn_area, summary.models[1].steps[0].worn_area);
  const fs::path out = *dir_ / "out" / "short";
  EXPECT_TRUE(fs::exists(out / "shared" / "step0" / "table.h5"));
  EXPECT_TRUE(fs::exists(out / "shared" / "step0" / "trajectory.csv"));
  EXPECT_EQ(load_scene(out / "shared" / "step0" / "scene.toml").normal.model, NormalModel::hertz);
  for (const char* p : {"hertz", "stripes-a"}) {
    EXPECT_TRUE(fs::exists(out / p / "step0" / "wear.csv"));
    EXPECT_TRUE(fs::exists(out / p / "step1" / "table.h5"));
    // Step 1 ran on the worn wheel its own post-processor wrote in step 0, with the dynamics'
    // (Hertz) table.
    const Scene step1 = load_scene(out / p / "step1" / "scene.toml");
    EXPECT_EQ(step1.wheel.file.filename(), "wheel_worn.txt");
    EXPECT_TRUE(fs::exists(out / p / "step1" / "wheel_worn.prw"));  // the same profile for SIMPACK
    EXPECT_EQ(step1.wheel.file.parent_path().filename(), "step1");
    EXPECT_EQ(step1.normal.model, NormalModel::hertz);
  }
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(out / "summary.json"));
  EXPECT_NEAR(j["post_processors"][0]["total_worn_area_m2"].get<double>(),
              summary.models[0].steps[1].cumulative_worn_area, 1e-15);
  EXPECT_EQ(j["dynamics_model"], "hertz");
}

// step_depth_limit: a step whose profile update (the smoothed mean depth) would pass the limit
// ends where it reaches it; the states are the same, so the wear per metre is the unlimited one's.
TEST_F(SimulateTest, DepthLimitedStepEndsWhereTheProfileUpdateReachesTheLimit) {
  const auto scene_text = [](const std::string& name, int steps, double limit) {
    return fmt::format("[simulation]\nname = \"{}\"\ncontact_scene = \"scene.toml\"\n"
                       "wear_post_processors = [\"hertz\"]\nspeed = 20.0\nwear_steps = {}\n"
                       "running_distance = 2.0e6\nprofile_smoothing = 0.004\nstep_depth_limit = {:.17g}\n{}"
                       "[route]\n[[route.section]]\nkind = \"tangent\"\nlength = 20.0\n"
                       "[[route.section]]\nkind = \"transition\"\nlength = 20.0\n"
                       "[[route.section]]\nkind = \"circular\"\nlength = 20.0\nradius = 1000.0\n",
                       name, steps, limit, kLightVehicle);
  };
  SimulationOptions options;
  options.out = *dir_ / "out";
  options.threads = 2;
  std::ofstream(*dir_ / "fixed.toml") << scene_text("fixed", 1, 0.0);
  const SimulationSummary fixed = run_simulation(load_simulation_scene(*dir_ / "fixed.toml"), options);
  const StepSummary& f = fixed.models.at(0).steps.at(0);
  EXPECT_FALSE(f.depth_limited);
  EXPECT_DOUBLE_EQ(f.running_distance, 2.0e6);
  ASSERT_GT(f.profile_peak_depth, 0.0);

  const double limit = 0.25 * f.profile_peak_depth;
  std::ofstream(*dir_ / "limited.toml") << scene_text("limited", 2, limit);
  const SimulationSummary limited = run_simulation(load_simulation_scene(*dir_ / "limited.toml"), options);
  const ModelSummary& m = limited.models.at(0);
  ASSERT_EQ(m.steps.size(), 2u);
  const StepSummary& s0 = m.steps[0];
  EXPECT_TRUE(s0.depth_limited);
  EXPECT_DOUBLE_EQ(s0.profile_peak_depth, limit);
  // The same states as the fixed run's 2000 km step, a quarter of its peak: 500 km.
  EXPECT_NEAR(s0.running_distance, 0.25 * f.running_distance, 1e-9 * f.running_distance);
  EXPECT_NEAR(s0.worn_area / s0.running_distance, f.worn_area / f.running_distance,
              1e-9 * f.worn_area / f.running_distance);
  // The profile update actually written: wear.csv's mean depth, smoothed as the profile.
  std::ifstream csv(*dir_ / "out" / "limited" / "hertz" / "step0" / "wear.csv");
  std::string line;
  std::getline(csv, line);
  std::vector<double> u, mean;
  while (std::getline(csv, line)) {
    std::vector<double> v;
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) v.push_back(std::stod(cell));
    u.push_back(v.front());
    mean.push_back(v[v.size() - 2]);  // depth_mean_m
  }
  const std::vector<double> update = smooth_depth(u, mean, 0.004);
  EXPECT_NEAR(*std::max_element(update.begin(), update.end()), limit, 1e-5 * limit);
  // Step 1 is never longer than the nominal step nor deeper than the limit.
  EXPECT_LE(m.steps[1].running_distance, 1.0e6);
  EXPECT_LE(m.steps[1].profile_peak_depth, limit * (1.0 + 1e-12));
  EXPECT_DOUBLE_EQ(m.running_distance, s0.running_distance + m.steps[1].running_distance);
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(*dir_ / "out" / "limited" / "summary.json"));
  EXPECT_EQ(j["post_processors"][0]["steps"][0]["depth_limited"], true);
  EXPECT_DOUBLE_EQ(j["post_processors"][0]["running_distance_m"].get<double>(), m.running_distance);
}

// Every post-processor works from the same wheelset states: the states recorded during one
// bogie run, fed again to fresh accumulators, give each post-processor's wear bit for bit.
TEST_F(SimulateTest, WearPostProcessorsSeeTheSameWheelsetStates) {
  const SimulationScene sim = parse_simulation_scene(
      std::string("[simulation]\ncontact_scene = \"scene.toml\"\nwear_post_processors = [\"hertz\", \"stripes-a\", "
                  "\"kik-piotrowski\"]\npositions = [\"leading\", \"trailing\"]\nspeed = 20.0\n"
                  "running_distance = 1e6\n[route]\n[[route.section]]\nkind = \"tangent\"\nlength = 10.0\n"
                  "[[route.section]]\nkind = \"transition\"\nlength = 10.0\n"
                  "[[route.section]]\nkind = \"circular\"\nlength = 20.0\nradius = 800.0\n"
                  "[route.irregularity]\namplitude = 0.002\n") +
          kLightVehicle,
      "sim.toml", *dir_);
  const Scene contact_scene = scene();
  LookupContactModel contact(table());
  WearPostProcessing wear(contact_scene, sim.wear_post_processors, sim.positions);
  std::vector<WheelsetSample> recorded;
  wear.record_samples(&recorded);
  const RunSummary run = run_bogie(sim, contact, &contact, nullptr, 0.3, 0.0, *dir_ / "trajectory_same.csv", wear);
  EXPECT_EQ(run.out_of_range, 0u);
  ASSERT_GT(recorded.size(), 20u);
  for (std::size_t p = 0; p < sim.wear_post_processors.size(); ++p) {
    for (std::size_t i = 0; i < sim.positions.size(); ++i) {
      SCOPED_TRACE(testing::Message() << sim.wear_post_processors[p] << " " << sim.positions[i]);
      WearAccumulator replay(contact_scene, sim.wear_post_processors[p]);
      for (const WheelsetSample& s : recorded) {
        if (s.wheelset == static_cast<int>(i)) replay.sample(s.y_relative, s.load, s.motion, s.distance);
      }
      const WearAccumulator& live = wear.accumulator(p, i);
      EXPECT_EQ(live.samples(), replay.samples());
      EXPECT_EQ(live.samples(), wear.accumulator(0, i).samples());
      EXPECT_EQ(live.distance(), wear.accumulator(0, i).distance());
      for (int w = 0; w < vehicle::kWheels; ++w) EXPECT_EQ(live.depth(w), replay.depth(w)) << "wheel " << w;
      EXPECT_GT(live.worn_area(0) + live.worn_area(1), 0.0);
    }
  }
  // The samples carry the dynamics' vertical contact force, close to the static 40 kN per wheel
  // (the curve transfers some of it to the outer wheel).
  for (const WheelsetSample& s : recorded) {
    EXPECT_NEAR(s.load[0] + s.load[1], 2 * 40.0e3, 0.02 * 80.0e3);
  }
}

// A minimal valid simulation scene; `extra` is appended to [simulation].
std::string simulation_text(const std::string& extra) {
  return "[simulation]\ncontact_scene = \"scene.toml\"\nwear_post_processors = [\"hertz\"]\nspeed = 20.0\n"
         "running_distance = 1e6\n" +
         extra +
         "\n[route]\n[[route.section]]\nkind = \"tangent\"\nlength = 100.0\n"
         "[[route.section]]\nkind = \"transition\"\nlength = 50.0\n"
         "[[route.section]]\nkind = \"circular\"\nlength = 100.0\nradius = 600.0\ncant = 0.15\n";
}

std::string error_of(const std::string& text, const fs::path& base) {
  return test::error_message([&] { parse_simulation_scene(text, "sim.toml", base); });
}

TEST_F(SimulateTest, SimulationSceneParsesAndResolvesTransitions) {
  const SimulationScene s = parse_simulation_scene(simulation_text(""), "sim.toml", *dir_);
  ASSERT_EQ(s.route.size(), 3u);
  EXPECT_DOUBLE_EQ(s.route[1].curvature_start, 0.0);
  EXPECT_DOUBLE_EQ(s.route[1].curvature_end, 1.0 / 600.0);
  EXPECT_DOUBLE_EQ(s.route[1].cant_end, 0.15);
  EXPECT_DOUBLE_EQ(s.route_length(), 250.0);
  EXPECT_EQ(s.name, "sim");
}

TEST_F(SimulateTest, BadSimulationSceneGivesALocatedError) {
  EXPECT_EQ(error_of(simulation_text("sped = 3.0"), *dir_).rfind("sim.toml:6: simulation.sped: unknown key", 0), 0u)
      << error_of(simulation_text("sped = 3.0"), *dir_);
  // The name is a directory under --out: "../x" would write beside it.
  for (const char* name : {"../escape", "a/b", "..", ""}) {
    const std::string text = simulation_text(fmt::format("name = \"{}\"", name));
    EXPECT_NE(error_of(text, *dir_).find("sim.toml:6: simulation.name: must be a plain directory name"),
              std::string::npos)
        << name << ": " << error_of(text, *dir_);
  }
  EXPECT_NE(error_of(simulation_text("time_step = \"fast\""), *dir_).find("sim.toml:6: simulation.time_step: expected a number"),
            std::string::npos);
  std::string bad_model = simulation_text("");
  bad_model.replace(bad_model.find("[\"hertz\"]"), 9, "[\"hertzz\"]");
  EXPECT_NE(error_of(bad_model, *dir_).find("sim.toml:3: simulation.wear_post_processors: unknown wear post-processor"),
            std::string::npos)
      << error_of(bad_model, *dir_);
  std::string halfspace = simulation_text("");
  halfspace.replace(halfspace.find("[\"hertz\"]"), 9, "[\"halfspace\"]");
  // The exact half-space post-processor is connected (simulate/halfspace_wheel_wear.hpp).
  EXPECT_EQ(parse_simulation_scene(halfspace, "sim.toml", *dir_).wear_post_processors,
            std::vector<std::string>{"halfspace"});
  EXPECT_NE(error_of(simulation_text("dynamics_model = \"stripes\""), *dir_)
                .find("sim.toml:6: simulation.dynamics_model: unknown normal model"),
            std::string::npos)
      << error_of(simulation_text("dynamics_model = \"stripes\""), *dir_);
  // The old key says what replaced it; the single-wheelset's carried mass is derived now.
  EXPECT_NE(error_of(simulation_text("models = [\"hertz\"]"), *dir_).find("replaced by dynamics_model"),
            std::string::npos);
  std::string carried = simulation_text("");
  carried.insert(carried.find("[route]"), "[vehicle]\ncarried_mass = 1000.0\n");
  EXPECT_NE(error_of(carried, *dir_).find("vehicle.carried_mass: the bogie vehicle derives"), std::string::npos)
      << error_of(carried, *dir_);
  EXPECT_NE(error_of(simulation_text("positions = [\"middle\"]"), *dir_).find("sim.toml:6: simulation.positions"),
            std::string::npos);
  EXPECT_NE(error_of(simulation_text("step_depth_limit = -1e-5"), *dir_).find("sim.toml:6: simulation.step_depth_limit"),
            std::string::npos)
      << error_of(simulation_text("step_depth_limit = -1e-5"), *dir_);
  // Missing required key, and a contact scene that does not exist.
  EXPECT_NE(error_of("[simulation]\ncontact_scene = \"scene.toml\"\nwear_post_processors = [\"hertz\"]\nspeed = 20.0\n", *dir_)
                .find("simulation.running_distance: missing required key"),
            std::string::npos);
  EXPECT_NE(error_of(simulation_text(""), "/nonexistent").find("simulation.contact_scene: no such file"),
            std::string::npos);
  // A radius on a transition.
  std::string text = simulation_text("");
  text.replace(text.find("length = 50.0"), 13, "length = 50.0\nradius = 300.0");
  EXPECT_NE(error_of(text, *dir_).find("route.section[2].radius"), std::string::npos) << error_of(text, *dir_);
}

// Ctrl-C (the flag `railtab simulate` hands in): the RK4 loop stops with Interrupted before it
// writes the trajectory, and run_simulation stops without a table, a summary or a temporary.
TEST_F(SimulateTest, InterruptStopsTheRunWithoutWritingHalfFiles) {
  const SimulationScene sim = parse_simulation_scene(
      std::string("[simulation]\nname = \"stopped\"\ncontact_scene = \"scene.toml\"\n"
                  "wear_post_processors = [\"hertz\"]\nspeed = 20.0\nrunning_distance = 1e6\n"
                  "[route]\n[[route.section]]\nkind = \"tangent\"\nlength = 20.0\n") +
          kLightVehicle,
      "sim.toml", *dir_);
  std::atomic<bool> stop{true};
  LookupContactModel contact(table());
  WearPostProcessing wear(scene(), sim.wear_post_processors, sim.positions);
  const fs::path trajectory = *dir_ / "trajectory_stopped.csv";
  EXPECT_THROW(run_bogie(sim, contact, &contact, nullptr, 0.3, 0.0, trajectory, wear, &stop), Interrupted);
  EXPECT_FALSE(fs::exists(trajectory));
  stop = false;  // the same run without the flag finishes and writes it
  run_bogie(sim, contact, &contact, nullptr, 0.3, 0.0, trajectory, wear, &stop);
  EXPECT_TRUE(fs::exists(trajectory));

  stop = true;
  SimulationOptions options;
  options.out = *dir_ / "out_stopped";
  options.threads = 1;
  options.interrupt = &stop;
  fs::create_directories(options.out / "stopped");
  std::ofstream(options.out / "stopped" / "summary.json") << "{}\n";  // a previous run's: removed first
  try {
    run_simulation(sim, options);
    ADD_FAILURE() << "run_simulation ignored the interrupt flag";
  } catch (const Interrupted& e) {
    EXPECT_NE(std::string(e.what()).find("stopped shared step 0: interrupted"), std::string::npos) << e.what();
  }
  for (const auto& entry : fs::recursive_directory_iterator(options.out)) {
    EXPECT_FALSE(entry.is_regular_file() && entry.path().filename() != "scene.toml") << entry.path();
  }
}

// Absurd time steps, distances and step counts are refused when the scene is read, naming the
// file, the line and the key: time_step 1e-300 made a run that never ended, running_distance
// 1e300 a worn profile 1e290 mm deep written with exit 0.
TEST_F(SimulateTest, AbsurdTimeStepDistanceAndStepCountAreRefusedUpFront) {
  EXPECT_NE(error_of(simulation_text("time_step = 1e-300"), *dir_).find("sim.toml:6: simulation.time_step: must be in "
                                                                        "[1e-6, 0.01] s, got 1e-300"),
            std::string::npos)
      << error_of(simulation_text("time_step = 1e-300"), *dir_);
  std::string huge = simulation_text("");
  huge.replace(huge.find("running_distance = 1e6"), 22, "running_distance = 1e300");
  EXPECT_NE(error_of(huge, *dir_).find("sim.toml:5: simulation.running_distance: must be in (0, 1e9] m"),
            std::string::npos)
      << error_of(huge, *dir_);
  // In range each, too many steps together: 1e6 m at 20 m/s in 1e-5 s steps is 5e9 steps.
  std::string long_route = simulation_text("time_step = 1e-5");
  long_route.replace(long_route.find("length = 100.0"), 14, "length = 1e6");
  EXPECT_NE(error_of(long_route, *dir_).find("sim.toml:6: simulation.time_step: 1e-05 s steps over the route"),
            std::string::npos)
      << error_of(long_route, *dir_);
  EXPECT_NO_THROW(parse_simulation_scene(simulation_text("time_step = 1e-6"), "sim.toml", *dir_));
}

// A dynamics run that blows up (here: a 15 kg wheelset at 10 ms steps) stops at the step where
// it leaves the rail head, naming the scene, the time and the time step; it ended with "wear
// sample: speed must be > 0 m/s, got 0" and no scene before.
TEST_F(SimulateTest, BlownUpDynamicsStopsNamingTheSceneAndTheStep) {
  std::ofstream(*dir_ / "blowup.toml") << "[simulation]\ncontact_scene = \"scene.toml\"\n"
                                          "wear_post_processors = [\"hertz\"]\nspeed = 20.0\ntime_step = 0.01\n"
                                          "running_distance = 1e6\n[vehicle]\nbody_mass = 20620.0\nmass = 15.0\n"
                                          "yaw_inertia = 0.7\n[route]\n[[route.section]]\nkind = \"tangent\"\n"
                                          "length = 40.0\n";
  const SimulationScene sim = load_simulation_scene(*dir_ / "blowup.toml");
  LookupContactModel contact(table());
  WearPostProcessing wear(scene(), sim.wear_post_processors, sim.positions);
  const std::string message = test::error_message(
      [&] { run_bogie(sim, contact, &contact, nullptr, 0.3, 0.0, *dir_ / "trajectory_blowup.csv", wear); });
  EXPECT_NE(message.find("blowup.toml: the dynamics blew up at t = "), std::string::npos) << message;
  EXPECT_NE(message.find("simulation.time_step = 0.01 s"), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(*dir_ / "trajectory_blowup.csv"));
}

// A step whose profile update would be deeper than a wheel can wear in one step is an error
// naming the scene, the post-processor and the step, not a worn profile written with exit 0.
TEST_F(SimulateTest, ProfileUpdateBeyondAnyWheelWearIsRefused) {
  std::ofstream(*dir_ / "deep.toml") << "[simulation]\ncontact_scene = \"scene.toml\"\n"
                                        "wear_post_processors = [\"hertz\"]\nspeed = 20.0\nrunning_distance = 1e9\n"
                                     << kLightVehicle
                                     << "[route]\n[[route.section]]\nkind = \"tangent\"\nlength = 20.0\n"
                                        "[[route.section]]\nkind = \"transition\"\nlength = 20.0\n"
                                        "[[route.section]]\nkind = \"circular\"\nlength = 20.0\nradius = 300.0\n";
  SimulationOptions options;
  options.out = *dir_ / "out_deep";
  options.threads = 2;
  const std::string message =
      test::error_message([&] { run_simulation(load_simulation_scene(*dir_ / "deep.toml"), options); });
  EXPECT_NE(message.find("deep.toml: hertz step 0: the profile update would wear"), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(options.out / "deep" / "hertz" / "step1" / "wheel_worn.txt"));
  EXPECT_FALSE(fs::exists(options.out / "deep" / "summary.json"));
}

}  // namespace
}  // namespace railtab
