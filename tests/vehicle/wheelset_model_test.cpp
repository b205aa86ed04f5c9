// SPDX-License-Identifier: Apache-2.0
// The wheelset equations of motion against closed-form results of the linear contact model
// (docs/vehicle-model.md, "Checks").
#include "vehicle/wheelset_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "core/check.hpp"
#include "core/status.hpp"
#include "vehicle/linear_contact_helper.hpp"

namespace railtab::vehicle {
namespace {

using testing::LinearContact;

TrackLayout tangent(double length) { return TrackLayout({{length, 0, 0, 0, 0}}, {}); }

// A circular curve from s = 0 with the cant (height on 1.5 m) given.
TrackLayout curve(double radius, double cant, double length = 2000.0) {
  return TrackLayout({{length, 1.0 / radius, 1.0 / radius, cant, cant}}, {});
}

// No springs, no carried mass: the wheelset is held by creep forces alone.
WheelsetParameters free_wheelset() {
  WheelsetParameters p;
  p.carried_mass = 0.0;
  p.primary_lateral_stiffness = 0.0;
  p.primary_longitudinal_stiffness = 0.0;
  p.primary_lateral_damping = 0.0;
  return p;
}

TEST(WheelsetSimulation, TangentTrackCentredStartStaysCentredWithoutCreepForces) {
  const TrackLayout track = tangent(400.0);
  LinearContact contact;
  WheelsetSimulation sim(WheelsetParameters{}, track, contact, 33.0, 1e-3);
  double largest_force = 0.0;
  for (int i = 0; i < 10000; ++i) {
    sim.step();
    for (const auto& wheel : sim.snapshot().forces) {
      largest_force = std::max({largest_force, std::abs(wheel[0].fx), std::abs(wheel[0].fy)});
    }
  }
  EXPECT_NEAR(sim.time(), 10.0, 1e-12);
  EXPECT_LT(std::abs(sim.state().y), 1e-12);
  EXPECT_LT(std::abs(sim.state().yaw), 1e-12);
  EXPECT_LT(largest_force, 1e-6);  // N; round-off of xi = 1 - Omega r / V
  EXPECT_EQ(sim.snapshot().status & status::kNotConverged, 0u);
}

// Zero crossings of y(s) by linear interpolation.
std::vector<double> zero_crossings(const std::vector<double>& s, const std::vector<double>& y) {
  std::vector<double> crossings;
  for (std::size_t i = 1; i < y.size(); ++i) {
    if ((y[i - 1] < 0.0) != (y[i] < 0.0)) {
      crossings.push_back(s[i - 1] + (s[i] - s[i - 1]) * y[i - 1] / (y[i - 1] - y[i]));
    }
  }
  return crossings;
}

TEST(WheelsetSimulation, FreeWheelsetOscillatesWithKlingelsWavelength) {
  const TrackLayout track = tangent(200.0);
  LinearContact contact;
  const WheelsetParameters p = free_wheelset();
  WheelsetState start;
  start.y = 1e-3;
  WheelsetSimulation sim(p, track, contact, 10.0, 1e-3, start);
  std::vector<double> s{0.0}, y{start.y};
  while (sim.distance() < 60.0) {
    sim.step();
    s.push_back(sim.distance());
    y.push_back(sim.state().y);
  }
  const std::vector<double> crossings = zero_crossings(s, y);
  ASSERT_GE(crossings.size(), 6u);
  const double measured =
      2.0 * (crossings.back() - crossings.front()) / double(crossings.size() - 1);
  const double q0 = p.running_circle_q;
  const double klingel = 2.0 * std::numbers::pi * std::sqrt(contact.r0 * q0 / contact.conicity);
  std::printf("  Klingel: wavelength %.4f m, 2 pi sqrt(r0 q0 / lambda) = %.4f m (%+.2f %%)\n",
              measured, klingel, 100.0 * (measured / klingel - 1.0));
  EXPECT_NEAR(measured / klingel, 1.0, 0.03) << "measured " << measured << " m, Klingel "
                                             << klingel << " m";
}

TEST(WheelsetSimulation, FreeWheelsetInBalancedCurveSettlesAtPureRolling) {
  const double v = 10.0, radius = 500.0, g = 9.81;
  // Cant that balances V^2 / R exactly: a_u = 0.
  const double cant = 1.5 * v * v / radius / g;
  const TrackLayout track = curve(radius, cant);
  LinearContact contact;
  WheelsetParameters p = free_wheelset();
  p.gravity = g;
  // Laterally free, but not left to hunt for ever: a wheelset without any suspension never
  // settles (its kinematic oscillation is not damped, docs/vehicle-model.md). A yaw spring to a
  // frame centred on the wheelset (a = 0, so psi_b = y_b = 0) and a lateral damper take the energy
  // out and add no static force or moment at the pure-rolling point (psi = 0, y_dot = 0).
  p.primary_longitudinal_stiffness = 5.0e6;
  p.semi_wheelbase = 0.0;
  p.primary_lateral_damping = 2.0e4;
  WheelsetSimulation sim(p, track, contact, v, 1e-3);
  while (sim.time() < 15.0) sim.step();
  // Pure rolling: the outer (right) wheel rolls on the larger radius, y = -r0 q0 kappa / lambda.
  const double expected = -contact.r0 * p.running_circle_q / radius / contact.conicity;
  std::printf("  balanced curve: y = %.6e m, pure rolling %.6e m, psi = %.1e rad\n",
              sim.state().y, expected, sim.state().yaw);
  EXPECT_NEAR(sim.state().y / expected, 1.0, 0.02) << "y " << sim.state().y;
  EXPECT_LT(std::abs(sim.state().yaw), 1e-6);
  EXPECT_LT(std::abs(sim.state().lateral_velocity), 1e-6);
  EXPECT_NEAR(sim.snapshot().load[0], sim.snapshot().load[1], 1e-9 * sim.snapshot().load[1]);
}

// The two static equations of docs/vehicle-model.md, linearised, with the test contact:
//   lateral: 2 f22 psi + 2 dQ tan(delta) - k_y (y - y_b) - (m + M) a_u = 0
//   yaw:     -2 f11 q0 (lambda y / r0 + kappa q0) - k_psi (psi - psi_b) = 0
// `cant_height` signed like the cant angle (+ right rail up).
struct StaticCurving {
  double y = 0.0, psi = 0.0, load_transfer = 0.0;
};
StaticCurving linear_static_curving(const WheelsetParameters& p, const LinearContact& contact,
                                    double v, double kappa, double cant_height) {
  const double q0 = p.running_circle_q, a = p.semi_wheelbase;
  const double a_u = v * v * kappa - p.gravity * cant_height / 1.5;
  const double dq = (p.carried_mass * p.cg_height + p.mass * p.nominal_radius) * a_u / (2 * q0);
  const double k_psi = 2 * p.primary_longitudinal_stiffness * std::pow(p.axlebox_semi_spacing, 2);
  const double y_b = -a * a * kappa / 2, psi_b = -a * kappa;
  const double a11 = -p.primary_lateral_stiffness, a12 = 2 * contact.f22;
  const double b1 = (p.mass + p.carried_mass) * a_u - 2 * dq * std::tan(contact.angle) -
                    p.primary_lateral_stiffness * y_b;
  const double a21 = -2 * contact.f11 * q0 * contact.conicity / contact.r0, a22 = -k_psi;
  const double b2 = 2 * contact.f11 * q0 * q0 * kappa - k_psi * psi_b;
  const double det = a11 * a22 - a12 * a21;
  return {(b1 * a22 - a12 * b2) / det, (a11 * b2 - a21 * b1) / det, dq};
}

TEST(WheelsetSimulation, SuspendedWheelsetInCurveMeetsStaticEquilibrium) {
  const double v = 20.0, radius = 300.0, cant = 0.1;
  const TrackLayout track = curve(radius, cant);
  LinearContact contact;
  WheelsetParameters p;
  p.primary_lateral_damping = 3.0e4;
  WheelsetSimulation sim(p, track, contact, v, 1e-3);
  while (sim.time() < 6.0) sim.step();

  const StaticCurving expected = linear_static_curving(p, contact, v, 1.0 / radius, cant);
  std::printf("  curving: y = %.6e m (linear statics %.6e), psi = %.6e rad (%.6e)\n",
              sim.state().y, expected.y, sim.state().yaw, expected.psi);
  EXPECT_NEAR(sim.state().y / expected.y, 1.0, 0.01);
  EXPECT_NEAR(sim.state().yaw / expected.psi, 1.0, 0.01);
  // The spin balance's first estimate is exact for a linear creep law with equal areas.
  EXPECT_EQ(contact.creep_calls, contact.normal_calls);
  // The inner (left) wheel is unloaded by the cant deficiency.
  EXPECT_NEAR(sim.snapshot().load[1] - sim.snapshot().load[0], 2 * expected.load_transfer,
              1e-9 * expected.load_transfer);
}

TEST(WheelsetSimulation, TrailingWheelsetThroughTransitionIntoRightCurve) {
  // Tangent, 60 m clothoid with cant ramp, then R 300 m to the right: the mirror image of the
  // curve above, reached through the transition, for a trailing wheelset (a < 0).
  const double v = 20.0, kappa = -1.0 / 300.0, cant = 0.1;
  const TrackLayout track(
      {{20, 0, 0, 0, 0}, {60, 0, kappa, 0, cant}, {300, kappa, kappa, cant, cant}}, {});
  LinearContact contact;
  WheelsetParameters p;
  p.primary_lateral_damping = 3.0e4;
  p.semi_wheelbase = -1.25;
  WheelsetSimulation sim(p, track, contact, v, 1e-3);
  while (sim.distance() < 300.0) sim.step();
  const StaticCurving expected = linear_static_curving(p, contact, v, kappa, -cant);
  std::printf("  right curve, trailing: y = %.6e m (%.6e), psi = %.6e rad (%.6e)\n",
              sim.state().y, expected.y, sim.state().yaw, expected.psi);
  // The trailing wheelset, yawed with the bogie, is steered to the inner (right) rail.
  EXPECT_LT(expected.y, 0.0);
  EXPECT_NEAR(sim.state().y / expected.y, 1.0, 0.01);
  EXPECT_NEAR(sim.state().yaw / expected.psi, 1.0, 0.01);
  // Now the left wheel is the outer one and carries more.
  EXPECT_GT(sim.snapshot().load[0], sim.snapshot().load[1]);
}

// y at t = 1 s after an initial offset, on a track with a lateral irregularity (it keeps the
// wheelset moving, so y(1 s) is millimetres, not round-off), with a given step.
double y_after_one_second(double time_step) {
  Irregularity irregularity;
  irregularity.amplitude = 3e-3;
  const TrackLayout track({{100.0, 0, 0, 0, 0}}, irregularity);
  LinearContact contact;
  WheelsetParameters p;
  p.primary_lateral_damping = 1.0e4;
  WheelsetState start;
  start.y = 2e-3;
  start.yaw = -1e-3;
  WheelsetSimulation sim(p, track, contact, 30.0, time_step, start);
  const auto steps = static_cast<int>(std::lround(1.0 / time_step));
  for (int i = 0; i < steps; ++i) sim.step();
  return sim.state().y;
}

TEST(WheelsetSimulation, Rk4ErrorFallsSixteenfoldPerHalvedStep) {
  const double reference = y_after_one_second(0.125e-3);
  const double coarse = std::abs(y_after_one_second(2e-3) - reference);
  const double fine = std::abs(y_after_one_second(1e-3) - reference);
  std::printf("  RK4: y(1 s) = %.6e m; error %.3e m at 2 ms, %.3e m at 1 ms: ratio %.1f\n",
              reference, coarse, fine, coarse / fine);
  EXPECT_GT(coarse / fine, 10.0) << "error " << coarse << " m at 2 ms, " << fine
                                 << " m at 1 ms";
}

TEST(WheelsetSimulation, SaturatedCreepStaysWithinFrictionAndBalancesTorque) {
  // A tight, under-canted curve with low conicity: the creepages saturate.
  const TrackLayout track = curve(120.0, 0.0);
  LinearContact contact;
  contact.mu = 0.3;
  contact.conicity = 0.02;
  WheelsetParameters p;
  p.primary_lateral_damping = 3.0e4;
  WheelsetSimulation sim(p, track, contact, 15.0, 5e-4);
  std::uint32_t seen = 0;
  for (int i = 0; i < 2000; ++i) {
    sim.step();
    const ContactSnapshot& snap = sim.snapshot();
    seen |= snap.status;
    double torque = 0.0;
    for (int w = 0; w < kWheels; ++w) {
      const SlotContact& c = snap.contacts[w].slot[0];
      const SlotForces& f = snap.forces[w][0];
      ASSERT_LE(std::hypot(f.fx, f.fy), contact.mu * c.normal_force * (1 + 1e-12));
      torque += c.rolling_radius * f.fx;
    }
    ASSERT_LE(std::abs(torque), 1e-9 * p.static_wheel_load() * p.nominal_radius * 1.0001);
  }
  std::printf("  saturated curving: %.2f creep() calls per normal() call\n",
              double(contact.creep_calls) / contact.normal_calls);
  EXPECT_NE(seen & status::kFullSlip, 0u);  // the case does reach saturation
  EXPECT_EQ(seen & status::kNotConverged, 0u);
}

TEST(WheelsetSimulation, StableStepEstimateMatchesCreepDamping) {
  const TrackLayout track = tangent(100.0);
  LinearContact contact;
  const WheelsetParameters p;
  WheelsetSimulation sim(p, track, contact, 33.0, 1e-3);
  // Linear creep: lateral damping 2 f22 / V, yaw damping 2 f11 y_c^2 / V (y_c = q0 when centred).
  const double lateral = 2 * contact.f22 / 33.0 / p.mass;
  const double yaw = 2 * contact.f11 * p.running_circle_q * p.running_circle_q / 33.0 /
                     p.yaw_inertia;
  EXPECT_NEAR(sim.stable_time_step_estimate(), 2.78 / std::max(lateral, yaw), 1e-9);
}

TEST(WheelsetSimulation, StableStepEstimateFollowsAStiffContact) {
  // A contact angle changing fast with y (as in flange contact): the lateral stiffness
  // 2 Q epsilon / cos^2(delta) of the normal forces sets the limit, not the creep damping.
  const TrackLayout track = tangent(100.0);
  LinearContact contact;
  contact.angle_slope = 5000.0;  // rad/m
  const WheelsetParameters p;
  WheelsetSimulation sim(p, track, contact, 33.0, 1e-3);
  const double stiffness = p.primary_lateral_stiffness + 2 * p.static_wheel_load() *
                                                             contact.angle_slope /
                                                             std::pow(std::cos(contact.angle), 2);
  EXPECT_NEAR(sim.stable_time_step_estimate() / (2.78 / std::sqrt(stiffness / p.mass)), 1.0, 1e-4);
}

TEST(WheelsetSimulation, StableStepEstimateIsStableAndTwiceItIsNot) {
  LinearContact contact;
  const TrackLayout track = tangent(400.0);
  const WheelsetParameters p = free_wheelset();
  WheelsetState start;
  start.y = 1e-3;
  WheelsetSimulation probe(p, track, contact, 10.0, 1e-3, start);
  const double h = probe.stable_time_step_estimate();
  auto final_offset = [&](double time_step) {
    WheelsetSimulation sim(p, track, contact, 10.0, time_step, start);
    while (sim.time() < 1.0) sim.step();
    return std::abs(sim.state().y);
  };
  EXPECT_LT(final_offset(0.9 * h), 1e-2);
  EXPECT_GT(final_offset(1.5 * h), 1.0);  // diverged (or NaN-free blow-up)
}

TEST(WheelsetSimulation, SnapshotIsTheContactAtTheStartOfTheStep) {
  Irregularity irregularity;
  irregularity.amplitude = 2e-3;
  const TrackLayout track({{50, 0, 0, 0, 0}, {60, 0, 1.0 / 400, 0, 0.08}}, irregularity);
  LinearContact contact;
  WheelsetSimulation sim(WheelsetParameters{}, track, contact, 25.0, 1e-3);
  for (int i = 0; i < 2500; ++i) sim.step();  // into the transition
  const WheelsetState before = sim.state();
  const ContactSnapshot expected = sim.evaluate(before, sim.distance());
  sim.step();
  const ContactSnapshot& got = sim.snapshot();
  EXPECT_EQ(got.y_relative, expected.y_relative);
  EXPECT_NE(got.y_relative, before.y);  // the irregularity is in it
  EXPECT_EQ(got.load[0], expected.load[0]);
  EXPECT_EQ(got.motion.curvature, expected.motion.curvature);
  EXPECT_GT(got.motion.curvature, 0.0);
  for (int w = 0; w < kWheels; ++w) {
    // Equal up to the spin balance's tolerance (its warm start differs between the two calls).
    EXPECT_NEAR(got.forces[w][0].fx, expected.forces[w][0].fx, 1e-6);
    EXPECT_NEAR(got.lateral_force[w], expected.lateral_force[w], 1e-6);
  }
}

TEST(WheelsetSimulation, BadInputsThrowNamingTheParameter) {
  const TrackLayout track = tangent(100.0);
  LinearContact contact;
  auto message = [&](auto make) -> std::string {
    try {
      make();
    } catch (const railtab::Error& e) {
      return e.what();
    }
    return "no exception";
  };
  EXPECT_NE(message([&] { WheelsetSimulation(WheelsetParameters{}, track, contact, 0.0, 1e-3); })
                .find("speed"),
            std::string::npos);
  WheelsetParameters negative_mass;
  negative_mass.mass = -1.0;
  EXPECT_NE(message([&] { WheelsetSimulation(negative_mass, track, contact, 30.0, 1e-3); })
                .find("mass"),
            std::string::npos);
  EXPECT_NE(message([&] {
              WheelsetSimulation(WheelsetParameters{}, track, contact, 30.0, std::nan(""));
            }).find("time_step"),
            std::string::npos);
  WheelsetState nan_state;
  nan_state.y = std::nan("");
  EXPECT_NE(message([&] {
              WheelsetSimulation(WheelsetParameters{}, track, contact, 30.0, 1e-3, nan_state);
            }).find("initial state"),
            std::string::npos);
}

}  // namespace
}  // namespace railtab::vehicle
