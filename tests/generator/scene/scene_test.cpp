// SPDX-License-Identifier: Apache-2.0
// Scene files (generator/scene/): defaults, every section, the shipped scenes, clear errors.
#include "scene/scene.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "core/check.hpp"
#include "error_message.hpp"

namespace railtab {
namespace {

constexpr const char* kMinimal = R"(
[scene]
name = "t"
[profiles]
wheel = "s1002"
rail = "uic60"
[grid]
y = [-0.001, 0.0, 0.001]
load = 78500
)";

// The message of the Error that parsing `text` throws ("" when it does not throw).
std::string error_of(const std::string& text) {
  return test::error_message([&] { parse_scene(text, "bad.toml"); });
}

TEST(Scene, MinimalSceneGetsDefaults) {
  Scene s = parse_scene(kMinimal, "t.toml");
  EXPECT_EQ(s.name, "t");
  EXPECT_EQ(s.wheel.name, "s1002");
  EXPECT_TRUE(s.wheel.file.empty());
  EXPECT_EQ(s.grids.y.size(), 3u);
  EXPECT_EQ(s.grids.load, std::vector<double>{78500.0});
  EXPECT_EQ(s.grids.roll, std::vector<double>{0.0});
  EXPECT_EQ(s.grids.xi, std::vector<double>{0.0});
  EXPECT_DOUBLE_EQ(s.track.rail_inclination, 1.0 / 40.0);
  EXPECT_EQ(s.normal.model, NormalModel::stripes_ab);
  EXPECT_EQ(s.text, kMinimal);
}

TEST(Scene, ShippedScenesParse) {
  for (const char* name : {"default_stripes.toml", "default.toml", "flange.toml", "worn_rail.toml", "worn_miniprof.toml"}) {
    Scene s = load_scene(std::filesystem::path(RAILTAB_SOURCE_DIR) / "tables" / name);
    EXPECT_FALSE(s.name.empty()) << name;
    EXPECT_GE(s.grids.y.size(), 20u) << name;
  }
}

TEST(Scene, AllSectionsParse) {
  std::string text = std::string(kMinimal) + R"(
equilibrium_roll = true
xi = {start = -0.002, stop = 0.002, count = 5}
eta = [0.0]
phi = [{start = -1.0, stop = 0.0, step = 0.5}, {start = 0.0, stop = 1.0, step = 1.0}]
[track]
gauge = 1.437
rail_inclination = "1:20"
[wheelset]
nominal_radius = 0.45
[material]
youngs_modulus = 200e9
[contact]
normal_model = "kik-piotrowski"
strips = 30
friction = 0.4
spin_per_strip = false
[wear]
lubrication_factor = 11
[geometry]
flange_angle = 0.4
)";
  Scene s = parse_scene(text, "t.toml");
  EXPECT_TRUE(s.equilibrium_roll);
  EXPECT_DOUBLE_EQ(s.track.gauge, 1.437);
  EXPECT_DOUBLE_EQ(s.track.rail_inclination, 0.05);
  EXPECT_DOUBLE_EQ(s.wheelset.nominal_radius, 0.45);
  EXPECT_DOUBLE_EQ(s.material.youngs_modulus, 200e9);
  EXPECT_EQ(s.normal.model, NormalModel::kik_piotrowski);
  EXPECT_EQ(s.normal.strips, 30);
  EXPECT_DOUBLE_EQ(s.tangential.friction, 0.4);
  EXPECT_FALSE(s.tangential.spin_per_strip);
  EXPECT_DOUBLE_EQ(s.wear.lubrication_factor, 11.0);
  EXPECT_DOUBLE_EQ(s.geometry.flange_angle, 0.4);
  EXPECT_EQ(s.grids.xi, (std::vector<double>{-0.002, -0.001, 0.0, 0.001, 0.002}));
  EXPECT_EQ(s.grids.phi, (std::vector<double>{-1.0, -0.5, 0.0, 1.0}));  // shared 0 merged
}

