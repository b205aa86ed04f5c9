// SPDX-License-Identifier: Apache-2.0
// overlap_references: weighted patch reference (CONTACT's interpenetration centre) on hand-made
// bands with closed-form answers, and on a synthetic cone/crown pair through the solver.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <numbers>

#include "core/check.hpp"
#include "geometry/contact_geometry.hpp"
#include "geometry/overlap_reference.hpp"
#include "synthetic_profiles.hpp"

namespace railtab {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kR0 = 0.46;  // undeformed radius of the hand-made bands [m]

// A flat rail (q = s, z = 0) under a wheel whose normal gap and angle are given functions of s;
// uniform step h on [s_lo, s_hi].
WheelContactGeometry make_band(const std::function<double(double)>& gap,
                               const std::function<double(double)>& angle, double s_lo, double s_hi,
                               double h = 1e-4, Side side = Side::right) {
  WheelContactGeometry g;
  g.side = side;
  g.band_step = h;
  const long k_lo = std::lround(s_lo / h), k_hi = std::lround(s_hi / h);
  for (long k = k_lo; k <= k_hi; ++k) {
    const double s = static_cast<double>(k) * h;
    BandSample b{};
    b.s = s;
    b.rail_u = 2.0 * s;   // distinguishable from q
    b.wheel_u = 3.0 * s;
    b.q = s;
    b.z = 0.0;
    b.contact_angle_side = angle(s);
    b.gap = gap(s);
    b.rolling_radius = kR0 + 0.1 * s;
    g.band.push_back(b);
  }
  return g;
}

double zero(double) { return 0.0; }

// Parabolic gap s^2/(2 rho) around 0: the overlap is symmetric and the reference is its centre.
// Closed forms of the total weight (R = nominal radius, h = approach):
//   squared: (2 pi/3) sqrt(R rho) h^3,  linear: pi sqrt(R rho) h^2 (volume of the overlap cap).
TEST(OverlapReference, SymmetricOverlapGivesCentreAndClosedFormWeight) {
  const double rho = 0.2, h = 0.1e-3;
  const WheelContactGeometry g = make_band([&](double s) { return s * s / (2 * rho); }, zero, -0.02, 0.02);
  const double half = std::sqrt(2 * rho * h);
  for (OverlapWeighting wt : {OverlapWeighting::squared, OverlapWeighting::linear}) {
    OverlapOptions o;
    o.weighting = wt;
    const auto refs = overlap_references(g, h, o);
    ASSERT_EQ(refs.size(), 1u);
    const OverlapReference& r = refs[0];
    EXPECT_NEAR(r.band_s, 0.0, 1e-12);
    EXPECT_NEAR(r.q, 0.0, 1e-12);
    EXPECT_NEAR(r.rail_u, 0.0, 1e-12);
    EXPECT_NEAR(r.wheel_u, 0.0, 1e-12);
    EXPECT_NEAR(r.contact_angle_side, 0.0, 1e-15);
    // Zero crossings, linear within the cell: off by about h^2/(8 rho s') = 2e-7 m here.
    EXPECT_NEAR(r.s_start, -half, 3e-7);
    EXPECT_NEAR(r.s_end, half, 3e-7);
    EXPECT_NEAR(r.max_overlap, h, 1e-15);
    EXPECT_NEAR(r.overlap, h, 1e-15);
    EXPECT_NEAR(r.rolling_radius, kR0, 1e-12);
    EXPECT_NEAR(r.loaded_rolling_radius, kR0 - h, 1e-12);
    EXPECT_EQ(r.runs, 1);
    EXPECT_FALSE(r.clipped);
    const double root = std::sqrt(o.nominal_radius * rho);
    const double expected = wt == OverlapWeighting::squared ? 2 * kPi / 3 * root * h * h * h : kPi * root * h * h;
    EXPECT_NEAR(r.total_weight / expected, 1.0, 2e-3);
  }
}

// Different curvature either side of the minimum: the centre moves towards the flatter side by
// an amount that tells the weight's exponent. With p = h - s^2/(2 rho) on each side,
//   int s p^e ds = rho h^(e+1)/(e+1),  int p^e ds = sqrt(2 rho h) h^e c_e
// (c_e = 5 pi/32 for e = 5/2, 3 pi/16 for e = 3/2), so the centre is a closed form.
TEST(OverlapReference, WeightIsOverlapPowerIntegratedAlongRolling) {
  const double rho1 = 0.05, rho2 = 0.4, h = 0.1e-3;
  const WheelContactGeometry g = make_band(
      [&](double s) { return s * s / (2 * (s < 0 ? rho1 : rho2)); }, [](double s) { return 0.3 * s; },
      -0.03, 0.03, 2e-5);
  for (OverlapWeighting wt : {OverlapWeighting::squared, OverlapWeighting::linear}) {
    OverlapOptions o;
    o.weighting = wt;
    const double e = wt == OverlapWeighting::squared ? 2.5 : 1.5;
    const double c = wt == OverlapWeighting::squared ? 5 * kPi / 32 : 3 * kPi / 16;
    const double moment = (rho2 - rho1) * std::pow(h, e + 1) / (e + 1);
    const double mass = (std::sqrt(2 * rho1 * h) + std::sqrt(2 * rho2 * h)) * std::pow(h, e) * c;
    const double centre = moment / mass;
    const auto refs = overlap_references(g, h, o);
    ASSERT_EQ(refs.size(), 1u);
    EXPECT_NEAR(refs[0].q, centre, 2e-3 * std::abs(centre)) << static_cast<int>(wt);
    EXPECT_NEAR(refs[0].band_s, centre, 2e-3 * std::abs(centre));
    EXPECT_NEAR(refs[0].contact_angle_side, 0.3 * centre, 2e-3 * 0.3 * std::abs(centre));  // angle linear in s
    // The angle is the weighted average, not the angle at a sample.
    EXPECT_NEAR(refs[0].contact_angle, -refs[0].contact_angle_side, 1e-15);  // right wheel
  }
  // The two exponents give clearly different centres (not a weak test).
  OverlapOptions lin;
  lin.weighting = OverlapWeighting::linear;
  EXPECT_GT(std::abs(overlap_references(g, h)[0].q - overlap_references(g, h, lin)[0].q), 1e-4);
}

// The vertical approach enters as d = dz cos(g) - gap; the weight uses p = d/cos(g) per dy =
// cos(g) ds; loaded radius on a rolled wheel = radius - (dz cos t - gap cos(g - t)).
TEST(OverlapReference, InclinedNormalAndRoll) {
  const double rho = 0.2, h = 0.1e-3, g0 = 0.3, theta = 0.01;
  WheelContactGeometry g =
      make_band([&](double s) { return s * s / (2 * rho); }, [&](double) { return g0; }, -0.02, 0.02);
  g.wheel_roll = theta;
  const auto refs = overlap_references(g, h);
  ASSERT_EQ(refs.size(), 1u);
  const OverlapReference& r = refs[0];
  EXPECT_NEAR(r.band_s, 0.0, 1e-12);
  EXPECT_NEAR(r.max_overlap, h * std::cos(g0), 1e-15);
  EXPECT_NEAR(r.contact_angle_side, g0, 1e-12);
  EXPECT_NEAR(r.loaded_rolling_radius, kR0 - h * std::cos(theta), 1e-12);
  // p = h - gap/cos(g0) over dy = cos(g0) ds: the cap of an effective rho' = rho cos(g0) in s,
  // weighed per s with p^2.5 cos(g0).
  const double expected = 2 * kPi / 3 * std::sqrt(0.46 * rho * std::cos(g0)) * h * h * h * std::cos(g0);
  EXPECT_NEAR(r.total_weight / expected, 1.0, 2e-3);
}

// Two dips of the gap, (|s| - c)^2 / (2 rho): two runs, each symmetric about +-c.
WheelContactGeometry two_dips(double c, double rho, double angle_left, double angle_right) {
  return make_band([=](double s) { return (std::abs(s) - c) * (std::abs(s) - c) / (2 * rho); },
                   [=](double s) { return s < 0 ? angle_left : angle_right; }, -0.04, 0.04);
}

TEST(OverlapReference, SeparatedRunsGiveSeparateReferences) {
  const double rho = 0.1, h = 0.05e-3, c = 0.01;  // half-width 3.2 mm, facing ends 13.7 mm apart
  const WheelContactGeometry g = two_dips(c, rho, 0.02, 0.05);
  for (const OverlapOptions& o : {OverlapOptions{}, contact_patch_rules()}) {
    const auto refs = overlap_references(g, h, o);
    ASSERT_EQ(refs.size(), 2u);
    EXPECT_NEAR(refs[0].band_s, -c, 1e-9);  // ascending s
    EXPECT_NEAR(refs[1].band_s, c, 1e-9);
    EXPECT_NEAR(refs[0].contact_angle_side, 0.02, 1e-12);  // beyond the 12 mm blending distance
    EXPECT_NEAR(refs[1].contact_angle_side, 0.05, 1e-12);
    EXPECT_NEAR(refs[0].total_weight, refs[1].total_weight, 2e-3 * refs[0].total_weight);  // cos(g)
    // Crossings linear within the cell: off by up to h^2/(8 half-width) = 4e-7 m here.
    EXPECT_NEAR(refs[0].s_end, -c + std::sqrt(2 * rho * h * std::cos(0.02)), 5e-7);
    EXPECT_NEAR(refs[1].s_start, c - std::sqrt(2 * rho * h * std::cos(0.05)), 5e-7);
    EXPECT_EQ(refs[0].runs, 1);
    EXPECT_EQ(refs[1].runs, 1);
  }
}

// CONTACT's rules: facing ends within 8 mm combine (weighted position and angle, weights add);
// 8..12 mm apart the angles are blended by (12 - dist)/(12 - 8) towards the combined angle.
TEST(OverlapReference, ContactRulesCombineAndBlendCloseRuns) {
  const double rho = 0.1, h = 0.05e-3, w = std::sqrt(2 * rho * h);  // run half-width 3.16 mm
  {
    const double c = 0.006;  // facing ends 5.7 mm apart
    const WheelContactGeometry g = two_dips(c, rho, 0.02, 0.05);
    const auto apart = overlap_references(g, h);
    ASSERT_EQ(apart.size(), 2u);
    const auto refs = overlap_references(g, h, contact_patch_rules());
    ASSERT_EQ(refs.size(), 1u);
    EXPECT_EQ(refs[0].runs, 2);
    const double w0 = apart[0].total_weight, w1 = apart[1].total_weight;
    EXPECT_NEAR(refs[0].band_s, (-c * w0 + c * w1) / (w0 + w1), 1e-9);
    EXPECT_NEAR(refs[0].contact_angle_side, (0.02 * w0 + 0.05 * w1) / (w0 + w1), 1e-12);
    EXPECT_NEAR(refs[0].contact_angle_side, 0.035, 1e-4);
    EXPECT_NEAR(refs[0].total_weight, w0 + w1, 1e-12 * (w0 + w1));
    EXPECT_NEAR(refs[0].s_start, -c - std::sqrt(2 * rho * h * std::cos(0.02)), 5e-7);
    EXPECT_NEAR(refs[0].s_end, c + std::sqrt(2 * rho * h * std::cos(0.05)), 5e-7);
    EXPECT_NEAR(refs[0].max_overlap, h * std::cos(0.02), 1e-15);
    // Between the runs the rail lies below the wheel: the local overlap is negative there.
    EXPECT_LT(refs[0].overlap, 0.0);
    EXPECT_NEAR(refs[0].overlap, h - c * c / (2 * rho), 1e-6);
  }
  {
    const double c = 0.008;  // facing ends 2 (c - w) = 9.7 mm apart: blend
    const WheelContactGeometry g = two_dips(c, rho, 0.02, 0.05);
    const auto apart = overlap_references(g, h);
    const auto refs = overlap_references(g, h, contact_patch_rules());
    ASSERT_EQ(refs.size(), 2u);
    const double w0 = apart[0].total_weight, w1 = apart[1].total_weight;
    const double comb = (0.02 * w0 + 0.05 * w1) / (w0 + w1);
    const double fac = (12e-3 - (apart[1].s_start - apart[0].s_end)) / 4e-3;
    EXPECT_NEAR(apart[1].s_start - apart[0].s_end, 2 * (c - w), 5e-6);  // w: cos(angle) aside
    EXPECT_NEAR(refs[0].contact_angle_side, 0.02 + fac * (comb - 0.02), 1e-12);
    EXPECT_NEAR(refs[1].contact_angle_side, 0.05 + fac * (comb - 0.05), 1e-12);
    EXPECT_NEAR(refs[0].band_s, -c, 1e-9);  // positions are not blended
  }
}

TEST(OverlapReference, NoApproachNoReference) {
  const WheelContactGeometry g = make_band([](double s) { return s * s / 0.4; }, zero, -0.01, 0.01);
  EXPECT_TRUE(overlap_references(g, 0.0).empty());
  EXPECT_TRUE(overlap_references(g, -1e-4).empty());
  EXPECT_TRUE(overlap_references(WheelContactGeometry{}, 1e-4).empty());
  EXPECT_THROW(overlap_references(g, std::numeric_limits<double>::quiet_NaN()), Error);
  // A band whose gap never closes at this approach.
  const WheelContactGeometry open = make_band([](double) { return 1e-3; }, zero, -0.01, 0.01);
  EXPECT_TRUE(overlap_references(open, 0.5e-3).empty());
}

TEST(OverlapReference, RunAtBandEndIsClipped) {
  const WheelContactGeometry g = make_band([](double s) { return s * s / 0.4; }, zero, 0.0, 0.01);
  const auto refs = overlap_references(g, 1e-4);
  ASSERT_EQ(refs.size(), 1u);
  EXPECT_TRUE(refs[0].clipped);
  EXPECT_DOUBLE_EQ(refs[0].s_start, 0.0);
}

// Through the solver: cone on a circular crown (synthetic_profiles.hpp). The overlap is nearly
// symmetric about the rigid point (its peak moves by dz sin(g0) along s), and the loaded radius
// is the rigid radius minus the approach.
TEST(OverlapReference, ConeOnCrownThroughSolver) {
  ProfilePtr wheel = std::make_shared<testing::ConeWheel>(0.05);
  ProfilePtr rail = std::make_shared<testing::CircleRail>(0.05, 0.04);
  const ContactGeometrySolver solver(wheel, rail, wheel, rail, TrackGeometry{}, WheelsetGeometry{});
  for (Side side : {Side::left, Side::right}) {
    const WheelContactGeometry g = solver.solve_wheel(side, {0.002, 0.0});
    const ContactPoint& p = g.points.at(0);
    const double dz = 0.1e-3;
    const auto refs = overlap_references(g, dz);
    ASSERT_EQ(refs.size(), 1u);
    const OverlapReference& r = refs[0];
    EXPECT_NEAR(r.band_s, 0.0, 2.0 * dz * std::abs(std::sin(p.contact_angle_side)) + 1e-7);
    EXPECT_NEAR(r.contact_angle_side, p.contact_angle_side, 1e-4);
    EXPECT_NEAR(r.contact_angle, p.contact_angle, 1e-4);
    EXPECT_NEAR(r.y_track, p.y_track, 1e-5);
    // ...plus the rail's rise between the rigid point and the reference.
    EXPECT_NEAR(r.loaded_rolling_radius, p.rolling_radius - dz,
                std::abs(std::tan(p.contact_angle_side) * r.band_s) + 1e-8);
    EXPECT_NEAR(r.max_overlap, dz * std::cos(p.contact_angle_side), 1e-8);
    // Half-width of the overlap: gap ~ s^2/(2R) with R = 50 mm.
    EXPECT_NEAR(r.s_end - r.s_start, 2 * std::sqrt(2 * 0.05 * dz), 5e-5);
  }
}

}  // namespace
}  // namespace railtab
