// SPDX-License-Identifier: Apache-2.0
// Steady rolling on Hertzian patches: Kalker's linear creep coefficients, saturation at mu N,
// symmetry, FASTSIM's signs, CONTACT's block D creep cases.
#include "halfspace/tangential_solver.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "halfspace/hertz_grid.hpp"
#include "halfspace/normal_solver.hpp"
#include "normal/hertz.hpp"
#include "tangential/fastsim.hpp"
#include "tangential/kalker_coefficients.hpp"
#include "tangential/patch_test_helper.hpp"

namespace railtab::tangential_solver_test {  // own namespace: unity builds compile several test files as one
namespace {

using halfspace::Grid;

Material steel() {
  Material m;
  m.poisson_ratio = 0.28;
  return m;
}

struct Solved {
  Grid grid;
  HertzContact hz;
  halfspace::NormalSolution normal;
};

// Hertz patch with curvatures A, B at force N, element 0.3 mm (laterally at most b/10).
Solved hertz_patch(double A, double B, double N, const Material& m, halfspace::Workspace& ws,
                   double element = 0.3e-3) {
  Solved s;
  s.hz = hertz_for_force(A, B, N, m);
  s.grid = test::grid_around(s.hz.a, s.hz.b, std::min(element, s.hz.a / 10.0),
                             std::min(element, s.hz.b / 10.0));
  halfspace::solve_normal_for_force(s.grid, test::quadratic_gap(s.grid, A, B), N, m, {}, ws,
                                    s.normal);
  return s;
}

// At vanishing creepage (no slip: mu large) the forces are Kalker's linear theory:
// fx = -G c^2 C11 xi, fy = -G c^2 C22 eta (- G c^3 C23 phi), c^2 = a b. Elements of 0.2 mm
// (about a/30): the discrete contact is larger than the continuum one by O(element) (the
// boundary elements count fully), which puts C11 and C22 +2.0 to +2.4 % high at 0.3 mm.
TEST(TangentialSolver, LinearCreepCoefficientsWithinTwoPercent) {
  const Material m = steel();
  const double G = m.shear_modulus();
  halfspace::Workspace ws;
  for (const double B_over_A : {1.0, 3.0, 0.4}) {
    const Solved p = hertz_patch(1.087, 1.087 * B_over_A, 78e3, m, ws, 0.2e-3);
    const double a = p.hz.a, b = p.hz.b, c2 = a * b;
    const KalkerCoefficients k = kalker_coefficients(a / b, m.poisson_ratio);
    halfspace::TangentialSolution t;
    const double mu = 1e4, xi = 1e-6, eta = 1e-6, phi = 1e-4;
    halfspace::solve_tangential(p.grid, p.normal.pressure, {xi, 0, 0}, mu, m, {}, ws, t);
    const double c11 = -t.fx / (G * c2 * xi);
    halfspace::solve_tangential(p.grid, p.normal.pressure, {0, eta, 0}, mu, m, {}, ws, t);
    const double c22 = -t.fy / (G * c2 * eta);
    halfspace::solve_tangential(p.grid, p.normal.pressure, {0, 0, phi}, mu, m, {}, ws, t);
    const double c23 = -t.fy / (G * std::pow(c2, 1.5) * phi);
    std::printf("[measured] a/b=%.3f C11 %.4f (Kalker %.4f, %+.2f%%) C22 %.4f (%.4f, %+.2f%%)"
                " C23 %.4f (%.4f, %+.2f%%), %d sweeps\n", a / b, c11, k.c11,
                100 * (c11 / k.c11 - 1), c22, k.c22, 100 * (c22 / k.c22 - 1), c23, k.c23,
                100 * (c23 / k.c23 - 1), t.sweeps);
    EXPECT_TRUE(t.status & status::kConverged);
    EXPECT_NEAR(c11 / k.c11, 1.0, 0.02) << a / b;
    EXPECT_NEAR(c22 / k.c22, 1.0, 0.02) << a / b;
    EXPECT_NEAR(c23 / k.c23, 1.0, 0.02) << a / b;
  }
}

// Growing creepage: |F| rises to mu N and never exceeds it; full slip at large creepage, also
// with large spin.
TEST(TangentialSolver, ForceSaturatesAtMuNAndNeverAbove) {
  const Material m = steel();
  halfspace::Workspace ws;
  const Solved p = hertz_patch(1.087, 2.0, 78e3, m, ws);
  const double mu = 0.3, muN = mu * p.normal.normal_force;
  halfspace::TangentialSolution t;
  double last = 0.0;
  for (const double c : {1e-4, 5e-4, 1e-3, 3e-3, 1e-2, 5e-2}) {
    halfspace::solve_tangential(p.grid, p.normal.pressure, {c, 0.5 * c, 0.0}, mu, m, {}, ws, t);
    const double F = std::hypot(t.fx, t.fy);
    EXPECT_TRUE(t.status & status::kConverged) << c;
    EXPECT_LE(F, muN * (1 + 1e-9)) << c;
    EXPECT_GE(F, last) << c;
    last = F;
  }
  EXPECT_NEAR(last / muN, 1.0, 1e-3);
  EXPECT_TRUE(t.status & status::kFullSlip);
  halfspace::solve_tangential(p.grid, p.normal.pressure, {0.0, 0.0, 2.0}, mu, m, {}, ws, t);
  std::printf("[measured] spin 2 rad/m: |F|/muN %.4f, %d sweeps, %s\n",
              std::hypot(t.fx, t.fy) / muN, t.sweeps, status::describe(t.status).c_str());
  EXPECT_TRUE(t.status & status::kConverged);
  EXPECT_LE(std::hypot(t.fx, t.fy), muN * (1 + 1e-9));
}

// y -> -y mirror: eta, phi -> -eta, -phi gives fx -> fx, fy -> -fy, mz -> -mz.
TEST(TangentialSolver, LateralMirrorSymmetry) {
  const Material m = steel();
  halfspace::Workspace ws;
  const Solved p = hertz_patch(1.087, 3.0, 78e3, m, ws);
  halfspace::TangentialSolution t1, t2;
  halfspace::solve_tangential(p.grid, p.normal.pressure, {1e-3, 1e-3, 0.1}, 0.3, m, {}, ws, t1);
  halfspace::solve_tangential(p.grid, p.normal.pressure, {1e-3, -1e-3, -0.1}, 0.3, m, {}, ws, t2);
  const double muN = 0.3 * p.normal.normal_force;
  EXPECT_NEAR(t1.fx, t2.fx, 1e-5 * muN);
  EXPECT_NEAR(t1.fy, -t2.fy, 1e-5 * muN);
  EXPECT_NEAR(t1.mz, -t2.mz, 1e-5 * muN * p.hz.a);
  EXPECT_GT(std::abs(t1.mz), 1.0);
}

// Same signs and nearly the same forces as FASTSIM (the simplified theory) at small creepage.
TEST(TangentialSolver, SignsAsFastsim) {
  const Material m = steel();
  halfspace::Workspace ws;
  const Solved p = hertz_patch(1.087, 2.0, 78e3, m, ws);
  FastsimWorkspace fw;
  for (const Creepage c : {Creepage{2e-4, 0, 0}, Creepage{-2e-4, 0, 0}, Creepage{0, 2e-4, 0},
                           Creepage{0, 0, 0.02}, Creepage{1e-4, -1e-4, -0.01}}) {
    halfspace::TangentialSolution t;
    halfspace::solve_tangential(p.grid, p.normal.pressure, {c.xi, c.eta, c.phi}, 0.3, m, {}, ws,
                                t);
    const FastsimResult f =
        fastsim_ellipse({p.hz.a, p.hz.b, p.normal.normal_force, 60}, c, 0.3, 20.0, m, 60, fw);
    const double muN = 0.3 * p.normal.normal_force;
    std::printf("[measured] creepage (%g, %g, %g): exact fx %.0f fy %.0f mz %.2f | FASTSIM fx %.0f"
                " fy %.0f mz %.2f\n", c.xi, c.eta, c.phi, t.fx, t.fy, t.mz, f.fx, f.fy, f.mz);
    for (const auto& [mine, theirs] : {std::pair{t.fx, f.fx}, std::pair{t.fy, f.fy}}) {
      if (std::abs(theirs) < 0.02 * muN) continue;
      EXPECT_EQ(std::signbit(mine), std::signbit(theirs));
      EXPECT_NEAR(mine / theirs, 1.0, 0.15);
    }
  }
}

// ../shared/reference block D creep cases (cksi = ceta = 0.001, cphi = 0.05 rad/m, mu 0.3):
// CONTACT's module 3 uses Kalker's convention (body 1 = wheel), the identity mapping.
TEST(TangentialSolver, BlockDCreepWithinOnePercentOfMuN) {
  const auto rows = test::read_csv(std::string(RAILTAB_SHARED_DIR) +
                                   "/reference/blockD_hertz_module3.csv");
  if (rows.empty()) GTEST_SKIP() << "../shared/reference/blockD_hertz_module3.csv not found";
  const Material m = steel();
  halfspace::Workspace ws;
  int cases = 0;
  for (const auto& row : rows) {
    if (row.at("case").find("creep") == std::string::npos) continue;
    ++cases;
    const double A = test::num(row, "A1_per_mm") * 1e3, B = test::num(row, "B1_per_mm") * 1e3;
    const double N = test::num(row, "fn_prescribed_N"), mu = test::num(row, "mu");
    const Solved p = hertz_patch(A, B, N, m, ws);
    halfspace::TangentialSolution t;
    halfspace::solve_tangential(
        p.grid, p.normal.pressure,
        {test::num(row, "cksi"), test::num(row, "ceta"), test::num(row, "cphi_rad_per_m")}, mu, m,
        {}, ws, t);
    const double muN = mu * N;
    const double ex = (t.fx - test::num(row, "fx_N")) / muN;
    const double ey = (t.fy - test::num(row, "fy_N")) / muN;
    std::printf("[measured] blockD %s: fx %.0f (CONTACT %.0f) fy %.0f (%.0f): %+.2f%% %+.2f%% of"
                " mu N, %d sweeps\n", row.at("case").c_str(), t.fx, test::num(row, "fx_N"), t.fy,
                test::num(row, "fy_N"), 100 * ex, 100 * ey, t.sweeps);
    EXPECT_LE(std::abs(ex), 0.01) << row.at("case");
    EXPECT_LE(std::abs(ey), 0.01) << row.at("case");
  }
  EXPECT_EQ(cases, 3);
}

TEST(TangentialSolver, BadInputIsFlagged) {
  const Material m = steel();
  halfspace::Workspace ws;
  const Solved p = hertz_patch(1.087, 2.0, 78e3, m, ws, 0.5e-3);
  halfspace::TangentialSolution t;
  halfspace::solve_tangential(p.grid, p.normal.pressure, {std::nan(""), 0, 0}, 0.3, m, {}, ws, t);
  EXPECT_EQ(t.status, status::kInvalidInput);
  halfspace::solve_tangential(p.grid, std::vector<double>(3, 1.0), {0, 0, 0}, 0.3, m, {}, ws, t);
  EXPECT_EQ(t.status, status::kInvalidInput);
}

}  // namespace
}  // namespace railtab::tangential_solver_test
