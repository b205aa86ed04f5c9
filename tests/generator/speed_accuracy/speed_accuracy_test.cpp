// SPDX-License-Identifier: Apache-2.0
// railtab chart's measurement (generator/speed_accuracy/speed_accuracy*.*) on a tiny state set: CSV columns,
// finite numbers, and a non-dominated Pareto front. Seconds, not minutes.
#include "speed_accuracy/speed_accuracy.hpp"
#include "generator/test_tables.hpp"
#include "table/table_io.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace railtab {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> f;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) f.push_back(cell);
  return f;
}

// Rows of a CSV with '#' comment lines: column name -> cell, per row.
std::vector<std::map<std::string, std::string>> read_csv(const fs::path& path, std::vector<std::string>& header) {
  std::ifstream in(path);
  std::string line;
  std::vector<std::map<std::string, std::string>> rows;
  header.clear();
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header.empty()) {
      header = split(line);
      continue;
    }
    const std::vector<std::string> f = split(line);
    EXPECT_EQ(f.size(), header.size()) << line;
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < f.size() && i < header.size(); ++i) row[header[i]] = f[i];
    rows.push_back(row);
  }
  return rows;
}

SpeedAccuracyOptions tiny(const fs::path& work) {
  SpeedAccuracyOptions o;
  o.dy_mm = {-2.0, 8.0};  // one tread, one flange state
  o.creep_sets = {"a_none", "c_lat0.001", "e_combined"};
  o.models = {{NormalModel::hertz, 0, 10}, {NormalModel::stripes_ab, 10, 10}, {NormalModel::kik_piotrowski, 10, 10}};
  o.tables = {{2e-3, false}};
  o.cubic = false;
  o.repeats = 1;
  o.lookup_passes = 3;
  o.table_threads = 1;
  o.work_dir = work;
  o.fallback_reference = {NormalModel::stripes_ab, 25, 20};
  return o;
}

void check_result(const SpeedAccuracyResult& r, const fs::path& dir) {
  ASSERT_EQ(r.rows.size(), 4u);  // 3 models + 1 table
  const fs::path csv = dir / "speed_accuracy.csv";
  write_speed_accuracy_csv(r, csv);
  write_states_csv(r, dir / "states.csv");
  write_table_memory_csv(r, dir / "memory.csv");
  std::vector<std::string> header;
  const auto rows = read_csv(csv, header);
  ASSERT_EQ(rows.size(), r.rows.size());
  for (const char* c : {"label", "kind", "family", "time_us", "time_tread_us", "time_flange_us", "err_force",
                        "err_force_tread", "err_force_flange", "err_area", "table_file_bytes", "table_memory_bytes",
                        "pareto_all", "pareto_tread", "pareto_flange", "reference"}) {
    EXPECT_NE(std::find(header.begin(), header.end(), c), header.end()) << "missing column " << c;
  }
  for (const auto& row : rows) {
    for (const char* c : {"time_us", "time_tread_us", "time_flange_us", "err_force", "err_force_tread",
                          "err_force_flange"}) {
      const double v = std::stod(row.at(c));
      EXPECT_TRUE(std::isfinite(v) && v >= 0.0) << row.at("label") << " " << c << " = " << row.at(c);
    }
    EXPECT_GT(std::stod(row.at("time_us")), 0.0);
    if (row.at("kind") == "lookup") {
      EXPECT_GT(std::stoull(row.at("table_file_bytes")), 0u);
      EXPECT_GT(std::stoull(row.at("table_memory_bytes")), 0u);
    }
  }
  // Pareto fronts: non-empty and non-dominated; every point off the front is dominated.
  struct Panel {
    const char* t;
    const char* e;
    const char* p;
  };
  for (const Panel& p : {Panel{"time_us", "err_force", "pareto_all"}, Panel{"time_tread_us", "err_force_tread", "pareto_tread"},
                         Panel{"time_flange_us", "err_force_flange", "pareto_flange"}}) {
    int on_front = 0;
    for (const auto& a : rows) {
      const double ta = std::stod(a.at(p.t)), ea = std::stod(a.at(p.e));
      bool dominated = false;
      for (const auto& b : rows) {
        const double tb = std::stod(b.at(p.t)), eb = std::stod(b.at(p.e));
        if (tb <= ta && eb <= ea && (tb < ta || eb < ea)) dominated = true;
      }
      const bool front = a.at(p.p) == "1";
      on_front += front;
      EXPECT_EQ(front, !dominated) << p.p << ": " << a.at("label");
    }
    EXPECT_GE(on_front, 1) << p.p;
  }
  // The per-state file has one line per (row, state).
  std::vector<std::string> sh;
  EXPECT_EQ(read_csv(dir / "states.csv", sh).size(), r.rows.size() * r.states.size());
  std::vector<std::string> mh;
  EXPECT_EQ(read_csv(dir / "memory.csv", mh).size(), 1u);
}

