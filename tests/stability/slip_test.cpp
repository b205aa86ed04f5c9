// SPDX-License-Identifier: Apache-2.0
// 7. Full slip and very large spin (FACTS 8 rows 8-9): creepages up to 1, spin up to +-10 rad/m, on
// tread (y = 0), flange root (6 mm) and flank (7 mm) patches of every model, both spin variations.
#include "stability_common.hpp"

namespace railtab::stability {
namespace {

TEST(Slip, SaturatesAtMuNAndNeverExceedsIt) {
  const ContactGeometrySolver& solver = s1002_uic60();
  const double mu = 0.3;
  for (const Variant& v : all_variants()) {
    for (double y : {0.0, 6e-3, 7e-3}) {
      const WheelContactGeometry g = solver.solve_wheel(Side::left, WheelsetState{y, 0.0});
      const WheelNormalResult r = solve_normal_for_load(g, kLoad, Material{}, options_for(v));
      ASSERT_EQ(normal_violation(g, r), "");
      for (const ContactPatch& p : r.patches) {
        for (SpinVariation spin : {SpinVariation::patch_constant, SpinVariation::per_strip}) {
          const std::string where = v.label + " y " + std::to_string(y) + " " + to_string(spin);
          double previous = 0.0;
          // |F| in pure longitudinal creepage rises monotonically to mu N.
          for (double xi : {1e-4, 1e-3, 1e-2, 0.1, 1.0}) {
            const CreepWear cw = creep_and_wear(g, p, Creepage{xi, 0.0, 0.0}, mu, spin);
            EXPECT_EQ(creep_violation(p, cw, mu), "") << where << " xi " << xi;
            const double f = std::hypot(cw.creep.fx, cw.creep.fy);
            EXPECT_GE(f, previous * (1.0 - 1e-9)) << where << " xi " << xi;
            previous = f;
          }
          for (const Creepage& c : {Creepage{1.0, 0.0, 0.0}, Creepage{0.0, 1.0, 0.0},
                                    Creepage{-1.0, 1.0, 0.0}, Creepage{1.0, 0.0, 10.0},
                                    Creepage{0.0, -1.0, -10.0}, Creepage{0.0, 0.0, 10.0},
                                    Creepage{0.0, 0.0, -10.0}}) {
            const CreepWear cw = creep_and_wear(g, p, c, mu, spin);
            const std::string at = where + " creepage " + std::to_string(c.xi) + " " +
                                   std::to_string(c.eta) + " " + std::to_string(c.phi);
            EXPECT_EQ(creep_violation(p, cw, mu), "") << at;
            const double f = std::hypot(cw.creep.fx, cw.creep.fy);
            if (c.phi == 0.0) {
              // Creepage 1 saturates the whole patch: kFullSlip and |F| = mu N.
              EXPECT_TRUE(cw.creep.status & status::kFullSlip) << at;
              EXPECT_GE(f, 0.99 * mu * p.normal_force) << at;
            }
            if (cw.creep.slip_fraction >= 1.0) {
              EXPECT_TRUE(cw.creep.status & status::kFullSlip) << at;
            }
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace railtab::stability