TEST(Scene, RangeWithStepEndsExactlyAtStop) {
  Scene s = parse_scene(R"(
[scene]
name = "t"
[profiles]
wheel = "s1002"
rail = "uic60"
[grid]
y = {start = -0.010, stop = 0.010, step = 0.0005}
load = [50e3, 78.5e3]
)", "t.toml");
  ASSERT_EQ(s.grids.y.size(), 41u);
  EXPECT_EQ(s.grids.y.front(), -0.010);
  EXPECT_EQ(s.grids.y.back(), 0.010);
  EXPECT_NEAR(s.grids.y[20], 0.0, 1e-15);
  EXPECT_DOUBLE_EQ(s.track.rail_inclination, 0.025);
}

TEST(Scene, InclinationAsNumber) {
  Scene s = parse_scene(std::string(kMinimal) + "[track]\nrail_inclination = 0.05\n", "t.toml");
  EXPECT_DOUBLE_EQ(s.track.rail_inclination, 0.05);
}

struct BadCase {
  const char* what;     // test label
  std::string text;     // scene text
  const char* needle1;  // substrings the message must contain
  const char* needle2;
};

// Each case's scene is refused with a message that starts with the file and holds both needles.
void expect_errors(const std::vector<BadCase>& cases) {
  for (const BadCase& c : cases) {
    std::string message = error_of(c.text);
    EXPECT_NE(message.find(c.needle1), std::string::npos) << c.what << ": " << message;
    EXPECT_NE(message.find(c.needle2), std::string::npos) << c.what << ": " << message;
    EXPECT_EQ(message.rfind("bad.toml:", 0), 0u) << c.what << ": " << message;
  }
}

TEST(Scene, ErrorsNameFileKeyAndLine) {
  const std::string m = kMinimal;  // grid is the last section: appended keys land in [grid]
  std::vector<BadCase> cases{
      {"typo in track", m + "[track]\ngague = 1.435\n", "track.gague", "unknown key"},
      {"unknown section", m + "[trak]\ngauge = 1.4\n", "trak", "unknown section"},
      {"unknown grid key", m + "roll_eq = true\n", "grid.roll_eq", "unknown key"},
      {"missing name", "[scene]\n[profiles]\nwheel='s1002'\nrail='uic60'\n[grid]\ny=[0.0]\nload=1.0\n",
       "scene.name", "missing required key"},
      {"missing grid.load", "[scene]\nname='t'\n[profiles]\nwheel='s1002'\nrail='uic60'\n[grid]\ny=[0.0]\n",
       "grid.load", "missing required key"},
      {"missing profiles", "[scene]\nname='t'\n[grid]\ny=[0.0]\nload=1.0\n", "profiles.wheel", "missing"},
      {"wrong type", m + "[track]\ngauge = \"wide\"\n", "track.gauge", "expected a number"},
      {"wrong type bool", m + "[contact]\nspin_per_strip = 1\n", "contact.spin_per_strip", "true or false"},
      {"empty grid", m + "xi = []\n", "grid.xi", "empty grid"},
      {"non-monotonic", m + "eta = [0.0, 0.002, 0.001]\n", "grid.eta", "strictly increasing"},
      {"duplicate", m + "eta = [0.0, 0.0]\n", "grid.eta", "strictly increasing"},
      {"nan", m + "phi = [0.0, nan]\n", "grid.phi", "not finite"},
      {"inf", m + "[track]\ngauge = inf\n", "track.gauge", "not finite"},
      {"range step and count", m + "xi = {start = 0.0, stop = 1.0, step = 0.5, count = 3}\n", "grid.xi",
       "exactly one of step or count"},
      {"range reversed", m + "xi = {start = 1.0, stop = 0.0, step = 0.5}\n", "grid.xi", "stop > start"},
      {"range bad key", m + "xi = {start = 0.0, stop = 1.0, stpe = 0.5}\n", "grid.xi.stpe", "unknown key"},
      {"range zero step", m + "xi = {start = 0.0, stop = 1.0, step = 0.0}\n", "grid.xi.step", "> 0"},
      {"bad model", m + "[contact]\nnormal_model = \"hurts\"\n", "contact.normal_model", "hurts"},
      {"bad inclination", m + "[track]\nrail_inclination = \"1/40\"\n", "track.rail_inclination", "1:40"},
      {"roll with equilibrium", m + "equilibrium_roll = true\nroll = [0.0, 0.001]\n", "grid.roll",
       "equilibrium_roll"},
      {"missing profile file", "[scene]\nname='t'\n[profiles]\nwheel='nope.prw'\nrail='uic60'\n", "profiles.wheel",
       "no such file"},
      {"negative load", m.substr(0, m.find("load")) + "load = [-1.0, 2.0]\n", "grid.load", "> 0"},
      {"syntax", m + "xi = [0.0,\n", "bad.toml", "TOML syntax error"},
      {"bad creep coordinates", m + "creep_coordinates = \"polar\"\n", "grid.creep_coordinates", "polar"},
      {"law spin without normalised", m + "creep_law_spin = 1.0\n", "grid.creep_law_spin", "normalised"},
      {"negative law spin", m + "creep_coordinates = \"normalised\"\ncreep_law_spin = -1.0\n", "grid.creep_law_spin",
       ">= 0"},
  };
  expect_errors(cases);
}

