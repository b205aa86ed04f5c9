// SPDX-License-Identifier: Apache-2.0
// The bogie equations of motion against closed-form results of the linear contact model
// (docs/vehicle-model.md, "The bogie").
#include "vehicle/bogie_model.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <utility>
#include <cstdio>
#include <string>

#include "core/check.hpp"
#include "core/status.hpp"
#include "error_message.hpp"
#include "vehicle/linear_contact_helper.hpp"

namespace railtab::vehicle {
namespace {

using testing::LinearContact;

TEST(BogieSimulation, TangentTrackCentredStartStaysCentredWithoutCreepForces) {
  const TrackLayout track({{500.0, 0, 0, 0, 0}}, {});
  LinearContact contact;
  const BogieParameters p;
  BogieSimulation sim(p, track, contact, 33.0, 1e-3, {}, 2.0);
  double largest_force = 0.0, largest_offset = 0.0;
  for (int i = 0; i < 10000; ++i) {
    sim.step();
    for (const ContactSnapshot& w : sim.snapshot().wheelset) {
      for (const auto& wheel : w.forces) {
        largest_force = std::max({largest_force, std::abs(wheel[0].fx), std::abs(wheel[0].fy)});
      }
    }
    for (const WheelsetState& x : {sim.state().wheelset[0], sim.state().wheelset[1], sim.state().frame}) {
      largest_offset = std::max({largest_offset, std::abs(x.y), std::abs(x.yaw)});
    }
  }
  EXPECT_NEAR(sim.time(), 10.0, 1e-12);
  EXPECT_NEAR(sim.distance(), 332.0, 1e-9);
  EXPECT_LT(largest_offset, 1e-12);
  EXPECT_LT(largest_force, 1e-6);  // N; round-off of xi = 1 - Omega r / V
  // Every wheel carries the bogie's static wheel load on level track.
  for (const ContactSnapshot& w : sim.snapshot().wheelset) {
    EXPECT_NEAR(w.load[0], p.static_wheel_load(), 1e-9 * p.static_wheel_load());
    EXPECT_NEAR(w.load[1], p.static_wheel_load(), 1e-9 * p.static_wheel_load());
  }
  EXPECT_EQ(sim.snapshot().status & status::kNotConverged, 0u);
}

// Steady curving of the linear coned bogie in a balanced curve (no load transfer, no unbalanced
// force) with no secondary stiffness (docs/vehicle-model.md derives it): the wheelsets yaw by
// +-p, the frame by psi_f, and
//   p     = -a kappa / (1 + 4 f11 f22 q0 lambda (a^2 / k_psi + 1 / k_y) / (r0 k_psi))
//   psi_f = 2 a f22 p / k_psi
//   y1 - y2 = 4 f22 p (a^2 / k_psi + 1 / k_y)
//   (y1 + y2) / 2 = -r0 q0 kappa / lambda + r0 a f22 p / (lambda f11 q0)
//   y_f = (y1 + y2) / 2 + a^2 kappa / 2
struct BogieCurving {
  double p, psi_f, y1, y2, y_f;
};
BogieCurving balanced_bogie_curving(const WheelsetParameters& w, const LinearContact& c,
                                    double kappa) {
  const double a = w.semi_wheelbase, q0 = w.running_circle_q, r0 = c.r0, lambda = c.conicity;
  const double k_y = w.primary_lateral_stiffness, k_psi = w.primary_yaw_stiffness();
  const double compliance = a * a / k_psi + 1.0 / k_y;
  const double p =
      -a * kappa / (1.0 + 4.0 * c.f11 * c.f22 * q0 * lambda * compliance / (r0 * k_psi));
  const double difference = 4.0 * c.f22 * p * compliance;
  const double mean = -r0 * q0 * kappa / lambda + r0 * a * c.f22 * p / (lambda * c.f11 * q0);
  return {p, 2.0 * a * c.f22 * p / k_psi, mean + difference / 2, mean - difference / 2,
          mean + a * a * kappa / 2};
}

TEST(BogieSimulation, LinearBogieInBalancedCurveMeetsItsClosedForm) {
  const double v = 15.0, radius = 300.0, g = 9.81;
  const double cant = 1.5 * v * v / radius / g;  // a_u = 0
  const TrackLayout track({{3000.0, 1.0 / radius, 1.0 / radius, cant, cant}}, {});
  LinearContact contact;
  BogieParameters p;
  p.wheelset.gravity = g;
  p.wheelset.primary_lateral_damping = 2.0e4;  // dampers only take the energy out:
  p.secondary_lateral_stiffness = 0.0;         // no force at the steady state
  p.secondary_yaw_stiffness = 0.0;
  p.secondary_lateral_damping = 3.0e4;
  p.secondary_yaw_damping = 5.0e4;
  BogieSimulation sim(p, track, contact, v, 1e-3, {}, 10.0);
  while (sim.time() < 30.0) sim.step();
  const BogieCurving expected = balanced_bogie_curving(p.wheelset, contact, 1.0 / radius);
  const BogieState& x = sim.state();
  std::printf("  bogie curving: leading y %.6e yaw %.6e, trailing y %.6e yaw %.6e, frame y %.6e "
              "yaw %.6e\n  closed form:   leading y %.6e yaw %.6e, trailing y %.6e yaw %.6e, "
              "frame y %.6e yaw %.6e\n",
              x.wheelset[0].y, x.wheelset[0].yaw, x.wheelset[1].y, x.wheelset[1].yaw, x.frame.y,
              x.frame.yaw, expected.y1, expected.p, expected.y2, -expected.p, expected.y_f,
              expected.psi_f);
  // The linearisation (sin, cos of the small contact angle; spin balance to first order) is
  // the only difference: 1 %.
  EXPECT_NEAR(x.wheelset[0].y / expected.y1, 1.0, 0.01);
  EXPECT_NEAR(x.wheelset[1].y / expected.y2, 1.0, 0.01);
  EXPECT_NEAR(x.wheelset[0].yaw / expected.p, 1.0, 0.01);
  EXPECT_NEAR(x.wheelset[1].yaw / -expected.p, 1.0, 0.01);
  EXPECT_NEAR(x.frame.y / expected.y_f, 1.0, 0.01);
  EXPECT_NEAR(x.frame.yaw / expected.psi_f, 1.0, 0.01);
  // The leading wheelset yaws towards the outer rail (under-radial), the trailing one mirrors it.
  EXPECT_LT(x.wheelset[0].yaw, 0.0);
  EXPECT_GT(x.wheelset[1].yaw, 0.0);
  EXPECT_LT(std::abs(x.wheelset[0].lateral_velocity), 1e-6);
}

// The general linear statics of docs/vehicle-model.md ("The bogie"), with cant deficiency, load
// transfer and the secondary springs, as six linear equations in (y0, psi0, y1, psi1, y_f, psi_f)
// solved by Gaussian elimination:
//   wheelset i:  2 f22 psi_i + 2 dQ tan(delta) - k_y (y_i - y_f - a_i psi_f + a_i^2 kappa / 2) - m a_u = 0
//                -2 f11 q0 (lambda y_i / r0 + kappa q0) - k_psi (psi_i - psi_f + a_i kappa) = 0
//   frame:       sum_i k_y (y_i - y_f - a_i psi_f + a_i^2 kappa / 2) - k_sy y_f - (M_c / 2 + m_f) a_u = 0
//                sum_i (a_i k_y (...)_i + k_psi (psi_i - psi_f + a_i kappa)) - k_spsi (psi_f + L kappa) = 0
std::array<double, 6> linear_bogie_statics(const BogieParameters& p, const LinearContact& c, double v,
                                           double kappa, double cant_height) {
  const WheelsetParameters& w = p.wheelset;
  const double a_u = v * v * kappa - w.gravity * cant_height / 1.5;
  const double dq = (p.carried_mass() * p.carried_cg_height() + w.mass * w.nominal_radius) * a_u /
                    (2 * w.running_circle_q);
  const double k_y = w.primary_lateral_stiffness, k_psi = w.primary_yaw_stiffness();
  const double q0 = w.running_circle_q, a = w.semi_wheelbase, L = p.bogie_semi_spacing;
  double m[6][7] = {};  // augmented matrix, unknowns y0 psi0 y1 psi1 yf psif
  for (int i = 0; i < 2; ++i) {
    const double ai = i == 0 ? a : -a;
    double* lat = m[2 * i];
    double* yaw = m[2 * i + 1];
    lat[2 * i + 1] = 2 * c.f22;
    lat[2 * i] = -k_y;
    lat[4] = k_y;
    lat[5] = k_y * ai;
    lat[6] = -(2 * dq * std::tan(c.angle) - k_y * ai * ai * kappa / 2 - w.mass * a_u);
    yaw[2 * i] = -2 * c.f11 * q0 * c.conicity / c.r0;
    yaw[2 * i + 1] = -k_psi;
    yaw[5] = k_psi;
    yaw[6] = 2 * c.f11 * q0 * q0 * kappa + k_psi * ai * kappa;
    // Frame: primary reactions.
    m[4][2 * i] += k_y;
    m[4][4] -= k_y;
    m[4][5] -= k_y * ai;
    m[4][6] -= k_y * ai * ai * kappa / 2;
    m[5][2 * i] += ai * k_y;
    m[5][4] -= ai * k_y;
    m[5][5] -= ai * ai * k_y;
    m[5][6] -= ai * k_y * ai * ai * kappa / 2;
    m[5][2 * i + 1] += k_psi;
    m[5][5] -= k_psi;
    m[5][6] -= k_psi * ai * kappa;
  }
  m[4][4] -= p.secondary_lateral_stiffness;
  m[4][6] += (p.body_mass / 2 + p.frame_mass) * a_u;
  m[5][5] -= p.secondary_yaw_stiffness;
  m[5][6] += p.secondary_yaw_stiffness * L * kappa;
  for (int col = 0; col < 6; ++col) {  // elimination with partial pivoting
    int pivot = col;
    for (int r = col + 1; r < 6; ++r) {
      if (std::abs(m[r][col]) > std::abs(m[pivot][col])) pivot = r;
    }
    std::swap(m[col], m[pivot]);
    for (int r = 0; r < 6; ++r) {
      if (r == col) continue;
      const double f = m[r][col] / m[col][col];
      for (int k = col; k < 7; ++k) m[r][k] -= f * m[col][k];
    }
  }
  std::array<double, 6> x{};
  for (int r = 0; r < 6; ++r) x[static_cast<std::size_t>(r)] = m[r][6] / m[r][r];
  return x;
}

TEST(BogieSimulation, LinearBogieUnderCantDeficiencyMeetsItsLinearStatics) {
  const double v = 20.0, radius = 300.0, cant = 0.1;
  const TrackLayout track({{3000.0, 1.0 / radius, 1.0 / radius, cant, cant}}, {});
  LinearContact contact;
  BogieParameters p;
  p.wheelset.primary_lateral_damping = 3.0e4;
  p.secondary_yaw_damping = 5.0e4;
  BogieSimulation sim(p, track, contact, v, 1e-3, {}, 10.0);
  while (sim.time() < 30.0) sim.step();
  const std::array<double, 6> e = linear_bogie_statics(p, contact, v, 1.0 / radius, cant);
  const BogieState& x = sim.state();
  const double got[6] = {x.wheelset[0].y, x.wheelset[0].yaw, x.wheelset[1].y,
                         x.wheelset[1].yaw, x.frame.y, x.frame.yaw};
  const char* names[6] = {"leading y", "leading yaw", "trailing y", "trailing yaw", "frame y",
                          "frame yaw"};
  for (int i = 0; i < 6; ++i) {
    std::printf("  cant deficiency: %-12s %.6e (linear statics %.6e)\n", names[i], got[i],
                e[static_cast<std::size_t>(i)]);
    EXPECT_NEAR(got[i] / e[static_cast<std::size_t>(i)], 1.0, 0.01) << names[i];
  }
}

TEST(BogieSimulation, CantDeficiencyTransfersTheCarriedWeightToTheOuterWheels) {
  const double v = 25.0, radius = 600.0, cant = 0.05;
  const TrackLayout track({{1000.0, 1.0 / radius, 1.0 / radius, cant, cant}}, {});
  LinearContact contact;
  const BogieParameters p;
  BogieSimulation sim(p, track, contact, v, 1e-3, {}, 10.0);
  const double a_u = v * v / radius - p.wheelset.gravity * cant / 1.5;
  const double transfer =
      (p.carried_mass() * p.carried_cg_height() + p.wheelset.mass * p.wheelset.nominal_radius) *
      a_u / (2 * p.wheelset.running_circle_q);
  for (const ContactSnapshot& w : sim.snapshot().wheelset) {
    EXPECT_NEAR(w.load[1] - w.load[0], 2 * transfer, 1e-9 * transfer);  // right = outer
    EXPECT_NEAR(w.load[0] + w.load[1], 2 * p.static_wheel_load(), 1e-9 * transfer);
  }
  // The body's and frame's unbalanced force, (M/2 + m_f) a_u, is carried by the wheelsets in
  // the steady curve: their primary forces on the frame balance it and the secondary spring.
  BogieParameters damped = p;
  damped.wheelset.primary_lateral_damping = 2.0e4;
  damped.secondary_yaw_damping = 5.0e4;
  BogieSimulation settled(damped, track, contact, v, 1e-3, {}, 10.0);
  while (settled.time() < 20.0) settled.step();
  const BogieSnapshot& s = settled.snapshot();
  const double primary_on_frame =
      -(s.wheelset[0].suspension_lateral_force + s.wheelset[1].suspension_lateral_force);
  EXPECT_NEAR(primary_on_frame + s.secondary_lateral_force, p.frame_mass * a_u,
              1e-4 * p.frame_mass * a_u);
}

// y of the leading wheelset at t = 1 s after an initial offset, on an irregular track.
double leading_y_after_one_second(double time_step) {
  Irregularity irregularity;
  irregularity.amplitude = 3e-3;
  const TrackLayout track({{100.0, 0, 0, 0, 0}}, irregularity);
  LinearContact contact;
  BogieParameters p;
  p.wheelset.primary_lateral_damping = 1.0e4;
  BogieState start;
  start.wheelset[0].y = 2e-3;
  start.wheelset[1].yaw = -1e-3;
  start.frame.y = 1e-3;
  BogieSimulation sim(p, track, contact, 30.0, time_step, start, 2.0);
  const auto steps = static_cast<int>(std::lround(1.0 / time_step));
  for (int i = 0; i < steps; ++i) sim.step();
  return sim.state().wheelset[0].y;
}

TEST(BogieSimulation, Rk4ErrorFallsSixteenfoldPerHalvedStep) {
  const double reference = leading_y_after_one_second(0.125e-3);
  const double coarse = std::abs(leading_y_after_one_second(2e-3) - reference);
  const double fine = std::abs(leading_y_after_one_second(1e-3) - reference);
  std::printf("  bogie RK4: y(1 s) = %.6e m; error %.3e m at 2 ms, %.3e m at 1 ms: ratio %.1f\n",
              reference, coarse, fine, coarse / fine);
  EXPECT_GT(coarse / fine, 10.0) << "error " << coarse << " m at 2 ms, " << fine << " m at 1 ms";
}

TEST(BogieSimulation, StableStepEstimateIsStable) {
  const TrackLayout track({{400.0, 0, 0, 0, 0}}, {});
  LinearContact contact;
  const BogieParameters p;
  BogieState start;
  start.wheelset[0].y = 1e-3;
  BogieSimulation probe(p, track, contact, 30.0, 1e-3, start, 2.0);
  const double h = probe.stable_time_step_estimate();
  EXPECT_GT(h, 0.0);
  BogieSimulation sim(p, track, contact, 30.0, 0.9 * h, start, 2.0);
  while (sim.time() < 2.0) sim.step();
  EXPECT_LT(std::abs(sim.state().wheelset[0].y), 1e-2);
}

TEST(BogieSimulation, BadInputsThrowNamingTheParameter) {
  const TrackLayout track({{100.0, 0, 0, 0, 0}}, {});
  LinearContact contact;
  auto message = [&](const BogieParameters& p, double speed = 30.0, double dt = 1e-3,
                     const BogieState& x = {}, double start = 0.0) {
    return railtab::test::error_message([&] { BogieSimulation(p, track, contact, speed, dt, x, start); });
  };
  EXPECT_NE(message(BogieParameters{}, 0.0).find("speed"), std::string::npos);
  EXPECT_NE(message(BogieParameters{}, 30.0, -1.0).find("time_step"), std::string::npos);
  BogieParameters bad;
  bad.frame_mass = 0.0;
  EXPECT_NE(message(bad).find("frame_mass"), std::string::npos);
  bad = {};
  bad.wheelset.semi_wheelbase = 0.0;
  EXPECT_NE(message(bad).find("wheelset.semi_wheelbase"), std::string::npos);
  bad = {};
  bad.secondary_yaw_damping = -1.0;
  EXPECT_NE(message(bad).find("secondary_yaw_damping"), std::string::npos);
  bad = {};
  bad.body_cg_height = std::nan("");
  EXPECT_NE(message(bad).find("body_cg_height"), std::string::npos);
  BogieState nan_frame;
  nan_frame.frame.yaw = std::nan("");
  EXPECT_NE(message(BogieParameters{}, 30.0, 1e-3, nan_frame).find("initial state of the frame"),
            std::string::npos);
  EXPECT_NE(message(BogieParameters{}, 30.0, 1e-3, {}, -1.0).find("start_distance"),
            std::string::npos);
}

}  // namespace
}  // namespace railtab::vehicle
