// SPDX-License-Identifier: Apache-2.0
// The exact model's linear creep coefficients (src/halfspace/patch_linear_creep): its steady
// rolling solution in full adhesion on a Hertzian patch is Kalker's linear theory within 2 %; on
// the patches of S1002 on UIC60 (tread, flange root, flange), the coefficients against those of the
// patch's equivalent ellipse (printed, docs/validation/creep-coefficients.md).
#include "halfspace/patch_linear_creep.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "geometry/contact_geometry.hpp"
#include "halfspace/hertz_grid.hpp"
#include "halfspace/normal_solver.hpp"
#include "halfspace/wheel_rail.hpp"
#include "normal/hertz.hpp"
#include "profile/standard/s1002.hpp"
#include "profile/standard/uic60.hpp"
#include "sanitizer.hpp"

namespace railtab::patch_linear_creep_test {  // own namespace: unity builds compile several test files as one
namespace {

Material steel(double nu) {
  Material m;
  m.poisson_ratio = nu;
  return m;
}

// Hertzian patches (quadratic gap), elements of about a/30 and b/30, against Kalker on Hertz's
// ellipse; the equivalent ellipse read off the elements matches Hertz's. Under a sanitizer the
// elongated patch only (the same code; a third of the time).
TEST(PatchLinearCreep, ExactModelOnHertzPatchesIsKalkerWithinTwoPercent) {
  const Material m = steel(0.28);
  halfspace::Workspace ws;
  const std::vector<double> ratios = test::kSanitized ? std::vector{3.0} : std::vector{1.0, 3.0, 0.4};
  for (const double B_over_A : ratios) {
    const double A = 1.087, B = A * B_over_A;
    const HertzContact hz = hertz_for_force(A, B, 78e3, m);
    const halfspace::Grid grid = test::grid_around(hz.a, hz.b, std::min(0.2e-3, hz.a / 30.0), std::min(0.2e-3, hz.b / 30.0));
    halfspace::NormalSolution normal;
    halfspace::solve_normal_for_force(grid, test::quadratic_gap(grid, A, B), 78e3, m, {}, ws, normal);
    const LinearCreep e = halfspace::patch_linear_creep(grid, normal.pressure, m, {}, ws);
    const LinearCreep k = kalker_linear_creep(hz.a, hz.b, m);
    // The equivalent ellipse of the elements is Hertz's, to about half an element (1/60 of a, b).
    const auto [ea, eb] = halfspace::patch_equivalent_ellipse(grid, normal);
    EXPECT_NEAR(ea / hz.a, 1.0, 0.03) << B_over_A;
    EXPECT_NEAR(eb / hz.b, 1.0, 0.03) << B_over_A;
    std::printf("[measured] Hertz a/b = %.3f (elements: a %.4f, b %.4f of Hertz's): exact / Kalker C11 %.4f C22 %.4f "
                "C23 %.4f; mz_eta / (G c^3 C23) %.4f\n",
                hz.a / hz.b, ea / hz.a, eb / hz.b, e.slope[0][0] / k.slope[0][0], e.slope[1][1] / k.slope[1][1],
                e.slope[1][2] / k.slope[1][2], e.slope[2][1] / k.slope[2][1]);
    EXPECT_NEAR(e.slope[0][0] / k.slope[0][0], 1.0, 0.02) << B_over_A;
    EXPECT_NEAR(e.slope[1][1] / k.slope[1][1], 1.0, 0.02) << B_over_A;
    EXPECT_NEAR(e.slope[1][2] / k.slope[1][2], 1.0, 0.02) << B_over_A;
    // Kalker's reciprocity: the spin moment per lateral creepage is +G c^3 C23.
    EXPECT_NEAR(e.slope[2][1] / k.slope[2][1], 1.0, 0.02) << B_over_A;
    EXPECT_NEAR(e.slope[0][1], 0.0, 1e-3 * std::abs(e.slope[0][0]));
  }
}

// S1002 on UIC60 1:40, left wheel, 78.5 kN, roll 0, the exact model's own patches (0.15 mm
// elements): slopes against Kalker's on the equivalent ellipse of the loaded elements. A
// measurement; it asserts the signs. Under a sanitizer the tread and the flange only (the same
// code; two fifths of the time).
TEST(PatchLinearCreep, WheelRailPatchesAgainstTheirEquivalentEllipse) {
  const Material m = steel(0.3);
  const ProfilePtr w = make_s1002_profile();
  const ProfilePtr r = make_uic60_profile();
  const ContactGeometrySolver solver(w, r, w, r, TrackGeometry{}, WheelsetGeometry{});
  halfspace::Workspace ws;
  // 0.15 mm elements (half the default): the flange patch is about 1.6 mm wide.
  halfspace::HalfspaceOptions options;
  options.element_size = 0.15e-3;
  std::printf("[measured] y_mm patch angle_rad area_mm2 a_mm b_mm C11/K C22/K C23/K (exact model on the "
              "equivalent ellipse's Kalker)\n");
  const std::vector<double> ys =
      test::kSanitized ? std::vector{0.0, 0.008} : std::vector{0.0, 0.003, 0.005, 0.0065, 0.008};
  for (const double y : ys) {
    const WheelContactGeometry g = solver.solve_wheel(Side::left, WheelsetState{y, 0.0});
    const halfspace::WheelHalfspaceResult res = halfspace::solve_halfspace_for_load(g, 78.5e3, m, options, ws);
    for (std::size_t k = 0; k < res.patches.size(); ++k) {
      const halfspace::HalfspacePatch& p = res.patches[k];
      const auto [a, b] = halfspace::patch_equivalent_ellipse(p.grid, p.normal);
      if (!(a > 0.0)) continue;
      const LinearCreep e = halfspace::patch_linear_creep(p.grid, p.normal.pressure, m, options.tangential, ws, p.track_sign);
      const LinearCreep ke = kalker_linear_creep(a, b, m);
      std::printf("[measured] %+5.1f %zu %.3f %6.1f %.2f %.2f %.3f %.3f %.3f\n", y * 1e3, k, p.contact_angle,
                  p.normal.area_estimate * 1e6, a * 1e3, b * 1e3, e.slope[0][0] / ke.slope[0][0],
                  e.slope[1][1] / ke.slope[1][1], e.slope[1][2] / ke.slope[1][2]);
      EXPECT_LT(e.slope[0][0], 0.0) << y;
      EXPECT_LT(e.slope[1][1], 0.0) << y;
    }
  }
}

}  // namespace
}  // namespace railtab::patch_linear_creep_test