// Scene values are SI; a value typed in mm, kN or GPa is refused with the SI spelling of a typical
// value, instead of a table of off-rail or meaningless points (a gauge of 1435 m gave a table whose
// every point failed and which the lookup then refused to load).
TEST(Scene, ValuesInTheWrongUnitAreRefused) {
  const std::string m = kMinimal;  // grid is the last section
  const std::string head = m.substr(0, m.find("y = "));
  std::vector<BadCase> cases{
      {"gauge in mm", m + "[track]\ngauge = 1435\n", "track.gauge", "1.435"},
      {"measuring depth in mm", m + "[track]\ngauge_measuring_depth = 14\n", "track.gauge_measuring_depth", "0.014"},
      {"back to back in mm", m + "[wheelset]\nback_to_back = 1360\n", "wheelset.back_to_back", "1.360"},
      {"flange back in mm", m + "[wheelset]\nflange_back_position = -70\n", "wheelset.flange_back_position",
       "-0.070"},
      {"radius in mm", m + "[wheelset]\nnominal_radius = 460\n", "wheelset.nominal_radius", "0.460"},
      {"modulus in GPa", m + "[material]\nyoungs_modulus = 210\n", "material.youngs_modulus", "210e9"},
      {"hardness in GPa", m + "[wear]\nhardness = 2.75\n", "wear.hardness", "2.75e9"},
      {"load in kN", head + "y = [0.0]\nload = [60, 78.5, 100]\n", "grid.load", "78.5e3"},
      {"y in mm", head + "y = {start = -10, stop = 10, step = 0.5}\nload = 78500\n", "grid.y", "0.010"},
  };
  expect_errors(cases);
  // The bounds leave every real wheelset alone: metre gauge, a 1.676 m broad gauge, a 0.3 m radius.
  EXPECT_EQ(error_of(m + "[track]\ngauge = 1.0\n"), "");
  EXPECT_EQ(error_of(m + "[track]\ngauge = 1.676\n"), "");
  EXPECT_EQ(error_of(m + "[wheelset]\nnominal_radius = 0.3\n"), "");
  EXPECT_EQ(error_of(head + "y = [-0.05, 0.05]\nload = [5e3, 250e3]\n"), "");
}

// Young's modulus and hardness above 1e13 Pa (1e300 overflowed the table's float32 outputs after
// the whole sweep, and the error named the temporary file) are refused at the scene, naming the key
// and the range; the bounds themselves are accepted.
TEST(Scene, MaterialConstantsOutsideTheirRangeAreRefused) {
  const std::string m = kMinimal;
  expect_errors({
      {"modulus 1e300", m + "[material]\nyoungs_modulus = 1e300\n", "material.youngs_modulus", "in [1e6, 1e13] Pa"},
      {"modulus 2e13", m + "[material]\nyoungs_modulus = 2e13\n", "material.youngs_modulus", "got 20000000000000"},
      {"hardness 1e300", m + "[wear]\nhardness = 1e300\n", "wear.hardness", "in [1e6, 1e13] Pa"},
      {"hardness below", m + "[wear]\nhardness = 9e5\n", "wear.hardness", "in [1e6, 1e13] Pa"},
  });
  EXPECT_EQ(error_of(m + "[material]\nyoungs_modulus = 1e13\n[wear]\nhardness = 1e6\n"), "");
  EXPECT_EQ(error_of(m + "[material]\nyoungs_modulus = 1e6\n[wear]\nhardness = 1e13\n"), "");
}

