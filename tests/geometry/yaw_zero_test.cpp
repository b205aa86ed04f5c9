// SPDX-License-Identifier: Apache-2.0
// Yaw = 0 is the yaw-free geometry to the last bit: S1002 / UIC60 1:40 at several states (tread,
// flange, two-point, rolled), every contact point's outputs and a digest of the band, compared as
// exact doubles (hex floats) with tests/data/geometry/yaw_free_outputs.txt, which the geometry
// wrote before it knew yaw. RAILTAB_RECORD_YAW_FREE=1 rewrites that file (only when the yaw-free
// geometry is meant to change).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "geometry/contact_geometry.hpp"
#include "profile/standard/s1002.hpp"
#include "profile/standard/uic60.hpp"

namespace railtab::yaw_zero_test {
namespace {

const char* kGoldenPath = RAILTAB_SOURCE_DIR "/tests/data/geometry/yaw_free_outputs.txt";

std::string hex(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%a", v);
  return buf;
}

// Every output of one wheel, one value per line: "name value".
std::vector<std::string> outputs(const WheelContactGeometry& g, const std::string& tag) {
  std::vector<std::string> lines;
  auto put = [&](const std::string& name, double v) { lines.push_back(tag + " " + name + " " + hex(v)); };
  put("wheel_drop", g.wheel_drop);
  put("wheel_roll", g.wheel_roll);
  put("status", static_cast<double>(g.status));
  put("n_points", static_cast<double>(g.points.size()));
  for (size_t k = 0; k < g.points.size(); ++k) {
    const ContactPoint& p = g.points[k];
    char prefix[32];
    std::snprintf(prefix, sizeof prefix, "p%zu.", k);
    const std::string pk = prefix;
    put(pk + "wheel_u", p.wheel_u);
    put(pk + "rail_u", p.rail_u);
    put(pk + "y_track", p.y_track);
    put(pk + "z_track", p.z_track);
    put(pk + "contact_angle", p.contact_angle);
    put(pk + "rolling_radius", p.rolling_radius);
    put(pk + "separation", p.separation);
    put(pk + "curvature_a", p.curvature_a);
    put(pk + "curvature_b", p.curvature_b);
    put(pk + "band_s", p.band_s);
    put(pk + "status", static_cast<double>(p.status));
  }
  put("band_size", static_cast<double>(g.band.size()));
  double s = 0, gap = 0, q = 0, z = 0, w = 0, r = 0, kw = 0, kr = 0;
  for (const BandSample& b : g.band) {  // ordered sums: deterministic
    s += b.s; gap += b.gap; q += b.q; z += b.z; w += b.wheel_u; r += b.rolling_radius;
    kw += b.curvature_wheel; kr += b.curvature_rail;
  }
  put("band.sum_s", s);
  put("band.sum_gap", gap);
  put("band.sum_q", q);
  put("band.sum_z", z);
  put("band.sum_wheel_u", w);
  put("band.sum_radius", r);
  put("band.sum_curvature_wheel", kw);
  put("band.sum_curvature_rail", kr);
  return lines;
}

std::vector<std::string> all_outputs() {
  ProfilePtr w = make_s1002_profile();
  ProfilePtr r = make_uic60_profile();
  const ContactGeometrySolver solver(w, r, w, r, TrackGeometry{}, WheelsetGeometry{});
  std::vector<std::string> lines;
  for (const double y : {-0.008, -0.003, 0.0, 0.0025, 0.005, 0.0065, 0.009})
    for (const double roll : {0.0, -0.004}) {
      WheelsetState state;
      state.y = y;
      state.roll = roll;
      for (const Side side : {Side::left, Side::right}) {
        const std::string tag = std::string(to_string(side)) + " y=" + hex(y) + " roll=" + hex(roll);
        const auto part = outputs(solver.solve_wheel(side, state), tag);
        lines.insert(lines.end(), part.begin(), part.end());
      }
    }
  return lines;
}

TEST(YawZero, GeometryIsTheYawFreeGeometryBitForBit) {
  const std::vector<std::string> now = all_outputs();
  if (std::getenv("RAILTAB_RECORD_YAW_FREE") != nullptr) {
    std::ofstream out(kGoldenPath);
    for (const std::string& l : now) out << l << "\n";
    GTEST_SKIP() << "recorded " << now.size() << " values to " << kGoldenPath;
  }
  std::ifstream in(kGoldenPath);
  ASSERT_TRUE(in) << "missing " << kGoldenPath;
  std::vector<std::string> golden;
  for (std::string l; std::getline(in, l);) golden.push_back(l);
  ASSERT_EQ(now.size(), golden.size());
  int differ = 0;
  for (size_t i = 0; i < now.size(); ++i)
    if (now[i] != golden[i] && ++differ <= 10) ADD_FAILURE() << "now: " << now[i] << "\nwas: " << golden[i];
  EXPECT_EQ(differ, 0);
}

}  // namespace
}  // namespace railtab::yaw_zero_test