TEST(SpeedAccuracy, ParetoFrontIsNonDominated) {
  const std::vector<double> t{1, 2, 3, 4, 2, std::nan("")};
  const std::vector<double> e{5, 3, 3, 1, 6, 0.1};
  const std::vector<bool> f = pareto_front(t, e);
  EXPECT_EQ(f, (std::vector<bool>{true, true, false, true, false, false}));
}

TEST(SpeedAccuracy, ContactReferenceOnlyForItsOwnPair) {
  // A worn scene must not be measured against CONTACT's S1002/UIC60 runs.
  const fs::path tables = fs::path(RAILTAB_SOURCE_DIR) / "tables";
  EXPECT_TRUE(contact_reference_applies(load_scene(tables / "default_stripes.toml")));
  EXPECT_FALSE(contact_reference_applies(load_scene(tables / "worn_rail.toml")));
  EXPECT_FALSE(contact_reference_applies(load_scene(tables / "worn_miniprof.toml")));
  Scene canted = load_scene(tables / "default_stripes.toml");
  canted.track.rail_inclination = 1.0 / 20.0;
  EXPECT_FALSE(contact_reference_applies(canted));
}

TEST(SpeedAccuracy, TinyRunAgainstContact) {
  const fs::path ref = fs::path(RAILTAB_SHARED_DIR) / "reference" / "blockC_sweep_integer_dy.csv";
  if (!fs::exists(ref)) GTEST_SKIP() << ref.string() << " absent";
  const testing::TempDir tmp("speed_accuracy_contact");  // per process: parallel suites do not share it
  const fs::path& dir = tmp.path();
  const Scene scene = load_scene(fs::path(RAILTAB_SOURCE_DIR) / "tables" / "default_stripes.toml");
  SpeedAccuracyOptions o = tiny(dir / "tables");
  o.reference_csv = ref;
  const SpeedAccuracyResult r = measure_speed_accuracy(scene, o);
  EXPECT_TRUE(r.contact_reference);
  EXPECT_EQ(r.states.size(), 6u);
  for (const SaState& s : r.states) {
    if (s.creep_set == "c_lat0.001") {
      EXPECT_GT(std::abs(s.ref_fy), 1000.0);  // CONTACT lateral force
    }
  }
  check_result(r, dir);
  EXPECT_FALSE(fs::exists(dir / "tables" / "speed_accuracy_y2mm.h5"));  // temporary table removed
}

TEST(SpeedAccuracy, TinyRunWithoutContactUsesFineStripes) {
  const testing::TempDir tmp("speed_accuracy_fallback");  // per process: parallel suites do not share it
  const fs::path& dir = tmp.path();
  const Scene scene = load_scene(fs::path(RAILTAB_SOURCE_DIR) / "tables" / "default_stripes.toml");
  SpeedAccuracyOptions o = tiny(dir / "tables");
  o.reference_csv = dir / "no-such-reference.csv";
  const SpeedAccuracyResult r = measure_speed_accuracy(scene, o);
  EXPECT_FALSE(r.contact_reference);
  EXPECT_NE(r.reference.find("STRIPES"), std::string::npos);
  check_result(r, dir);
}