// Grids the lookup could not interpolate (tests/data/hostile/scene_y_subnormal.toml: y nodes
// 5e-324 apart) and scene texts too large for the table's scene attribute are refused up front,
// naming the file and the key, before any table is computed.
TEST(Scene, GridNodesTooCloseAreRefused) {
  const std::filesystem::path file = std::filesystem::path(RAILTAB_SOURCE_DIR) / "tests/data/hostile/scene_y_subnormal.toml";
  const std::string m = test::error_message([&] { load_scene(file); });
  EXPECT_EQ(m.rfind(file.string() + ":", 0), 0u) << m;
  EXPECT_NE(m.find("grid.y"), std::string::npos) << m;
  EXPECT_NE(m.find("too close"), std::string::npos) << m;
  expect_errors({{"nodes 1e-13 apart", "[scene]\nname = \"t\"\n[profiles]\nwheel = \"s1002\"\nrail = \"uic60\"\n"
                                       "[grid]\ny = [0.001, 0.0010000000000001]\nload = 78500\n",
                  "grid.y", "too close"},
                 {"a range of subnormal width", "[scene]\nname = \"t\"\n[profiles]\nwheel = \"s1002\"\nrail = \"uic60\"\n"
                                                "[grid]\ny = 0.0\nload = {start = 6e4, stop = 6.00000000000001e4, count = 3}\n",
                  "grid.load", "too close"}});
  // Close but resolvable nodes still parse (1e-9 m apart).
  EXPECT_EQ(error_of("[scene]\nname = \"t\"\n[profiles]\nwheel = \"s1002\"\nrail = \"uic60\"\n"
                     "[grid]\ny = [0.001, 0.001000001]\nload = 78500\n"),
            "");
}

