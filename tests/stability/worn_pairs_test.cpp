// SPDX-License-Identifier: Apache-2.0
// Worn profiles through every normal model (docs/validation/worn-profiles.md): the measured worn
// high rail site_b_hr.prr (CONTACT testbank, overhanging gauge face; tests/data/profiles), a
// hollow-worn S1002 wheel built here (a 1.5 mm deep, 25 mm wide wear groove on the tread, the shape
// that gives two near-equal gap minima), and the measured MiniProf wheel Car7216_0001r.whl with the
// averaged high rail avg_HR.BAN (CONTACT testbank), paired with each other and with the new
// profiles. Each sweep in y: every result finite and bitwise repeatable, FASTSIM and wear within
// |F| <= mu N (sweep()), and the forces, approach and area continuous in y except where the
// patch/point count, the status flags or the contact angle change (expect_continuous).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "profile/formats/profile_io.hpp"
#include "profile/curves/spline_profile.hpp"
#include "stability_common.hpp"

namespace railtab::stability {
namespace {

ProfilePtr data_profile(const char* name, ProfileKind kind, double smoothing_length = 0.0) {
  return read_profile(std::filesystem::path(RAILTAB_SOURCE_DIR) / "tests" / "data" / "profiles" / name,
                      kind, smoothing_length);
}

ProfilePtr site_b_rail() {
  static const ProfilePtr rail = data_profile("site_b_hr.prr", ProfileKind::rail);
  return rail;
}

// Measured MiniProf pair of CONTACT's testbank, a worn wheel and an averaged high rail, raw from
// the instrument: smoothed with L_filt = 2 mm as docs/profiles.md advises for such data.
constexpr double kMiniProfSmoothing = 2e-3;
ProfilePtr car7216_wheel() {
  static const ProfilePtr wheel = data_profile("Car7216_0001r.whl", ProfileKind::wheel, kMiniProfSmoothing);
  return wheel;
}
ProfilePtr avg_hr_rail() {
  static const ProfilePtr rail = data_profile("avg_HR.BAN", ProfileKind::rail, kMiniProfSmoothing);
  return rail;
}

// S1002 with a Gaussian wear groove (depth 1.5 mm, 1/e half-width 12.5 mm) centred 5 mm to the
// field side of the running circle: a hollow tread with a false flange on its field side.
ProfilePtr hollow_worn_s1002() {
  static const ProfilePtr wheel = [] {
    const ProfilePtr s1002 = make_s1002_profile();
    std::vector<double> u, z;
    for (int i = 0; i <= 258; ++i) {
      const double x = -69e-3 + 0.5e-3 * i;  // to +60 mm
      const double d = (x - 5e-3) / 12.5e-3;
      u.push_back(x);
      z.push_back(s1002->eval(x).z + 1.5e-3 * std::exp(-d * d));
    }
    return std::make_shared<const SplineProfile>("S1002-hollow", ProfileKind::wheel, u, z);
  }();
  return wheel;
}

struct Pair {
  const char* label;
  ProfilePtr wheel;
  ProfilePtr rail;
};

std::vector<Pair> worn_pairs() {
  return {{"S1002 / site_b_hr", make_s1002_profile(), site_b_rail()},
          {"hollow S1002 / UIC60", hollow_worn_s1002(), make_uic60_profile()},
          {"hollow S1002 / site_b_hr", hollow_worn_s1002(), site_b_rail()},
          {"Car7216 / avg_HR", car7216_wheel(), avg_hr_rail()},
          {"Car7216 / UIC60", car7216_wheel(), make_uic60_profile()}};
}

const std::vector<double>& sweep_ys() {
  static const std::vector<double> ys = grid(-5e-3, 9e-3, 0.05e-3);  // the step first_jump is made for
  return ys;
}

// Continuity that does not hold yet (the DISABLED tests below say what fails).
bool known_stripes_flank_jump(const Pair& pair, const Variant& v) {
  return std::string(pair.label) == "hollow S1002 / UIC60" && v.label == "stripes-a/shift";
}
bool measured_miniprof_pair(const Pair& pair) { return std::string(pair.label).starts_with("Car7216"); }

TEST(WornPairs, EveryModelFiniteRepeatableAndContinuous) {
  for (const Pair& pair : worn_pairs()) {
    const ContactGeometrySolver solver(pair.wheel, pair.rail, pair.wheel, pair.rail, TrackGeometry{},
                                       WheelsetGeometry{});
    for (const Variant& v : all_variants()) {
      const std::vector<Sample> s = sweep(solver, Side::left, v, sweep_ys());  // finite, repeatable
      if (known_stripes_flank_jump(pair, v) || measured_miniprof_pair(pair)) continue;
      expect_continuous(s, std::string(pair.label) + " " + v.label, v.model != NormalModel::hertz);
    }
  }
}

// KNOWN FAILURE (src/normal, STRIPES; the same as TwoPoint.DISABLED_FlangeOnsetContinuityStripes,
// whose S1002 flange the hollow-worn wheel keeps): after the rigid point jumps onto the 70 deg
// flange flank, stripes-a/shift's vertical approach jumps unflagged between y = 6.65 and 6.70 mm
// (0.361 -> 0.503 mm) on the hollow S1002 / UIC60 pair. Every other model and pair passes.
// Passes with STRIPES' eps from the patch (s7-eps, branch eps-from-patch, not merged: creep forces
// further from CONTACT, slower; two_point_test.cpp has the numbers and the remaining cause).
TEST(WornPairs, DISABLED_StripesFlankJumpOnHollowWheel) {
  for (const Pair& pair : worn_pairs()) {
    const ContactGeometrySolver solver(pair.wheel, pair.rail, pair.wheel, pair.rail, TrackGeometry{},
                                       WheelsetGeometry{});
    for (const Variant& v : all_variants()) {
      if (!known_stripes_flank_jump(pair, v)) continue;
      expect_continuous(sweep(solver, Side::left, v, sweep_ys()), std::string(pair.label) + " " + v.label);
    }
  }
}

// Measured MiniProf pairs (Car7216, smoothed 2 mm), 0.05 mm steps: continuity in y except where
// the character changes (character_change) or the geometry flags near_equal_minima (the primary
// point may jump: the tread-to-flange takeover at y = 5.25 mm, where the point jumps 37.5 mm
// (avg_HR) and 24.3 mm (UIC60), and the tread jumps between near-equal minima) or curvature_step
// (B at the point steps: UIC60's R300/R80 transition, below). Without the flag exemptions the
// transition fails for Hertz, Linder and STRIPES with the shift (refined: the approach and area
// steps keep their size). The flange takeover's load transfer (130 -> 162 kN between y = 5.30 and
// 5.35 mm for Hertz on avg_HR), which the neighbour measure alone reported for every model, is
// linear at 1/32 of the step (kept sub-step 0.033 of the step): steep, not a jump.
// Formerly known failures, fixed:
// - Car7216 / UIC60 hertz, linder (and stripes-a/shift, stripes-ab/shift there), y = -0.10 ->
//   -0.05 mm: ONE rigid point (no second minimum within 0.5 mm) crosses the UIC60 R300/R80 radius
//   transition (rail u -10.519 -> -10.494 mm); B steps 11.5 -> 6.9 1/m, so Hertz's approach
//   (0.1143 -> 0.1078 mm) and Linder's area (94.8 -> 84.6 mm2) step. A point model is
//   discontinuous there by construction (constant curvature at the point): the geometry now
//   flags curvature_step on the samples within half a band step of the transition (y = -0.15 ..
//   0.00 mm here), and the step is exempt as a flagged jump.
// - Car7216 / avg_HR linder, kik-piotrowski: the area stepped 1.3 % (84.40 -> 83.30 mm2, Linder)
//   between y = -2.510 and -2.505 mm with the rigid points and the approach continuous: a
//   vanishing second point (weight 0.003) 3.7 mm from the primary one split the band domains at
//   the largest-gap sample, the primary's run ended at that sample and the cell beyond it belonged
//   to no run; when the saddle passed a sample the run lost a 0.1 mm cell of overlap. Fixed in
//   src/normal (normal_model.cpp, normal_band.cpp): the planar runs end at the continuous saddle.
// - Car7216 / UIC60 stripes-a/clip, stripes-a/shift, stripes-ab/shift, stripes-ab/clip (N,
//   lateral force, approach +2 % between y = 8.90 and 8.95 mm, stripes-a/shift also N 138.5 ->
//   141.6 kN between 8.65 and 8.70 mm) and Car7216 / avg_HR stripes-ab/shift (area 78.89 ->
//   79.13 mm2 between 4.95 and 5.00 mm) were failures of the measure, not of the models: smooth,
//   steep changes next to an extremum or an exempt step, where the neighbour-slope test has no
//   slope to compare (the relaxation of the STRIPES patch after the second rigid point vanishes in
//   a fold at y = 8.857 mm; the second minimum forming at 8.71 mm; a band-sampling wobble of the
//   curvature shift). Every suspected step is now confirmed by refinement (refine below,
//   refined_jump in stability_common.hpp): refined to 1/32 of the step (1.6 um) the kept sub-step
//   is 0.038 .. 0.047 of the step for the UIC60 ones and 0.070 for the avg_HR area (a jump keeps
//   > 0.37), so all 14 combinations pass. Continuity is not plausibility: in the exempt step where
//   the second point vanishes (8.850 -> 8.875 mm) the wheel height wheel_drop - approach FALLS by
//   43 um (stripes-a/shift; 22 um stripes-a/clip) while the wheel is pushed towards its flange
//   (25 um steps, measured once, not asserted) - the kind of defect TwoPoint's STRIPES test found.
TEST(WornPairs, MeasuredMiniProfPairContinuity) {
  for (const Pair& pair : worn_pairs()) {
    if (!measured_miniprof_pair(pair)) continue;
    const ContactGeometrySolver solver(pair.wheel, pair.rail, pair.wheel, pair.rail, TrackGeometry{},
                                       WheelsetGeometry{});
    for (const Variant& v : all_variants()) {
      const NormalOptions o = options_for(v);
      auto refine = [&](double y) {  // a suspected step is confirmed by refinement (first_jump)
        const WheelContactGeometry g = solver.solve_wheel(Side::left, WheelsetState{y, 0.0});
        return summarise(g, solve_normal_for_load(g, kLoad, Material{}, o));
      };
      expect_continuous(sweep(solver, Side::left, v, sweep_ys()), std::string(pair.label) + " " + v.label,
                        v.model != NormalModel::hertz, kExemptNearEqualMinima, refine);
    }
  }
}

// The refinement that confirms a suspected step (first_jump + refined_jump) still catches a real
// model discontinuity: Hertz's approach on Car7216 / UIC60 steps 0.1143 -> 0.1078 mm between
// y = -0.10 and -0.05 mm where the single rigid point crosses UIC60's R300/R80 transition (a
// point model is discontinuous there by construction). With the curvature_step exemption ignored
// the refined measure reports that step; with it the sweep passes.
TEST(WornPairs, RefinementCatchesTheCurvatureStepJump) {
  const ContactGeometrySolver solver(car7216_wheel(), make_uic60_profile(), car7216_wheel(),
                                     make_uic60_profile(), TrackGeometry{}, WheelsetGeometry{});
  const NormalOptions o = options_for(all_variants().front());  // hertz
  ASSERT_EQ(o.model, NormalModel::hertz);
  auto at = [&](double y) {
    const WheelContactGeometry g = solver.solve_wheel(Side::left, WheelsetState{y, 0.0});
    return summarise(g, solve_normal_for_load(g, kLoad, Material{}, o));
  };
  const std::vector<double> ys = grid(-0.4e-3, 0.3e-3, 0.05e-3);
  std::vector<Summary> s;
  std::vector<double> q;
  for (double y : ys) {
    s.push_back(at(y));
    q.push_back(s.back().approach);
  }
  auto changes = [](const Summary& a, const Summary& b) { return character_change(a, b); };
  auto confirm = [&](int k) {
    return refined_jump([&](double y) { return at(y).approach; }, ys[k], ys[k + 1],
                        [&](double a, double b) { return changes(at(a), at(b)); });
  };
  const int k = first_jump(q, [&](int j) { return changes(s[j], s[j + 1]); }, confirm);
  ASSERT_GE(k, 0) << "the R300/R80 step is not caught";
  EXPECT_NEAR(ys[k], -0.10e-3, 1e-9);
  EXPECT_GT(std::abs(q[k + 1] - q[k]), 5e-6);  // [m], the 6.5 um step of the approach
  std::printf("[ info ] caught: approach %.5f -> %.5f mm between y = %.2f and %.2f mm\n", q[k] * 1e3,
              q[k + 1] * 1e3, ys[k] * 1e3, ys[k + 1] * 1e3);
  auto flagged = [&](int j) {
    return changes(s[j], s[j + 1]) || s[j].curvature_step || s[j + 1].curvature_step;
  };
  EXPECT_EQ(first_jump(q, flagged, confirm), -1);
}

// Measured worn profiles, hollow-worn treads: the primary rigid contact point moves continuously in
// y except where the geometry flags near_equal_minima. A step of the sweep in which the primary
// point moves more than 1 mm (on the rail, side frame) is a jump; at least one of its two samples
// must carry the flag (it is set where a second point would become primary within a 0.1 mm shift).
// The sweeps hold 12 such jumps (up to 53 mm: hollow-tread minima and flange takeovers; without the
// flag, i.e. near_equal_shift = 0, each one fails). The flag must also stay specific: at most a
// quarter of the samples carry it (42 of 1405 do).
TEST(WornPairs, PrimaryPointJumpsAreFlagged) {
  constexpr double kJump = 1e-3;  // [m]; continuous motion is <= 0.52 mm per 0.05 mm step here
  int jumps = 0, flagged_samples = 0, samples = 0;
  for (const Pair& pair : worn_pairs()) {
    const ContactGeometrySolver solver(pair.wheel, pair.rail, pair.wheel, pair.rail, TrackGeometry{},
                                       WheelsetGeometry{});
    WheelContactGeometry prev;
    for (std::size_t k = 0; k < sweep_ys().size(); ++k) {
      const double y = sweep_ys()[k];
      WheelContactGeometry g = solver.solve_wheel(Side::left, WheelsetState{y, 0.0});
      const bool flagged = (g.status & status::kNearEqualMinima) != 0;
      ++samples;
      flagged_samples += flagged ? 1 : 0;
      if (flagged) {  // the flag is on the wheel, the primary point and the point it competes with
        EXPECT_GE(g.points.size(), 2u);
        EXPECT_TRUE(g.points.front().status & status::kNearEqualMinima);
      }
      if (k > 0) {
        const ContactPoint& a = prev.points.front();
        const ContactPoint& b = g.points.front();
        const double moved = std::hypot(b.y_track - a.y_track, b.z_track - a.z_track);
        if (moved > kJump) {
          ++jumps;
          EXPECT_TRUE((prev.status | g.status) & status::kNearEqualMinima)
              << pair.label << ": the primary point jumps " << moved * 1e3 << " mm between y = "
              << sweep_ys()[k - 1] * 1e3 << " and " << y * 1e3 << " mm without near_equal_minima";
        }
      }
      prev = std::move(g);
    }
  }
  EXPECT_GE(jumps, 5);  // the sweeps do cross hollow-tread and flange-onset jumps
  EXPECT_LT(flagged_samples, samples / 4) << flagged_samples << " of " << samples << " samples flagged";
  std::printf("[ info ] %d jumps of the primary point, %d of %d samples flagged near_equal_minima\n",
              jumps, flagged_samples, samples);
}

// B at the primary rigid point steps only where the geometry flags curvature_step (a profile
// radius transition within half a band step of the point): along each sweep, B is continuous
// by the measure of the continuity tests (first_jump) once the steps where the point jumps
// (> 1 mm, PrimaryPointJumpsAreFlagged), the point count changes, near_equal_minima or
// curvature_step is set are exempt. Without the curvature_step exemption the Car7216 / UIC60
// sweep fails (B 11.5 -> 6.9 1/m where the point crosses UIC60's R300/R80 transition), so the flag
// is what passes it. The flag stays specific: at most 5 % of the samples carry it.
TEST(WornPairs, CurvatureStepsAreFlagged) {
  int unflagged_fails = 0, flagged_samples = 0, samples = 0;
  std::vector<Pair> pairs = worn_pairs();
  pairs.push_back({"S1002 / UIC60", make_s1002_profile(), make_uic60_profile()});
  for (const Pair& pair : pairs) {
    const ContactGeometrySolver solver(pair.wheel, pair.rail, pair.wheel, pair.rail, TrackGeometry{},
                                       WheelsetGeometry{});
    std::vector<WheelContactGeometry> g;
    std::vector<double> b;
    for (double y : sweep_ys()) {
      g.push_back(solver.solve_wheel(Side::left, WheelsetState{y, 0.0}));
      b.push_back(g.back().points.front().curvature_b);
      const bool flagged = (g.back().status & status::kCurvatureStep) != 0;
      ++samples;
      flagged_samples += flagged ? 1 : 0;
      if (flagged) {  // on the wheel and on at least one point
        bool on_point = false;
        for (const ContactPoint& p : g.back().points) on_point = on_point || (p.status & status::kCurvatureStep);
        EXPECT_TRUE(on_point) << pair.label << " y = " << y * 1e3 << " mm";
      }
    }
    auto exempt = [&](int k, StatusBits flags) {
      const ContactPoint& p = g[k].points.front();
      const ContactPoint& q = g[k + 1].points.front();
      return g[k].points.size() != g[k + 1].points.size() ||
             std::hypot(q.y_track - p.y_track, q.z_track - p.z_track) > 1e-3 ||
             ((g[k].status | g[k + 1].status) & flags) != 0;
    };
    const int k = first_jump(b, [&](int j) {
      return exempt(j, status::kNearEqualMinima | status::kCurvatureStep);
    });
    EXPECT_EQ(k, -1) << pair.label << ": B at the primary point steps " << b[k < 0 ? 0 : k] << " -> "
                     << b[k < 0 ? 0 : k + 1] << " 1/m between y = " << sweep_ys()[k < 0 ? 0 : k] * 1e3
                     << " and " << sweep_ys()[k < 0 ? 0 : k + 1] * 1e3 << " mm without curvature_step";
    if (first_jump(b, [&](int j) { return exempt(j, status::kNearEqualMinima); }) >= 0) ++unflagged_fails;
  }
  EXPECT_GE(unflagged_fails, 1);  // Car7216 / UIC60 crosses the R300/R80 transition
  EXPECT_LT(flagged_samples, samples / 20) << flagged_samples << " of " << samples << " samples flagged";
  std::printf("[ info ] %d sweeps fail without the flag, %d of %d samples flagged curvature_step\n",
              unflagged_fails, flagged_samples, samples);
}

// Leaving the tread is flagged: the flange contact on the worn gauge face carries kFlangeContact
// and the two-point phase before it kTwoPoint (the sweep reaches the conformal 70 deg flank).
TEST(WornPairs, DomainLimitsAreFlagged) {
  const ContactGeometrySolver solver(hollow_worn_s1002(), site_b_rail(), hollow_worn_s1002(),
                                     site_b_rail(), TrackGeometry{}, WheelsetGeometry{});
  StatusBits seen = 0;
  for (double y : sweep_ys()) {
    const WheelContactGeometry g = solver.solve_wheel(Side::left, WheelsetState{y, 0.0});
    for (const ContactPoint& p : g.points) seen |= p.status;
    seen |= g.status;
  }
  EXPECT_TRUE(seen & status::kFlangeContact);
  EXPECT_TRUE(seen & status::kTwoPoint);
}

}  // namespace
}  // namespace railtab::stability