// Without CONTACT data the default reference is the exact half-space model, and the result says so.
TEST(SpeedAccuracy, TinyRunWithoutContactUsesTheExactModel) {
  const testing::TempDir tmp("speed_accuracy_exact");  // per process: parallel suites do not share it
  const fs::path& dir = tmp.path();
  const Scene scene = load_scene(fs::path(RAILTAB_SOURCE_DIR) / "tables" / "default_stripes.toml");
  SpeedAccuracyOptions o = tiny(dir / "tables");
  o.fallback_reference = SpeedAccuracyOptions{}.fallback_reference;
  ASSERT_EQ(o.fallback_reference.model, NormalModel::halfspace);
  o.reference_csv = dir / "no-such-reference.csv";
  const SpeedAccuracyResult r = measure_speed_accuracy(scene, o);
  EXPECT_FALSE(r.contact_reference);
  EXPECT_TRUE(r.exact_reference);
  EXPECT_NE(r.reference.find("exact half-space"), std::string::npos) << r.reference;
  for (const SaState& s : r.states) {
    EXPECT_GT(s.ref_area, 20e-6) << s.creep_set;  // a loaded contact in every state
    if (s.creep_set == "c_lat0.001") {
      EXPECT_GT(std::abs(s.ref_fy), 1000.0);  // the exact lateral creep force
      EXPECT_LE(std::abs(s.ref_fy), 0.3 * 120e3);
    }
  }
  check_result(r, dir);
}

// The chart's tables are the kind `railtab generate` makes of the scene: its creep coordinates
// (normalised nodes with the scene's knees, its whole creepage ranges) and located contact jumps,
// so the chart measures the product, not a plainer table.
TEST(SpeedAccuracy, TablesAreTheOnesGenerateMakes) {
  const testing::TempDir tmp("speed_accuracy_product");  // per process: parallel suites do not share it
  const fs::path& dir = tmp.path();
  const Scene scene = load_scene(fs::path(RAILTAB_SOURCE_DIR) / "tables" / "default_stripes.toml");
  ASSERT_TRUE(scene.creep_normalised);
  SpeedAccuracyOptions o = tiny(dir / "tables");
  o.models = {{NormalModel::hertz, 0, 10}};
  o.reference_csv = dir / "no-such-reference.csv";
  o.keep_tables = true;
  const SpeedAccuracyResult r = measure_speed_accuracy(scene, o);
  ASSERT_EQ(r.rows.size(), 2u);
  const Table t = read_table(dir / "tables" / "speed_accuracy_y2mm.h5");
  const std::string* creep_map = t.attribute("creep_map");
  ASSERT_NE(creep_map, nullptr) << "the chart's table lost the scene's normalised creep coordinates";
  // The scene's whole ranges and knees (default_stripes.toml: xi -4e-3..4e-3, eta knee 3, phi knee 4).
  EXPECT_NE(creep_map->find("\"xi_min\":-0.004"), std::string::npos) << *creep_map;
  EXPECT_NE(creep_map->find("\"eta_knee\":3.0"), std::string::npos) << *creep_map;
  EXPECT_NE(creep_map->find("\"phi_knee\":4.0"), std::string::npos) << *creep_map;
  // The right wheel's flange onset lies between the tiny run's y nodes (-10..4 mm every 2 mm).
  EXPECT_NE(t.group(kJumpGroup), nullptr) << "the chart's table has no located contact jumps";
}

// A scene of the exact model makes every chart table an exact one (15-30 ms CPU per point): its
// default tables stay within a few minutes of CPU (tables/default.toml: one y 0.5 mm
// table over block C's 16 mm, about 11,000 points), where the fast scenes' seven tables (fine
// creepage grids of 891 creepages per y, y steps down to 0.25 mm) would be about 125,000 exact
// points, hours.
TEST(SpeedAccuracy, ExactSceneTablesAreCapped) {
  const Scene scene = load_scene(fs::path(RAILTAB_SOURCE_DIR) / "tables" / "default.toml");
  ASSERT_EQ(scene.normal.model, NormalModel::halfspace);
  const double span = 16e-3;  // block C: dy -6 to 10 mm
  auto points = [&](const std::vector<SaTableSetting>& settings) {
    double n = 0.0;
    for (const SaTableSetting& ts : settings) {
      const double creepages = ts.fine_creep ? 11.0 * 9.0 * 9.0
                                             : static_cast<double>(scene.grids.xi.size() * scene.grids.eta.size() *
                                                                   scene.grids.phi.size());
      n += (span / ts.y_step + 2.0) * creepages;
    }
    return n;
  };
  const double exact = points(default_table_settings(true));
  std::printf("exact scene: %.0f chart table points (fast scenes' settings: %.0f)\n", exact,
              points(default_table_settings(false)));
  EXPECT_GT(exact, 0.0);
  EXPECT_LT(exact, 15000.0);
  for (const SaTableSetting& ts : default_table_settings(true)) EXPECT_FALSE(ts.fine_creep) << ts.label();
}

}  // namespace
}  // namespace railtab