TEST(Scene, OversizedDescriptionOrSceneIsRefused) {
  const std::string head = "[scene]\nname = \"t\"\ndescription = \"";
  const std::string tail = "\"\n[profiles]\nwheel = \"s1002\"\nrail = \"uic60\"\n[grid]\ny = 0.0\nload = 78500\n";
  // The round's case: a 1.5 MB description (the table would carry it in its scene attribute,
  // which the lookup refuses above 1 MiB).
  std::string m = error_of(head + std::string(1'500'000, 'd') + tail);
  EXPECT_EQ(m.rfind("bad.toml", 0), 0u) << m.substr(0, 200);
  EXPECT_NE(m.find("above the limit"), std::string::npos) << m.substr(0, 200);
  m = error_of(head + std::string(200'000, 'd') + tail);
  EXPECT_NE(m.find("scene.description"), std::string::npos) << m.substr(0, 200);
  EXPECT_NE(m.find("above the limit of 100000"), std::string::npos) << m.substr(0, 200);
  // Comments count too: the whole text is stored.
  m = error_of(head + "d" + tail + "#" + std::string(1'100'000, 'c') + "\n");
  EXPECT_NE(m.find("the scene is 1100"), std::string::npos) << m.substr(0, 200);
  EXPECT_EQ(error_of(head + std::string(90'000, 'd') + tail), "");
}

TEST(Scene, ErrorGivesTheLineOfTheKey) {
  std::string text = std::string(kMinimal) + "[track]\n\ngague = 1.435\n";
  int line = 0;
  for (std::size_t i = 0; i < text.find("gague"); ++i) line += text[i] == '\n';
  EXPECT_NE(error_of(text).find("bad.toml:" + std::to_string(line + 1) + ":"), std::string::npos)
      << error_of(text);
}

TEST(Scene, ProfileFileResolvedRelativeToScene) {
  auto dir = std::filesystem::temp_directory_path() / "railtab_scene_test";
  std::filesystem::create_directories(dir / "profiles");
  std::ofstream(dir / "profiles" / "w.prw") << "0 0\n";
  std::ofstream(dir / "s.toml") << "[scene]\nname='t'\n[profiles]\nwheel='profiles/w.prw'\nrail='uic60'\n"
                                   "smoothing = 0.002\n[grid]\ny=[0.0]\nload=78500.0\n";
  Scene s = load_scene(dir / "s.toml");
  EXPECT_EQ(s.wheel.file, dir / "profiles" / "w.prw");
  EXPECT_DOUBLE_EQ(s.wheel.smoothing_length, 0.002);
  EXPECT_EQ(s.path, dir / "s.toml");
  std::filesystem::remove_all(dir);
}

TEST(Scene, MissingFileNamesIt) {
  try {
    load_scene("/nonexistent/x.toml");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/x.toml"), std::string::npos);
  }
}

TEST(Scene, MiniProfMirrorKeys) {
  std::string text = kMinimal;
  text.replace(text.find("rail = \"uic60\"\n"), 15, "rail = \"uic60\"\nwheel_mirror_y = \"yes\"\nrail_mirror_z = \"no\"\n");
  const Scene s = parse_scene(text, "mirror.toml");
  EXPECT_EQ(s.wheel.mirror_y, AxisMirror::yes);
  EXPECT_EQ(s.wheel.mirror_z, AxisMirror::automatic);
  EXPECT_EQ(s.rail.mirror_z, AxisMirror::no);
  std::string bad = kMinimal;
  bad.replace(bad.find("rail = \"uic60\"\n"), 15, "rail = \"uic60\"\nrail_mirror_y = \"maybe\"\n");
  const std::string m = error_of(bad);
  EXPECT_NE(m.find("profiles.rail_mirror_y"), std::string::npos) << m;
  EXPECT_NE(m.find("not one of auto, no, yes"), std::string::npos) << m;
}

// Measured worn profiles: wheels measured from the flange back get profiles.wheel_shift_y; the
// built-in s1002 has its origin on the running circle already, so a shift of it is refused.
TEST(Scene, WheelShiftYAndNearEqualKeys) {
  std::string text = kMinimal;
  text.replace(text.find("rail = \"uic60\"\n"), 15, "rail = \"uic60\"\nwheel_shift_y = 0.0\n");
  text += "[geometry]\nnear_equal_shift = 2e-4\nnear_equal_distance = 5e-4\n";
  const Scene s = parse_scene(text, "shift.toml");
  EXPECT_EQ(s.wheel.lateral_shift, 0.0);
  EXPECT_EQ(s.geometry.near_equal_shift, 2e-4);
  EXPECT_EQ(s.geometry.near_equal_distance, 5e-4);
  std::string bad = kMinimal;
  bad.replace(bad.find("rail = \"uic60\"\n"), 15, "rail = \"uic60\"\nwheel_shift_y = -0.07\n");
  const std::string m = error_of(bad);
  EXPECT_NE(m.find("profiles.wheel_shift_y"), std::string::npos) << m;
  EXPECT_NE(m.find("wheel profile files only"), std::string::npos) << m;
}

// Reliability (docs/reliability.md): a device or FIFO given as a scene used to be read without
// limit (/dev/zero) or to block forever (a FIFO without a writer).
TEST(Scene, DeviceOrFifoIsRefusedWithoutReading) {
  for (const char* dev : {"/dev/zero", "/dev/urandom"}) {
    if (!std::filesystem::exists(dev)) continue;
    const std::string m = test::error_message([&] { load_scene(dev); });
    EXPECT_NE(m.find("not a regular file"), std::string::npos) << m;
  }
  const std::filesystem::path fifo =
      std::filesystem::temp_directory_path() / ("railtab_scene_fifo_" + std::to_string(::getpid()));
  std::filesystem::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string m = test::error_message([&] { load_scene(fifo); });
  std::filesystem::remove(fifo);
  EXPECT_NE(m.find("not a regular file"), std::string::npos) << m;
}

}  // namespace
}  // namespace railtab
