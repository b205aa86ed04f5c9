// SPDX-License-Identifier: Apache-2.0
// Tests of the normal model interface (src/normal/normal_model.hpp).
#include "normal/normal_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/check.hpp"
#include "geometry/overlap_reference.hpp"
#include "normal/hertz.hpp"
#include "synthetic_geometry.hpp"

namespace railtab::normal_model_test {  // own namespace: unity builds compile several test files as one
namespace {

constexpr double kA = 0.5 / 0.46;
const NormalModel kModels[] = {NormalModel::hertz, NormalModel::linder,
                               NormalModel::kik_piotrowski, NormalModel::stripes_a,
                               NormalModel::stripes_ab};

NormalOptions opts(NormalModel m) {
  NormalOptions o;
  o.model = m;
  return o;
}

// Non-Hertzian band: B varies across the patch (B(s) = B0 + 6 C s^2), contact angle tilts.
WheelContactGeometry quartic_band() {
  test::BandSpec spec;
  spec.A = kA;
  const double B0 = 0.4, C = 2e4;
  spec.gap = [=](double s) { return B0 * s * s + C * s * s * s * s; };
  spec.B_local = [=](double s) { return B0 + 6.0 * C * s * s; };
  spec.angle_fn = [](double s) { return 0.02 + 3.0 * s; };
  auto g = test::make_band(spec);
  g.points.push_back(test::make_point(0.0, 0.0, kA, B0, 0.02));
  return g;
}

TEST(NormalModel, NamesRoundTrip) {
  for (NormalModel m : kModels) EXPECT_EQ(parse_normal_model(to_string(m)), m);
  EXPECT_THROW(parse_normal_model("contact"), Error);
  EXPECT_EQ(parse_negative_curvature("shift"), NegativeCurvature::shift);
  EXPECT_EQ(parse_negative_curvature(to_string(NegativeCurvature::clip_and_smooth)),
            NegativeCurvature::clip_and_smooth);
}

// Load sweep 1..150 kN: approach increases monotonically and smoothly (no jumps: the second
// difference of the approach on a uniform load grid stays small against the first).
TEST(NormalModel, LoadSweepMonotoneAndSmooth) {
  const Material steel{};
  const WheelContactGeometry geometries[] = {test::hertz_band(kA, 0.5 * (0.1 + 1 / 0.3)),
                                             quartic_band()};
  for (const auto& g : geometries) {
    for (NormalModel m : kModels) {
      SCOPED_TRACE(to_string(m));
      std::vector<double> dz;
      for (double W = 1e3; W <= 150e3 + 1; W += 1e3) {
        const WheelNormalResult r = solve_normal_for_load(g, W, steel, opts(m));
        ASSERT_TRUE(r.status & status::kConverged) << W << " " << status::describe(r.status);
        EXPECT_NEAR(r.carried_load / W, 1.0, 2e-8);
        EXPECT_LE(r.iterations, 30);
        dz.push_back(r.vertical_approach);
      }
      for (std::size_t i = 1; i < dz.size(); ++i) EXPECT_GT(dz[i], dz[i - 1]);
      // delta ~ W^(2/3): smooth in W^(2/3); second differences < 2 % of the first ones.
      for (std::size_t i = 2; i < dz.size(); ++i) {
        const double d1 = dz[i] - dz[i - 1], d0 = dz[i - 1] - dz[i - 2];
        EXPECT_LT(std::abs(d1 - d0), 0.35 * d0) << i;  // (n/(n-1))^(-1/3) - 1 <= 0.21 at n = 2
      }
      // Approach control inverts load control.
      const WheelNormalResult a = solve_normal_for_approach(g, dz[77], steel, opts(m));
      EXPECT_NEAR(a.carried_load / 78e3, 1.0, 1e-7);
    }
  }
}

TEST(NormalModel, HertzModelMatchesHertzFormulas) {
  const Material steel{};
  const double B = 0.5 * (0.1 + 1 / 0.3);
  const auto g = test::hertz_band(kA, B);
  const HertzContact h = hertz_for_force(kA, B, 78e3, steel);
  NormalOptions o = opts(NormalModel::hertz);
  EXPECT_TRUE(solve_normal_for_load(g, 78e3, steel, o).patches.at(0).strips.empty());
  o.hertz_strips = true;
  const auto r = solve_normal_for_load(g, 78e3, steel, o);
  ASSERT_EQ(r.patches.size(), 1u);
  const ContactPatch& p = r.patches[0];
  EXPECT_NEAR(p.semi_axis_a / h.a, 1.0, 1e-7);
  EXPECT_NEAR(p.semi_axis_b / h.b, 1.0, 1e-7);
  EXPECT_NEAR(p.max_pressure / h.p0, 1.0, 1e-7);
  EXPECT_NEAR(p.penetration / h.approach, 1.0, 1e-7);
  EXPECT_NEAR(r.vertical_approach / h.approach, 1.0, 1e-7);
  ASSERT_EQ(p.strips.size(), 50u);
  // Strip sums of the semi-ellipsoid: force within the midpoint-rule error.
  double N = 0.0;
  for (const Strip& s : p.strips) N += 0.5 * std::numbers::pi * s.pressure_peak * s.x_lead * s.width;
  EXPECT_NEAR(N / 78e3, 1.0, 2e-3);
}

// Two patches of one wheel share the rigid approach.
WheelContactGeometry two_wells(double h, double B2) {
  test::BandSpec spec;
  spec.A = kA;
  spec.half_width = 30e-3;
  const double B1 = 1.7;
  spec.gap = [=](double s) {
    return std::min(B1 * (s + 12e-3) * (s + 12e-3), B2 * (s - 12e-3) * (s - 12e-3) + h);
  };
  spec.B_local = [=](double s) { return s < 0.0 ? B1 : B2; };
  auto g = test::make_band(spec);
  g.points.push_back(test::make_point(-12e-3, 0.0, kA, B1, 0.0));
  g.points.push_back(test::make_point(12e-3, h, kA, B2, 0.0));
  g.status = status::kTwoPoint;
  return g;
}

TEST(NormalModel, TwoIdenticalPointsShareEqually) {
  const Material steel{};
  const auto g = two_wells(0.0, 1.7);
  for (NormalModel m : kModels) {
    SCOPED_TRACE(to_string(m));
    const auto r = solve_normal_for_load(g, 100e3, steel, opts(m));
    ASSERT_EQ(r.patches.size(), 2u);
    EXPECT_NEAR(r.patches[0].normal_force / 50e3, 1.0, 1e-6);
    EXPECT_NEAR(r.patches[1].normal_force / 50e3, 1.0, 1e-6);
    EXPECT_TRUE(r.status & status::kTwoPoint);
  }
}

// Two wells of one wheel at +-d (same B), both touching (separation 0 and h2).
WheelContactGeometry wells_at(double d, double h2 = 0.0) {
  test::BandSpec spec;
  spec.A = kA;
  spec.half_width = 30e-3;
  const double B = 1.7;
  spec.gap = [=](double s) { return std::min(B * (s + d) * (s + d), B * (s - d) * (s - d) + h2); };
  spec.B_local = [=](double) { return B; };
  auto g = test::make_band(spec);
  g.points.push_back(test::make_point(-d, 0.0, kA, B, 0.0));
  g.points.push_back(test::make_point(d, h2, kA, B, 0.0));
  g.status = status::kTwoPoint;
  return g;
}

// Two rigid minima inside one continuous overlap region (hump 15 um, approach ~70 um): one patch.
TEST(NormalModel, MinimaInOneOverlapRunAreOnePatch) {
  const Material steel{};
  const auto g = wells_at(3e-3, 1e-6);
  for (NormalModel m : kModels) {
    SCOPED_TRACE(to_string(m));
    const auto r = solve_normal_for_load(g, 100e3, steel, opts(m));
    ASSERT_TRUE(r.status & status::kConverged);
    ASSERT_EQ(r.patches.size(), 1u);
    const ContactPatch& p = r.patches[0];
    EXPECT_FALSE(r.status & status::kTwoPoint);
    EXPECT_EQ(p.points, 2);
    EXPECT_EQ(p.point_index, 0);  // smallest separation
    EXPECT_EQ(r.point_patch, (std::vector<int>{0, 0}));
    EXPECT_NEAR(p.normal_force / 100e3, 1.0, 1e-7);  // flat: normal = vertical
    // Reference: CONTACT's weighted centre of the run, close to the middle (symmetric but for h2).
    // Hertz: the centre of force of its two ellipses (each centred at its point), extent their union.
    const auto refs = overlap_references(g, r.vertical_approach);
    ASSERT_EQ(refs.size(), 1u);
    EXPECT_NEAR(p.band_s, 0.0, 0.3e-3);
    if (m == NormalModel::hertz) {
      EXPECT_LT(p.s_start, -3e-3);  // the ellipses reach beyond their centres at -+3 mm
      EXPECT_GT(p.s_end, 3e-3);
    } else {
      EXPECT_NEAR(p.band_s, refs[0].band_s, 1e-9);
      EXPECT_NEAR(p.s_start, refs[0].s_start, 1e-12);
      EXPECT_NEAR(p.s_end, refs[0].s_end, 1e-12);
    }
    for (std::size_t k = 1; k < p.strips.size(); ++k) EXPECT_GT(p.strips[k].s, p.strips[k - 1].s);
    if (m != NormalModel::hertz) {
      EXPECT_LE(p.strips.front().s - 0.5 * p.strips.front().width, p.strips.back().s);
      EXPECT_GE(p.strips.front().s, p.s_start - 1e-12);
      EXPECT_LE(p.strips.back().s, p.s_end + 1e-12);
    }
  }
}

// Run weights (normal_internal.hpp): a second minimum whose prominence vanishes (here its gap h2
// is 1e-4 below the height where its well stops being a minimum, the fold) carries no share of
// its own, whatever its curvature; with per-point closures its share grew like B^-1/2.
TEST(NormalModel, RunWeightsFadeAVanishingMinimum) {
  const Material steel{};
  const double d = 3e-3, B = 1.7;
  auto g = wells_at(d, 0.9999 * 4.0 * B * d * d);  // fold at h2 = 4 B d^2 (61 um)
  WheelContactGeometry single = g;
  single.points.pop_back();
  single.status = 0;
  for (NormalModel m : {NormalModel::hertz, NormalModel::linder}) {
    SCOPED_TRACE(to_string(m));
    const auto alone = solve_normal_for_load(single, 100e3, steel, opts(m));
    for (double B1 : {B, 1e-4}) {
      g.points[1].curvature_b = B1;
      const auto r = solve_normal_for_load(g, 100e3, steel, opts(m));
      ASSERT_TRUE(r.status & status::kConverged);
      ASSERT_GT(r.vertical_approach, g.points[1].separation);  // the second point is penetrated
      EXPECT_NEAR(r.vertical_approach / alone.vertical_approach, 1.0, 1e-3) << B1;
    }
  }
}

// The reference point equals overlap_references on a tilted, non-Hertzian band; CONTACT's
// combination rule is optional.
TEST(NormalModel, PatchReferenceAndCombination) {
  const Material steel{};
  const auto g = quartic_band();
  for (NormalModel m : kModels) {
    SCOPED_TRACE(to_string(m));
    const auto r = solve_normal_for_load(g, 90e3, steel, opts(m));
    ASSERT_EQ(r.patches.size(), 1u);
    const auto refs = overlap_references(g, r.vertical_approach);
    ASSERT_EQ(refs.size(), 1u);
    const ContactPatch& p = r.patches[0];
    if (m == NormalModel::hertz) {
      // Hertz: the patch is the ellipse centred at the rigid contact point; that is its reference.
      const ContactPoint& cp = g.points[0];
      EXPECT_NEAR(p.band_s, cp.band_s, 1e-12);
      EXPECT_NEAR(p.contact_angle, cp.contact_angle, 1e-12);
      EXPECT_NEAR(p.rail_u, cp.rail_u, 1e-12);
      EXPECT_NEAR(p.wheel_u, cp.wheel_u, 1e-12);
      EXPECT_NEAR(p.rolling_radius, cp.rolling_radius, 1e-12);
    } else {
      EXPECT_NEAR(p.band_s, refs[0].band_s, 1e-9);
      EXPECT_NEAR(p.contact_angle, refs[0].contact_angle, 1e-9);
      EXPECT_NEAR(p.rail_u, refs[0].rail_u, 1e-9);
      EXPECT_NEAR(p.wheel_u, refs[0].wheel_u, 1e-9);
      EXPECT_NEAR(p.rolling_radius, refs[0].rolling_radius, 1e-9);
    }
    // Planar models: one normal, the point's angle; STRIPES strips follow their own angles.
    const bool planar = m != NormalModel::stripes_a && m != NormalModel::stripes_ab;
    EXPECT_NEAR(std::cos(p.contact_angle) * p.normal_force / 90e3, 1.0, planar ? 1e-7 : 1e-4);
  }
  // Wells at +-7 mm: separate runs (hump 83 um above the approach) whose facing ends are < 8 mm
  // apart: two patches by default, one with CONTACT's rule.
  const auto w = wells_at(7e-3);
  for (NormalModel m : kModels) {
    SCOPED_TRACE(to_string(m));
    NormalOptions o = opts(m);
    const auto apart = solve_normal_for_load(w, 100e3, steel, o);
    ASSERT_EQ(apart.patches.size(), 2u);
    EXPECT_EQ(apart.point_patch, (std::vector<int>{0, 1}));
    EXPECT_TRUE(apart.status & status::kTwoPoint);
    o.combine_patches = true;
    const auto joined = solve_normal_for_load(w, 100e3, steel, o);
    ASSERT_EQ(joined.patches.size(), 1u);
    EXPECT_EQ(joined.point_patch, (std::vector<int>{0, 0}));
    EXPECT_NEAR(joined.patches[0].normal_force / 100e3, 1.0, 1e-7);
    EXPECT_NEAR(joined.vertical_approach / apart.vertical_approach, 1.0, 1e-9);
    EXPECT_NEAR(joined.patches[0].area / (apart.patches[0].area + apart.patches[1].area), 1.0, 1e-9);
  }
}

TEST(NormalModel, SeparatedPointLoadsOnlyBeyondItsSeparation) {
  const Material steel{};
  const double h = 40e-6;
  const auto g = two_wells(h, 3.0);
  for (NormalModel m : kModels) {
    SCOPED_TRACE(to_string(m));
    const auto below = solve_normal_for_approach(g, 0.98 * h, steel, opts(m));
    ASSERT_EQ(below.patches.size(), 1u);  // only loaded patches are listed
    EXPECT_GT(below.patches[0].normal_force, 0.0);
    EXPECT_EQ(below.patches[0].point_index, 0);
    ASSERT_EQ(below.point_patch.size(), 2u);
    EXPECT_EQ(below.point_patch[0], 0);
    EXPECT_EQ(below.point_patch[1], -1);
    EXPECT_FALSE(below.status & status::kTwoPoint);
    const auto above = solve_normal_for_approach(g, 1.02 * h, steel, opts(m));
    ASSERT_EQ(above.patches.size(), 2u);  // ascending band s: point 0 at -12 mm, point 1 at +12 mm
    EXPECT_EQ(above.point_patch[0], 0);
    EXPECT_EQ(above.point_patch[1], 1);
    EXPECT_EQ(above.patches[1].point_index, 1);
    EXPECT_LT(above.patches[0].band_s, above.patches[1].band_s);
    EXPECT_GT(above.patches[1].normal_force, 0.0);
    EXPECT_LT(above.patches[1].normal_force, 0.01 * above.patches[0].normal_force);
    EXPECT_TRUE(above.status & status::kTwoPoint);
    // Penetration of each point: (dz - h_i) cos(angle).
    EXPECT_NEAR(above.patches[1].penetration, 0.02 * h, 1e-12);
    // Load control: the second point carries load only when the first one alone cannot.
    const auto light = solve_normal_for_load(g, 10e3, steel, opts(m));
    EXPECT_EQ(light.patches.size(), 1u);
    EXPECT_EQ(light.point_patch[1], -1);
    const auto heavy = solve_normal_for_load(g, 150e3, steel, opts(m));
    ASSERT_EQ(heavy.patches.size(), 2u);
    EXPECT_GT(heavy.patches[heavy.point_patch[1]].normal_force, 0.0);
    EXPECT_NEAR(heavy.carried_load / 150e3, 1.0, 1e-7);
  }
}

TEST(NormalModel, LiftOffAndInvalidInputNeverCrash) {
  const Material steel{};
  const auto g = test::hertz_band(kA, 1.7);
  for (NormalModel m : kModels) {
    for (double W : {0.0, -5e3}) {
      const auto r = solve_normal_for_load(g, W, steel, opts(m));
      EXPECT_TRUE(r.status & status::kLiftOff);
      EXPECT_TRUE(r.patches.empty());
      ASSERT_EQ(r.point_patch.size(), 1u);
      EXPECT_EQ(r.point_patch[0], -1);
    }
    const auto bad = solve_normal_for_load(g, std::nan(""), steel, opts(m));
    EXPECT_TRUE(bad.status & status::kInvalidInput);
    const auto tiny = solve_normal_for_load(g, 1e-9, steel, opts(m));
    EXPECT_TRUE(tiny.status & status::kConverged) << to_string(m);
    EXPECT_TRUE(std::isfinite(tiny.vertical_approach));
    const auto none = solve_normal_for_approach(g, -1e-6, steel, opts(m));
    EXPECT_TRUE(none.status & status::kLiftOff);
  }
  WheelContactGeometry empty;
  EXPECT_TRUE(solve_normal_for_load(empty, 1e3, steel, NormalOptions{}).status & status::kLiftOff);
}

TEST(NormalModel, HertzFallsBackWhereCurvatureIsNotPositive) {
  const Material steel{};
  test::BandSpec spec;
  spec.A = kA;
  spec.gap = [](double s) { return 4e3 * s * s * s * s; };
  spec.B_local = [](double s) { return 2.4e4 * s * s - 0.05; };
  auto g = test::make_band(spec);
  g.points.push_back(test::make_point(0.0, 0.0, kA, -0.05, 0.0));
  const auto r = solve_normal_for_load(g, 50e3, steel, opts(NormalModel::hertz));
  ASSERT_TRUE(r.status & status::kConverged);
  EXPECT_EQ(r.patches[0].model, NormalModel::kik_piotrowski);
  EXPECT_TRUE(r.patches[0].status & status::kFallbackModel);
  EXPECT_TRUE(r.patches[0].status & status::kNonHertzian);
  EXPECT_GT(r.patches[0].area, 0.0);
  // Without a band only clipped-curvature Hertz remains.
  g.band.clear();
  const auto c = solve_normal_for_load(g, 50e3, steel, opts(NormalModel::stripes_ab));
  EXPECT_EQ(c.patches[0].model, NormalModel::hertz);
  EXPECT_TRUE(c.patches[0].status & status::kFallbackModel);
  EXPECT_TRUE(c.patches[0].status & status::kCurvatureClipped);
  EXPECT_TRUE(std::isfinite(c.patches[0].max_pressure));
}

TEST(NormalModel, ExtremeEllipticity) {
  const Material steel{};
  for (double A_over_B : {1e-4, 1e4}) {
    const double B = kA / A_over_B;
    const double step = A_over_B > 1 ? 0.05e-3 : 0.002e-3;
    const auto g = test::hertz_band(kA, B, step, A_over_B > 1 ? 100e-3 : 5e-3);
    for (NormalModel m : kModels) {
      const auto r = solve_normal_for_load(g, 78e3, steel, opts(m));
      SCOPED_TRACE(std::string(to_string(m)) + " " + std::to_string(A_over_B));
      EXPECT_TRUE(r.status & status::kConverged) << status::describe(r.status);
      EXPECT_TRUE(std::isfinite(r.patches[0].max_pressure) && r.patches[0].max_pressure > 0.0);
      EXPECT_TRUE(std::isfinite(r.patches[0].area) && r.patches[0].area > 0.0);
    }
  }
}

}  // namespace
}  // namespace railtab::normal_model_test
