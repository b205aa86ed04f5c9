// SPDX-License-Identifier: Apache-2.0
// Parametric profiles in the contact geometry: a worn rail whose gauge face overhangs
// (site_b_hr.prr of CONTACT's testbank, as shipped) and an undercut added below a UIC60 head.
// The part of a rail under an overhang cannot be reached by a wheel coming from above, so it must
// change nothing; the rest must behave as for any rail: finite contacts, no overlap at rigid
// contact anywhere along the band.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "geometry/contact_geometry.hpp"
#include "profile/curves/parametric_profile.hpp"
#include "profile/formats/profile_io.hpp"
#include "profile/standard/s1002.hpp"
#include "profile/test_profile_files.hpp"

namespace railtab {
namespace {

std::filesystem::path data_file(const std::string& name) {
  return std::filesystem::path(RAILTAB_SOURCE_DIR) / "tests" / "data" / "profiles" / name;
}

// UIC60 (its 1:20 gauge face continued down to 32 mm below the top) as a parametric curve, with
// or without an undercut below that: the surface turns back under the head, 33-36 mm down.
ProfilePtr uic60_curve(bool with_undercut) {
  std::vector<test::Point> pts;
  if (with_undercut) pts = {{-35.0, -36.0}, {-36.0, -35.5}, {-36.7, -34.5}, {-37.0, -33.2}};
  for (double depth = 32.0; depth > 24.5; depth -= 0.5) pts.push_back({-36.5 - (depth - 24.3) / 20.0, -depth});
  for (const test::Point& p : test::uic60_points(0.25)) pts.push_back(p);
  std::vector<double> y, z;
  for (const test::Point& p : pts) {
    y.push_back(p.y * 1e-3);
    z.push_back(p.z * 1e-3);
  }
  return std::make_shared<const ParametricProfile>(with_undercut ? "undercut" : "plain", ProfileKind::rail, y, z);
}

TEST(Overhang, UndercutBelowTheHeadChangesNothing) {
  const ProfilePtr wheel = make_s1002_profile();
  const ProfilePtr plain = uic60_curve(false);
  const ProfilePtr cut = uic60_curve(true);
  ASSERT_LT(cut->u_min(), plain->u_min());  // the undercut reaches further towards the track
  const ContactGeometrySolver a(wheel, plain, wheel, plain, TrackGeometry{}, WheelsetGeometry{});
  const ContactGeometrySolver b(wheel, cut, wheel, cut, TrackGeometry{}, WheelsetGeometry{});
  double d_rail = 0.0, d_wheel = 0.0, d_angle = 0.0, d_drop = 0.0;
  for (double y = -6e-3; y <= 8e-3 + 1e-12; y += 0.5e-3) {
    const WheelContactGeometry ga = a.solve_wheel(Side::left, WheelsetState{y, 0.0});
    const WheelContactGeometry gb = b.solve_wheel(Side::left, WheelsetState{y, 0.0});
    ASSERT_EQ(ga.points.size(), gb.points.size()) << "y = " << y;
    for (std::size_t k = 0; k < ga.points.size(); ++k) {
      d_rail = std::max(d_rail, std::abs(ga.points[k].rail_u - gb.points[k].rail_u));
      d_wheel = std::max(d_wheel, std::abs(ga.points[k].wheel_u - gb.points[k].wheel_u));
      d_angle = std::max(d_angle, std::abs(ga.points[k].contact_angle - gb.points[k].contact_angle));
    }
    d_drop = std::max(d_drop, std::abs(ga.wheel_drop - gb.wheel_drop));
  }
  std::cout << "undercut vs none: max |d rail_u| " << d_rail << " m, |d wheel_u| " << d_wheel
            << " m, |d angle| " << d_angle << " rad, |d drop| " << d_drop << " m\n";
  // The splines differ only through their end conditions, far from every contact: round-off.
  EXPECT_LT(d_rail, 1e-9);
  EXPECT_LT(d_wheel, 1e-9);
  EXPECT_LT(d_angle, 1e-9);
  EXPECT_LT(d_drop, 1e-11);
}

TEST(Overhang, WornRailSiteBAsShipped) {
  const ProfilePtr rail = read_profile(data_file("site_b_hr.prr"), ProfileKind::rail);
  ASSERT_TRUE(rail->parametric());
  const ProfilePtr wheel = make_s1002_profile();
  const ContactGeometrySolver solver(wheel, rail, wheel, rail, TrackGeometry{}, WheelsetGeometry{});
  int flange = 0;
  for (Side side : {Side::left, Side::right}) {
    for (double y = -8e-3; y <= 9e-3 + 1e-12; y += 0.25e-3) {
      const WheelContactGeometry g = solver.solve_wheel(side, WheelsetState{y, 0.0});
      ASSERT_FALSE(g.points.empty());
      for (const ContactPoint& p : g.points) {
        EXPECT_TRUE(std::isfinite(p.rail_u) && std::isfinite(p.contact_angle) && p.curvature_a > 0.0)
            << to_string(side) << " y = " << y;
        EXPECT_GE(p.rail_u, rail->u_min());
        EXPECT_LE(p.rail_u, rail->u_max());
        if (p.status & status::kFlangeContact) ++flange;
      }
      // Rigid contact: nowhere along the band may the wheel be inside the rail.
      for (const BandSample& b : g.band) EXPECT_GE(b.gap, -1e-9) << to_string(side) << " y = " << y << " s = " << b.s;
    }
  }
  EXPECT_GT(flange, 0);  // the sweep reaches the worn gauge corner
}

}  // namespace
}  // namespace railtab
