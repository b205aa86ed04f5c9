// SPDX-License-Identifier: Apache-2.0
// Creepages of the yawed wheelset's rigid motion (rigid_creepage) and the yawed half-space patch:
// the yaw-free closed forms, the lateral creepage of yaw on tread and flange, the mirror between
// the wheels, and the limit yaw -> 0 of the exact model.
#include "halfspace/wheelset_kinematics.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/contact_geometry.hpp"
#include "profile/standard/s1002.hpp"
#include "profile/standard/uic60.hpp"

namespace railtab::wheelset_kinematics_test {
namespace {

ContactGeometrySolver solver() {
  ProfilePtr w = make_s1002_profile();
  ProfilePtr r = make_uic60_profile();
  return ContactGeometrySolver(w, r, w, r, TrackGeometry{}, WheelsetGeometry{});
}

halfspace::HalfspacePatch reference(const WheelContactGeometry& g) {
  halfspace::Workspace ws;
  const auto r = halfspace::solve_halfspace_for_load(g, 10000.0, Material{}, halfspace::HalfspaceOptions{}, ws);
  EXPECT_FALSE(r.patches.empty());
  return r.patches.front();
}

TEST(WheelsetKinematics, YawFreeClosedForms) {
  const ContactGeometrySolver s = solver();
  const WheelContactGeometry g = s.solve_wheel(Side::left, {0.002, 0.001});
  const halfspace::HalfspacePatch p = reference(g);
  halfspace::WheelsetMotion m;
  m.speed = 20.0;
  m.spin = 20.0 / 0.4601;
  m.lateral_velocity = 0.05;
  const Creepage c = halfspace::rigid_creepage(g, p, m);
  const double gt = p.contact_angle;
  EXPECT_NEAR(c.xi, 1.0 - m.spin * p.rolling_radius / m.speed, 1e-12);
  EXPECT_NEAR(c.eta, m.lateral_velocity * std::cos(gt) / m.speed, 1e-12);
  EXPECT_NEAR(c.phi, -m.spin * std::sin(gt - 0.001) / m.speed, 1e-12);  // axle rolled with the wheelset
}

// Yaw adds a lateral creepage of about -yaw / cos(g) (the wheel runs at the yaw angle to the
// rail, and on a steep contact the slip along x is tipped into the contact plane), the same on
// both wheels; the slip stays in the contact plane.
TEST(WheelsetKinematics, YawAddsLateralCreepage) {
  const ContactGeometrySolver s = solver();
  for (const double y : {0.0, 0.009}) {  // tread; left flange at 9 mm
    for (const Side side : {Side::left, Side::right}) {
      const double yaw = 0.01;
      const WheelContactGeometry g = s.solve_wheel(side, {y, 0.0, yaw});
      const halfspace::HalfspacePatch p = reference(g);
      halfspace::WheelsetMotion m;
      m.speed = 2.0;
      m.spin = 2.0 / p.rolling_radius;  // free rolling at the reference
      const Creepage c = halfspace::rigid_creepage(g, p, m);
      const double expected = -yaw / std::cos(p.contact_angle);
      EXPECT_NEAR(c.eta, expected, 0.02 * std::abs(expected)) << "y " << y << " " << to_string(side);
      // Rolling at Omega r along its own heading, the wheel moves forward at Omega r cos(yaw)
      // cos(tau) at the contact (tau: its angle on the wheel circle, r sin(tau) = x_wheel).
      const double s_tau = p.x_wheel / p.rolling_radius;
      EXPECT_NEAR(c.xi, 1.0 - std::cos(outward_sign(side) * yaw) * std::sqrt(1.0 - s_tau * s_tau), 1e-12);
    }
  }
}

TEST(WheelsetKinematics, MirrorBetweenTheWheels) {
  const ContactGeometrySolver s = solver();
  const WheelsetState a{0.004, 0.002, 0.015}, b{-0.004, -0.002, -0.015};
  const WheelContactGeometry gl = s.solve_wheel(Side::left, a), gr = s.solve_wheel(Side::right, b);
  const halfspace::HalfspacePatch pl = reference(gl), pr = reference(gr);
  halfspace::WheelsetMotion m;
  m.speed = 10.0;
  m.spin = 10.0 / 0.46;
  const Creepage cl = halfspace::rigid_creepage(gl, pl, m), cr = halfspace::rigid_creepage(gr, pr, m);
  EXPECT_NEAR(cl.xi, cr.xi, 1e-12);
  EXPECT_NEAR(cl.eta, -cr.eta, 1e-12);  // s points to +y on both wheels
  EXPECT_NEAR(cl.phi, -cr.phi, 1e-12);
  EXPECT_EQ(pl.x_track, pr.x_track);
  EXPECT_NEAR(pl.normal.normal_force, pr.normal.normal_force, 1e-9 * pl.normal.normal_force);
}

// The yawed patch (sheared grid) meets the yaw-free one as yaw -> 0: force and area. Not the
// last digit: away from the contact point the yawed strips take A from the wheel's own slope,
// the yaw-free ones from the rail's angle (p_max differs by 0.04 % in flange contact).
TEST(WheelsetKinematics, YawedPatchTendsToTheYawFreeOne) {
  const ContactGeometrySolver s = solver();
  for (const double y : {0.0, 0.009}) {
    const halfspace::HalfspacePatch p0 = reference(s.solve_wheel(Side::left, {y, 0.0, 0.0}));
    const halfspace::HalfspacePatch p1 = reference(s.solve_wheel(Side::left, {y, 0.0, 1e-9}));
    EXPECT_NEAR(p1.normal.normal_force, p0.normal.normal_force, 1e-6 * p0.normal.normal_force);
    EXPECT_NEAR(p1.normal.area, p0.normal.area, 1e-6 * p0.normal.area) << "y " << y;
    EXPECT_NEAR(p1.x_track, 0.0, 1e-8);
  }
}

TEST(WheelsetKinematics, BadMotionIsRefused) {
  const ContactGeometrySolver s = solver();
  const WheelContactGeometry g = s.solve_wheel(Side::left, {0.0, 0.0});
  const halfspace::HalfspacePatch p = reference(g);
  halfspace::WheelsetMotion m;
  m.speed = 0.0;
  EXPECT_THROW(halfspace::rigid_creepage(g, p, m), Error);
  m.speed = 1.0;
  m.spin = std::nan("");
  EXPECT_THROW(halfspace::rigid_creepage(g, p, m), Error);
}

}  // namespace
}  // namespace railtab::wheelset_kinematics_test
