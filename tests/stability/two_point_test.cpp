// SPDX-License-Identifier: Apache-2.0
// 1. Two-point contact (tread + flange root/gauge corner) and the jump into flange contact on
// S1002/UIC60 1:40 (FACTS 8 rows 1-2). The left wheel climbs its flange for y > 0, the right one
// for y < 0; the rigid second point appears at |y| = 4.25 mm, the two contacts are separate patches
// around 4.5 mm, the contact reaches the R13 gauge corner at about 5.25 mm and the rigid point jumps
// onto the 70 deg flange flank at about 6.62 mm.
#include "stability_common.hpp"

namespace railtab::stability {
namespace {

std::vector<Sample> onset_sweep(const Variant& v, Side side) {
  std::vector<double> ys = grid(4.0e-3, 7.5e-3, 0.05e-3);
  for (double& y : ys) y *= outward_sign(side);  // towards this wheel's flange
  return sweep(s1002_uic60(), side, v, ys);
}

// 0.05 mm steps across the whole onset, both wheels, every model: finite, bounded iterations,
// bitwise repeatable, FASTSIM and wear finite with |F| <= mu N on every patch (sweep()); the jump
// onto the flank is flagged (flange contact, reference angle beyond 1 rad at 7.5 mm).
TEST(TwoPoint, FlangeOnsetSweepIsFiniteAndRepeatable) {
  for (const Variant& v : all_variants()) {
    for (Side side : {Side::left, Side::right}) {
      const auto s = onset_sweep(v, side);
      EXPECT_TRUE(s.back().normal.status & status::kFlangeContact) << v.label;
      EXPECT_GT(s.back().summary.max_angle, 1.0) << v.label;
    }
  }
}

// Continuity (stability_common.hpp first_jump: a 0.05 mm step may not exceed 4x the local slope
// from its neighbouring steps + 0.1 % of the sweep's magnitude unless the patch/point count, the
// status bits or the rigid point's contact angle (> 0.05 rad) change there).
TEST(TwoPoint, FlangeOnsetContinuity) {
  for (const Variant& v : variants_named({"hertz", "linder", "kik-piotrowski"}))
    for (Side side : {Side::left, Side::right})
      expect_continuous(onset_sweep(v, side), v.label + " " + to_string(side),
                        v.model != NormalModel::hertz);
}

// KNOWN FAILURE (src/normal, STRIPES, all four variants): after the rigid point jumps onto the flank
// (|y| = 6.615 -> 6.62 mm, flagged by the point angle) the STRIPES solution does not settle in one
// step: N rises 113 kN -> 207 kN over the next 0.08 mm and the vertical approach zig-zags (5 um
// steps: 6.08e-4, 6.24e-4, 6.39e-4, 6.26e-4, 6.38e-4, 6.25e-4 m at 6.700..6.725 mm,
// stripes-a/shift); at 0.05 mm steps this shows as an unflagged jump of the approach between 6.65
// and 6.70 mm (3.98e-4 -> 6.08e-4 m; stripes-a/clip also N 155.8 -> 208.8 kN).
// Normal layer follow-up (src/normal, commit "STRIPES strip A_c as the mean over the strip"): the
// zig-zag was a non-monotone N(delta): the strip lengths jumped by 3x where the straight flank meets
// the flange-root arc (lateral curvature 38 -> 0 1/m across one band cell) and the strips sampled
// A_c at their centres; fixed (A_c averaged over each strip, profile curvature jumps cell-averaged),
// the approach is now smooth at 2-5 um steps. What remains is a steep but smooth transition: after
// the rigid point jumps onto the 70 deg flank at 6.62 mm the rigid wheel lifts at tan(70 deg) per
// unit y, while the STRIPES patch (own angles) stays partly on the conformal R13-in-R13 root for
// ~0.1 mm, so the vertical approach (measured from the rigid position) rises 2e-4 -> 6e-4 m and N
// 113 -> 220 kN within ~0.1 mm. At 0.05 mm steps that follows the exempt jump step and precedes a
// plateau, so the measure still reports it. Still disabled.
// Measure or model? The model (checked after the run weights, stripes-a/shift, left wheel, 78.5 kN,
// 0.025 mm steps): the elastic wheel height z = wheel_drop - vertical_approach is 704, 720, 739 um
// at y = 6.550..6.600 mm (rising with the root contact), then 665, 565, 493, 482 um at 6.625..6.700
// and rises again at the flank's tan(70 deg) from 6.725 mm (529, 603, 686 um). Pushed towards its
// flange, the wheel SINKS by 257 um, although the jump adds the flank as a support: at a fixed load
// more rigid contact can only lift the wheel. So the continuity measure is right to report it and
// the model is wrong here. Not the cause (tried, not kept): the point of the Boussinesq closure.
// With the contact condition at the patch's centre of force (rigid approach dz cos g - gap there)
// instead of at the rigid point, block B moved < 1 % but the wheel still sank 736 -> 498 um. The
// cause is eps, the virtual-penetration fraction STRIPES takes from the rigid point for the whole
// patch: 0.42 / 0.47 at y = 6.575 / 6.600 mm (root point, A0 = 0.88, B0 = 1.25 1/m), 0.23 from
// 6.625 mm on (flank point, A0 = 0.36, B0 = 38.5 1/m). The virtual overlap eps dz cos g - gap of
// the root part of the patch halves at the jump, so the approach must roughly double before the
// root carries the load again. Fix (not done): eps from the patch (e.g. the curvatures at its
// weighted reference) rather than from the rigid point; until then the step is a model defect.
// Tried (s7-eps, 2026-11-26; NOT merged, branch eps-from-patch of /work/s7-eps, commit 06f974b): eps
// as the Hertz eps of the mean curvatures over the rigid overlap r = dz cos g - gap > 0 at the
// current approach, weighted by r (the point's eps on Hertz geometry and as the load vanishes).
// eps is then continuous at the jump (a first variant weighted over the treatment window: stripes-a/
// shift 0.348 -> 0.332 there), this test (all four variants) and WornPairs.DISABLED_StripesFlankJump
// OnHollowWheel pass, and the sink (z max before -> min after the jump, 0.025 mm steps) shrinks:
// stripes-a/shift 739 -> 482 um (257) to 731 -> 612 um (119), stripes-a/clip 211 -> 98,
// stripes-ab/shift 199 -> 66, stripes-ab/clip 177 -> 62 um. Not merged: against CONTACT block C the
// areas and peak pressures improve (stripes-ab 50x20 tread area median 4.9 -> 1.9 %, p_max 31.1 ->
// 28.2 %) but the creep forces get worse (tread median 8.5 -> 10.2 %, flange 5.2 -> 5.5 %;
// ContactEndToEnd direct median of mu N tread 0.0309 -> 0.0331, flange 0.0261 -> 0.0325), and the
// normal solve costs 25-30 % more (the loop over the whole rigid overlap). Numbers and commands:
// that branch's docs/validation/normal.md "eps from the patch".
// New diagnosis: eps is only part of the cause. The virtual overlap eps dz cos g(s) - gap(s) =
// r(s) - (1 - eps) dz cos g(s) (r the rigid overlap at the elastic wheel position) deducts (1 - eps)
// times the approach at the rigid point from every strip. On the flank the rigid wheel lifts at
// tan(70 deg) = 2.75 per unit y, so at a fixed elastic position a root strip (angle ~0.6 rad) gains
// sin g = 0.56 of rigid overlap per unit y and loses (1 - eps) 2.75 cos g (1.5 at eps 0.35): its
// virtual overlap falls for any eps < 0.75, i.e. for any Hertz-based eps, and the wheel sinks until
// the flank carries the load. A full fix needs another elastic-deflection estimate for the strips
// away from the rigid point (e.g. ANALYN's per-strip deflection), not another eps.
TEST(TwoPoint, DISABLED_FlangeOnsetContinuityStripes) {
  for (const Variant& v : variants_named({"stripes-a/shift", "stripes-a/clip", "stripes-ab/shift",
                                          "stripes-ab/clip"}))
    for (Side side : {Side::left, Side::right})
      expect_continuous(onset_sweep(v, side), v.label + " " + to_string(side));
}

// Two patches share the load at |y| = 4.5 mm: kTwoPoint, both loaded, the vertical load carried to
// the load-control tolerance, the flange patch first (band s ascending) at the larger angle, and
// each rigid point paired with its own patch.
TEST(TwoPoint, TwoPatchesShareTheLoad) {
  const ContactGeometrySolver& solver = s1002_uic60();
  for (const Variant& v : all_variants()) {
    for (Side side : {Side::left, Side::right}) {
      const double sigma = outward_sign(side);
      const WheelContactGeometry g = solver.solve_wheel(side, WheelsetState{sigma * 4.5e-3, 0.0});
      ASSERT_EQ(g.points.size(), 2u);
      ASSERT_TRUE(g.status & status::kTwoPoint);
      const WheelNormalResult r = solve_normal_for_load(g, kLoad, Material{}, options_for(v));
      ASSERT_EQ(normal_violation(g, r), "") << v.label;
      ASSERT_EQ(r.patches.size(), 2u) << v.label;
      EXPECT_TRUE(r.status & status::kTwoPoint) << v.label;
      EXPECT_TRUE(r.status & status::kConverged) << v.label;
      for (const ContactPatch& p : r.patches) EXPECT_GT(p.normal_force, 0.0) << v.label;
      EXPECT_NEAR(r.carried_load, kLoad, 2.0 * NormalOptions{}.tolerance * kLoad) << v.label;
      EXPECT_GT(sigma * r.patches[0].contact_angle, sigma * r.patches[1].contact_angle) << v.label;
      EXPECT_NE(r.point_patch[0], r.point_patch[1]) << v.label;
    }
  }
}

// The right pair is the mirror of the left one: the right wheel at -y gives the left wheel's answer
// at +y (forces equal, angles opposite) - the two code paths share everything but sigma.
TEST(TwoPoint, RightWheelMirrorsLeftWheel) {
  const ContactGeometrySolver& solver = s1002_uic60();
  for (const Variant& v : all_variants()) {
    for (double y : {4.5e-3, 5.25e-3, 6.75e-3}) {
      const WheelContactGeometry gl = solver.solve_wheel(Side::left, WheelsetState{y, 0.0});
      const WheelContactGeometry gr = solver.solve_wheel(Side::right, WheelsetState{-y, 0.0});
      const WheelNormalResult rl = solve_normal_for_load(gl, kLoad, Material{}, options_for(v));
      const WheelNormalResult rr = solve_normal_for_load(gr, kLoad, Material{}, options_for(v));
      ASSERT_EQ(rl.patches.size(), rr.patches.size()) << v.label << " y " << y;
      EXPECT_EQ(rl.status, rr.status) << v.label << " y " << y;
      for (std::size_t i = 0; i < rl.patches.size(); ++i) {
        EXPECT_NEAR(rl.patches[i].normal_force, rr.patches[i].normal_force,
                    1e-9 * rl.patches[i].normal_force) << v.label << " y " << y;
        EXPECT_NEAR(rl.patches[i].contact_angle, -rr.patches[i].contact_angle, 1e-12) << v.label;
      }
    }
  }
}

}  // namespace
}  // namespace railtab::stability
