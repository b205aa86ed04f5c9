// SPDX-License-Identifier: Apache-2.0
// Linear creep coefficients (src/tangential/linear_creep): central differences reproduce a linear
// model's matrix; FASTSIM on the Hertz patches of S1002 on UIC60 gives Kalker's C11, C22, C23
// within 2 %; and how far the non-elliptic STRIPES patches of that pair depart from the
// equivalent ellipse's coefficients (printed, docs/validation/creep-coefficients.md).
#include "tangential/linear_creep.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/check.hpp"
#include "geometry/contact_geometry.hpp"
#include "profile/standard/s1002.hpp"
#include "profile/standard/uic60.hpp"

namespace railtab::linear_creep_test {  // own namespace: unity builds compile several test files as one
namespace {

ContactGeometrySolver make_solver() {
  const ProfilePtr wheel = make_s1002_profile();
  const ProfilePtr rail = make_uic60_profile();
  return ContactGeometrySolver(wheel, rail, wheel, rail, TrackGeometry{}, WheelsetGeometry{});
}

Material steel() {  // the shipped scenes': E 210 GPa, nu 0.3
  Material m;
  m.youngs_modulus = 210e9;
  m.poisson_ratio = 0.3;
  return m;
}

TEST(LinearCreep, DifferencesOfALinearModelAreItsMatrix) {
  const double m[3][3] = {{-3e7, 2e5, -4e4}, {1e5, -2.5e7, -6e5}, {3e3, 7e5, -90.0}};
  const CreepForces linear = [&](const Creepage& c) -> std::array<double, 3> {
    return {m[0][0] * c.xi + m[0][1] * c.eta + m[0][2] * c.phi, m[1][0] * c.xi + m[1][1] * c.eta + m[1][2] * c.phi,
            m[2][0] * c.xi + m[2][1] * c.eta + m[2][2] * c.phi};
  };
  const LinearCreep l = linear_creep(linear, {1e-6, 2e-6, 1e-4});
  for (int f = 0; f < 3; ++f)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(l.slope[f][c], m[f][c], 1e-8 * std::abs(m[f][c])) << f << c;
  EXPECT_THROW(linear_creep(linear, {1e-6, 0.0, 1e-4}), Error);
}

TEST(LinearCreep, KalkerOnAnEllipse) {
  // a = b = 5 mm, nu = 0.25: Kalker's table (Table E.3, a/b = 1) C11 = 4.12, C22 = 3.67, C23 = 1.47;
  // c^2 = 25 mm2: fx_xi = -G c^2 C11, fy_eta = -G c^2 C22, fy_phi = -G c^3 C23, mz_eta = +G c^3 C23.
  Material mat = steel();
  mat.poisson_ratio = 0.25;
  const LinearCreep k = kalker_linear_creep(5e-3, 5e-3, mat);
  const double g = mat.shear_modulus(), c2 = 25e-6;
  EXPECT_NEAR(k.slope[0][0] / (-g * c2), 4.12, 1e-9);
  EXPECT_NEAR(k.slope[1][1] / (-g * c2), 3.67, 1e-9);
  EXPECT_NEAR(k.slope[1][2] / (-g * c2 * 5e-3), 1.47, 1e-9);
  EXPECT_NEAR(k.slope[2][1] / (g * c2 * 5e-3), 1.47, 1e-9);
  EXPECT_EQ(k.slope[0][1], 0.0);
  EXPECT_EQ(k.slope[2][2], 0.0);  // C33: not held
  EXPECT_THROW(kalker_linear_creep(0.0, 5e-3, mat), Error);
}

// FASTSIM in full adhesion on the Hertz patches of the pair (tread, and the flange at 8 mm) is
// Kalker's linear theory on the patch's ellipse, within 2 % (FASTSIM's flexibilities are Kalker's;
// what remains is its discretisation).
TEST(LinearCreep, FastsimOnHertzPatchesIsKalkerWithinTwoPercent) {
  const ContactGeometrySolver solver = make_solver();
  const Material mat = steel();
  NormalOptions normal;
  normal.model = NormalModel::hertz;
  FastsimOptions fastsim;
  FastsimWorkspace ws;
  int patches = 0;
  for (double y : {-0.004, 0.0, 0.003, 0.008}) {
    const WheelContactGeometry g = solver.solve_wheel(Side::left, WheelsetState{y, 0.0});
    const WheelNormalResult n = solve_normal_for_load(g, 78.5e3, mat, normal);
    for (const ContactPatch& p : n.patches) {
      const LinearCreep f = fastsim_linear_creep(g, p, CreepConditions{}, mat, fastsim, ws);
      const LinearCreep k = kalker_linear_creep(p.semi_axis_a, p.semi_axis_b, mat);
      std::printf("[measured] Hertz y = %+.1f mm a/b = %.3f: FASTSIM / Kalker C11 %.4f C22 %.4f C23 %.4f\n", y * 1e3,
                  p.semi_axis_a / p.semi_axis_b, f.slope[0][0] / k.slope[0][0], f.slope[1][1] / k.slope[1][1],
                  f.slope[1][2] / k.slope[1][2]);
      EXPECT_NEAR(f.slope[0][0] / k.slope[0][0], 1.0, 0.02) << y;
      EXPECT_NEAR(f.slope[1][1] / k.slope[1][1], 1.0, 0.02) << y;
      EXPECT_NEAR(f.slope[1][2] / k.slope[1][2], 1.0, 0.02) << y;
      EXPECT_NEAR(f.slope[0][1], 0.0, 1e-6 * std::abs(f.slope[0][0]));  // symmetric patch: no coupling
      ++patches;
    }
  }
  EXPECT_GE(patches, 4);
}

// The non-elliptic patches of STRIPES (A&B, the STRIPES scene's model) against Kalker's theory on
// their equivalent ellipse (equal area, the patch's lateral extent): the ratio of each slope.
// A measurement: it asserts only the signs of the direct slopes; the numbers are the report.
TEST(LinearCreep, StripesPatchesAgainstTheirEquivalentEllipse) {
  const ContactGeometrySolver solver = make_solver();
  const Material mat = steel();
  NormalOptions normal;  // stripes-ab, shift, 50 strips: the STRIPES scene's
  FastsimOptions fastsim;
  fastsim.elements_per_strip = 20;
  FastsimWorkspace ws;
  std::printf("[measured] y_mm patch angle_rad area_mm2 a_mm b_mm C11/K C22/K C23/K (STRIPES-AB + FASTSIM on the "
              "equivalent ellipse's Kalker)\n");
  for (int i = -6; i <= 10; ++i) {
    const double y = 1e-3 * i;
    const WheelContactGeometry g = solver.solve_wheel(Side::left, WheelsetState{y, 0.0});
    const WheelNormalResult n = solve_normal_for_load(g, 78.5e3, mat, normal);
    for (std::size_t k = 0; k < n.patches.size(); ++k) {
      const ContactPatch& p = n.patches[k];
      const auto [a, b] = equivalent_ellipse(p);
      if (!(a > 0.0)) continue;
      const LinearCreep f = fastsim_linear_creep(g, p, CreepConditions{}, mat, fastsim, ws);
      const LinearCreep e = kalker_linear_creep(a, b, mat);
      std::printf("[measured] %+5.1f %zu %.3f %6.1f %.2f %.2f %.3f %.3f %.3f\n", y * 1e3, k, p.contact_angle,
                  p.area * 1e6, a * 1e3, b * 1e3, f.slope[0][0] / e.slope[0][0], f.slope[1][1] / e.slope[1][1],
                  f.slope[1][2] / e.slope[1][2]);
      EXPECT_LT(f.slope[0][0], 0.0) << y;
      EXPECT_LT(f.slope[1][1], 0.0) << y;
    }
  }
}

}  // namespace
}  // namespace railtab::linear_creep_test
