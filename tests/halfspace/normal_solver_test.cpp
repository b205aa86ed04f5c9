// SPDX-License-Identifier: Apache-2.0
// Normal half-space solver (BCCG + FFT) against Hertz's closed forms.
#include "halfspace/normal_solver.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "halfspace/hertz_grid.hpp"
#include "halfspace/influence.hpp"
#include "normal/hertz.hpp"

namespace railtab {
namespace {

using halfspace::Grid;
using halfspace::NormalSolution;

Material steel() {  // ../shared/reference block D: E = 210 GPa, nu = 0.28
  Material m;
  m.poisson_ratio = 0.28;
  return m;
}

TEST(NormalInfluence, SquareCentreMatchesClosedForm) {
  // Centre of a uniformly loaded square of side 2c: u = 4 c ln(1 + sqrt 2) * 2 / (pi E*)
  // (Johnson eq. 3.27 for one body, doubled for the two bodies' difference with E*).
  const Material m = steel();
  const double c = 1e-3;
  const double expected = 8.0 * c * std::log(1.0 + std::sqrt(2.0)) / (M_PI * m.contact_modulus());
  EXPECT_NEAR(halfspace::normal_influence(0, 0, c, c, m) / expected, 1.0, 1e-12);
  // Far field: a point load N = 4c^2 at distance d gives 4c^2 / (pi E* d).
  const double d = 0.2;
  EXPECT_NEAR(halfspace::normal_influence(d, 0, c, c, m) * M_PI * m.contact_modulus() * d /
                  (4 * c * c), 1.0, 1e-4);
}

struct HertzCase {
  double A, B;
};

// Block D's three curvature ratios (A/B = 1, 0.2, 0.05) at 78 kN with the default element size
// 0.3 mm along x; laterally the element is at most 1/20 of the Hertz width 2b.
TEST(NormalSolver, HertzAreaPressureApproachWithinOnePercent) {
  const Material m = steel();
  const double N = 78e3, A = 1.087;  // A = 1/(2 * 460 mm) [1/m]
  for (const double ratio : {1.0, 0.2, 0.05}) {
    const double B = A / ratio;
    const HertzContact hz = hertz_for_force(A, B, N, m);
    const double dx = 0.3e-3, dy = std::min(0.3e-3, hz.b / 10.0);
    const Grid g = test::grid_around(hz.a, hz.b, dx, dy);
    halfspace::Workspace ws;
    NormalSolution s;
    halfspace::solve_normal_for_force(g, test::quadratic_gap(g, A, B), N, m, {}, ws, s);
    std::printf("[measured] Hertz A/B=%.2f grid %dx%d dx %.3f dy %.3f mm: area %+.2f%% (element"
                " count %+.2f%%) pmax %+.2f%% approach %+.2f%% iterations %d\n", ratio, g.nx, g.ny,
                dx * 1e3, dy * 1e3, 100 * (s.area_estimate / hz.area - 1),
                100 * (s.area / hz.area - 1), 100 * (s.max_pressure / hz.p0 - 1),
                100 * (s.approach / hz.approach - 1), s.iterations);
    EXPECT_TRUE(s.status & status::kConverged) << status::describe(s.status);
    EXPECT_FALSE(s.status & status::kAreaTooSmall);
    EXPECT_NEAR(s.normal_force / N, 1.0, 1e-9);
    EXPECT_NEAR(s.area_estimate / hz.area, 1.0, 0.01) << ratio;
    EXPECT_NEAR(s.max_pressure / hz.p0, 1.0, 0.01) << ratio;
    EXPECT_NEAR(s.approach / hz.approach, 1.0, 0.01) << ratio;
  }
}

TEST(NormalSolver, ApproachControlReproducesLoadControl) {
  const Material m = steel();
  const double A = 1.087, B = 2.0;
  const HertzContact hz = hertz_for_force(A, B, 50e3, m);
  const Grid g = test::grid_around(hz.a, hz.b, 0.3e-3, 0.3e-3);
  const auto h = test::quadratic_gap(g, A, B);
  halfspace::Workspace ws;
  NormalSolution by_force, by_approach;
  halfspace::solve_normal_for_force(g, h, 50e3, m, {}, ws, by_force);
  halfspace::solve_normal_for_approach(g, h, by_force.approach, m, {}, ws, by_approach);
  EXPECT_TRUE(by_approach.status & status::kConverged);
  EXPECT_NEAR(by_approach.normal_force / 50e3, 1.0, 1e-6);
  EXPECT_EQ(by_approach.area, by_force.area);
}

// Grid convergence: the approach error against Hertz falls with the element size at an
// observed order of at least 1 (elements 0.6, 0.3, 0.15 mm on a circular contact).
TEST(NormalSolver, GridConvergenceOrder) {
  const Material m = steel();
  const double A = 1.087, N = 78e3;
  const HertzContact hz = hertz_for_force(A, A, N, m);
  double err[3];
  int k = 0;
  for (const double h : {0.6e-3, 0.3e-3, 0.15e-3}) {
    const Grid g = test::grid_around(hz.a, hz.b, h, h);
    halfspace::Workspace ws;
    NormalSolution s;
    halfspace::solve_normal_for_force(g, test::quadratic_gap(g, A, A), N, m, {}, ws, s);
    err[k++] = std::abs(s.approach / hz.approach - 1);
  }
  const double order1 = std::log2(err[0] / err[1]), order2 = std::log2(err[1] / err[2]);
  std::printf("[measured] approach error 0.6/0.3/0.15 mm: %.2e %.2e %.2e, order %.2f %.2f\n",
              err[0], err[1], err[2], order1, order2);
  EXPECT_GT(order1, 1.0);
  EXPECT_GT(order2, 1.0);
}

TEST(NormalSolver, SmallPotentialAreaIsFlagged) {
  const Material m = steel();
  const double A = 1.087;
  const HertzContact hz = hertz_for_force(A, A, 78e3, m);
  const Grid g = test::grid_around(hz.a, hz.b, 0.3e-3, 0.3e-3, 0.8);  // smaller than the contact
  halfspace::Workspace ws;
  NormalSolution s;
  halfspace::solve_normal_for_force(g, test::quadratic_gap(g, A, A), 78e3, m, {}, ws, s);
  EXPECT_TRUE(s.status & status::kAreaTooSmall);
}

TEST(NormalSolver, BadInputIsFlaggedNotThrown) {
  const Material m = steel();
  const Grid g = test::grid_around(5e-3, 5e-3, 0.5e-3, 0.5e-3);
  auto h = test::quadratic_gap(g, 1.0, 1.0);
  halfspace::Workspace ws;
  NormalSolution s;
  halfspace::solve_normal_for_force(g, h, -1.0, m, {}, ws, s);
  EXPECT_EQ(s.status, status::kInvalidInput);
  h[3] = std::nan("");
  halfspace::solve_normal_for_force(g, h, 1e4, m, {}, ws, s);
  EXPECT_EQ(s.status, status::kInvalidInput);
  halfspace::solve_normal_for_approach(g, test::quadratic_gap(g, 1.0, 1.0), -1e-3, m, {}, ws, s);
  EXPECT_TRUE(s.status & status::kLiftOff);
  EXPECT_EQ(s.normal_force, 0.0);
}

}  // namespace
}  // namespace railtab
