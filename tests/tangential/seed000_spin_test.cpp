// SPDX-License-Identifier: Apache-2.0
// Seed 000 / reference block A: right wheel S1002 on UIC60 1:40, central position, 78.5 kN,
// pure spin 0.052 rad/m, mu 0.3, through the real geometry and normal layers. Compares the two
// spin treatments (patch-constant as CONTACT, per-strip as STRIPES). Forces are printed in
// CONTACT's convention (on the rail): fx_N = -fx, fs_N = +fy (docs/conventions.md).
// Reference: CONTACT (block A, dy = 0) -226 / -1581 N; Sichani et al. 2014: CONTACT -2459 / -1558,
// STRIPES -5333 / -2843, KP -2333 / -1258, Linder -2870 / -1672 N.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "geometry/contact_geometry.hpp"
#include "normal/normal_model.hpp"
#include "profile/standard/s1002.hpp"
#include "profile/standard/uic60.hpp"
#include "tangential/fastsim.hpp"

namespace railtab {
namespace {

TEST(Seed000PureSpin, PatchConstantVersusPerStrip) {
  const ProfilePtr wheel = make_s1002_profile();
  const ProfilePtr rail = make_uic60_profile();
  const ContactGeometrySolver solver(wheel, rail, wheel, rail, TrackGeometry{},
                                     WheelsetGeometry{});
  const Material steel{210e9, 0.28};
  const WheelContactGeometry g = solver.solve_wheel(Side::right, WheelsetState{0.0, 0.0});
  FastsimWorkspace ws;
  const NormalModel models[] = {NormalModel::hertz, NormalModel::linder,
                                NormalModel::kik_piotrowski, NormalModel::stripes_a,
                                NormalModel::stripes_ab};
  for (NormalModel model : models) {
    NormalOptions o;
    o.model = model;
    o.hertz_strips = true;  // Hertz patches carry strips only on request
    const WheelNormalResult nr = solve_normal_for_load(g, 78.5e3, steel, o);
    ASSERT_FALSE(nr.patches.empty());
    for (const ContactPatch& patch : nr.patches) {
      if (patch.strips.empty()) continue;
      const PatchPlacement place = placement_of(g, patch);
      const Creepage spin{0.0, 0.0, 0.052};
      FastsimOptions pc, ps;
      ps.spin = SpinVariation::per_strip;
      const FastsimResult a = fastsim_patch(patch, place, spin, 0.3, 20.0, steel, pc, ws);
      const FastsimResult b = fastsim_patch(patch, place, spin, 0.3, 20.0, steel, ps, ws);
      std::printf("[measured] seed000 %-14s gamma %.4f N %.0f: patch-constant fx_N %6.0f fs_N %6.0f"
                  " | per-strip fx_N %6.0f fs_N %6.0f (CONTACT convention)\n",
                  to_string(model), patch.contact_angle, patch.normal_force, -a.fx, a.fy, -b.fx,
                  b.fy);
      for (const FastsimResult* r : {&a, &b}) {
        ASSERT_TRUE(std::isfinite(r->fx) && std::isfinite(r->fy));
        EXPECT_LE(std::hypot(r->fx, r->fy), 0.3 * patch.normal_force * (1 + 1e-12));
      }
      // Lateral force from positive spin is negative on the wheel (s axis), as CONTACT's fs.
      EXPECT_LT(a.fy, 0.0);
    }
  }
}

}  // namespace
}  // namespace railtab
