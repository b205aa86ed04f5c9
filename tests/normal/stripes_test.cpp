// SPDX-License-Identifier: Apache-2.0
// Tests of STRIPES with the A- and A&B-corrections (src/normal/stripes.cpp).
#include <gtest/gtest.h>

#include <cstdio>

#include <algorithm>
#include <cmath>

#include "normal/hertz.hpp"
#include "normal/normal_model.hpp"
#include "synthetic_geometry.hpp"

namespace railtab {
namespace {

constexpr double kA = 0.5 / 0.46;  // 1/m

struct Extent {
  double length;  // max half-length [m]
  double width;   // lateral half-width [m]
};

Extent extent(const ContactPatch& p) {
  double L = 0.0;
  for (const Strip& s : p.strips) L = std::max(L, s.x_lead);
  const double w = p.strips.back().s + 0.5 * p.strips.back().width - p.strips.front().s +
                   0.5 * p.strips.front().width;
  return {L, 0.5 * w};
}

NormalOptions opts(NormalModel m) {
  NormalOptions o;
  o.model = m;
  return o;
}

// Seed 001 Fig. 2: STRIPES (A-correction) reproduces the Hertz ellipse on the Table 1 cases; Sichani et al. 2014:
// the A-correction gives exactly Hertz's semi-axes. We ask for 2 % at the same 78 kN load.
TEST(Stripes, ACorrectionReproducesHertzOnTable1Cases) {
  const Material steel{210e9, 0.3};
  struct Case {
    double B, step;
  } cases[] = {{0.5 * (0.1 + 1.0 / 0.3), 0.02e-3}, {0.5 * (1.0 / 0.03 + 1.0 / 0.013), 0.005e-3}};
  for (const auto& c : cases)
  for (StripesClosure closure : {StripesClosure::boussinesq, StripesClosure::hertz_peak}) {
    SCOPED_TRACE(closure == StripesClosure::boussinesq ? "boussinesq" : "hertz_peak");
    const auto g = test::hertz_band(kA, c.B, c.step);
    const HertzContact h = hertz_for_force(kA, c.B, 78e3, steel);
    NormalOptions o = opts(NormalModel::stripes_a);
    o.stripes_closure = closure;
    const WheelNormalResult r = solve_normal_for_load(g, 78e3, steel, o);
    ASSERT_TRUE(r.status & status::kConverged) << status::describe(r.status);
    ASSERT_EQ(r.patches.size(), 1u);
    const ContactPatch& p = r.patches[0];
    EXPECT_EQ(p.pressure_shape, StripPressure::parabolic);
    EXPECT_NEAR(r.carried_load / 78e3, 1.0, 1e-7);
    const Extent e = extent(p);
    std::printf("[measured] stripes-a %s B = %.4f 1/m: length %+.2f %% width %+.2f %% area %+.2f %% "
                "peak/(4/3 p0) %+.2f %% approach %+.2f %%\n",
                closure == StripesClosure::boussinesq ? "boussinesq" : "hertz-peak", c.B,
                100 * (e.length / h.a - 1), 100 * (e.width / h.b - 1), 100 * (p.area / h.area - 1),
                100 * (p.max_pressure / (4.0 / 3.0 * h.p0) - 1), 100 * (p.penetration / h.approach - 1));
    EXPECT_NEAR(e.length / h.a, 1.0, 0.02) << "B = " << c.B;
    EXPECT_NEAR(e.width / h.b, 1.0, 0.02) << "B = " << c.B;
    EXPECT_NEAR(p.area / h.area, 1.0, 0.02);
    // Parabolic law: same force and ellipse give 4/3 of the Hertz peak (FACTS 2.4.4).
    EXPECT_NEAR(p.max_pressure / (4.0 / 3.0 * h.p0), 1.0, 0.02);
    EXPECT_NEAR(p.penetration / h.approach, 1.0, 0.01);
    EXPECT_FALSE(p.status & (status::kCurvatureShifted | status::kCurvatureClipped));
  }
}

// Seed 000: the A&B-correction keeps Hertz's length, its width b = n0 sqrt(d/(r0 B0 (1 + (n0/m0)^2)))
// differs from Hertz unless A/B -> 0 or 1. Approach control at the Hertz approach.
TEST(Stripes, ABCorrectionSameLengthDifferentWidth) {
  const Material steel{};
  for (double A_over_B : {1.0, 0.02, 0.3, 5.0}) {
    const double B = kA / A_over_B;
    const auto g = test::hertz_band(kA, B, 0.005e-3, 20e-3);
    const HertzContact h = hertz_for_force(kA, B, 78e3, steel);
    const WheelNormalResult r =
        solve_normal_for_approach(g, h.approach, steel, opts(NormalModel::stripes_ab));
    const Extent e = extent(r.patches.at(0));
    const double m0 = h.coef_a, n0 = h.coef_b, r0 = h.shape.r;
    const double b_ab = n0 * std::sqrt(h.approach / (r0 * B * (1.0 + (n0 / m0) * (n0 / m0))));
    SCOPED_TRACE(A_over_B);
    EXPECT_NEAR(e.length / h.a, 1.0, 0.01);
    EXPECT_NEAR(e.width / b_ab, 1.0, 0.01);
    if (A_over_B == 1.0 || A_over_B == 0.02) {
      EXPECT_NEAR(e.width / h.b, 1.0, 0.01);
    }
    if (A_over_B == 5.0) {
      EXPECT_LT(e.width / h.b, 0.85);  // tread-like B << A: narrower
    }
  }
}

// B <= 0 around the point (conformal): treated, flagged, finite; the A&B patch is wider than Hertz
// would allow and the load is carried.
TEST(Stripes, NegativeCurvatureShiftAndClip) {
  test::BandSpec spec;
  spec.A = kA;
  // Flat-bottomed gap C s^4 with lateral curvatures that are negative near the point (as on a
  // concave tread facing a flatter rail): B(s) = 6 C s^2 - 0.02 1/m.
  const double C = 4e3;
  spec.gap = [C](double s) { return C * s * s * s * s; };
  spec.B_local = [C](double s) { return 6.0 * C * s * s - 0.02; };
  auto g = test::make_band(spec);
  g.points.push_back(test::make_point(0.0, 0.0, kA, -0.02, 0.0));
  const Material steel{};
  for (NegativeCurvature t : {NegativeCurvature::shift, NegativeCurvature::clip_and_smooth}) {
    for (NormalModel m : {NormalModel::stripes_a, NormalModel::stripes_ab}) {
      NormalOptions o = opts(m);
      o.negative_curvature = t;
      const WheelNormalResult r = solve_normal_for_load(g, 80e3, steel, o);
      SCOPED_TRACE(std::string(to_string(m)) + " " + to_string(t));
      ASSERT_TRUE(r.status & status::kConverged) << status::describe(r.status);
      const ContactPatch& p = r.patches[0];
      EXPECT_TRUE(p.status & (t == NegativeCurvature::shift ? status::kCurvatureShifted
                                                            : status::kCurvatureClipped));
      EXPECT_TRUE(p.status & status::kNonHertzian);
      EXPECT_TRUE(std::isfinite(p.area) && p.area > 0.0);
      EXPECT_TRUE(std::isfinite(p.max_pressure) && p.max_pressure > 0.0);
      for (const Strip& s : p.strips) {
        EXPECT_TRUE(std::isfinite(s.x_lead) && std::isfinite(s.pressure_peak));
        EXPECT_TRUE(std::isfinite(s.ellipse_b) && s.ellipse_b >= 0.0);
      }
      EXPECT_NEAR(r.carried_load / 80e3, 1.0, 1e-6);
    }
  }
}

TEST(Stripes, StripsFollowTheContactAngle) {
  // Contact angle varying along the band: STRIPES strips carry their own angle, KP the reference.
  test::BandSpec spec;
  spec.A = kA;
  const double B = 0.5 * (0.1 + 1.0 / 0.3);
  spec.gap = [B](double s) { return B * s * s; };
  spec.B_local = [B](double) { return B; };
  spec.angle_fn = [](double s) { return 0.05 + 5.0 * s; };  // 5 rad/m
  auto g = test::make_band(spec);
  g.points.push_back(test::make_point(0.0, 0.0, kA, B, 0.05));
  const Material steel{};
  const auto st = solve_normal_for_load(g, 78e3, steel, opts(NormalModel::stripes_ab));
  const auto kp = solve_normal_for_load(g, 78e3, steel, opts(NormalModel::kik_piotrowski));
  const auto& ps = st.patches[0].strips;
  // Right wheel: track-frame angle = -side-frame angle.
  EXPECT_NEAR(ps.front().contact_angle, -(0.05 + 5.0 * ps.front().s), 1e-9);
  EXPECT_NEAR(ps.back().contact_angle, -(0.05 + 5.0 * ps.back().s), 1e-9);
  for (const Strip& s : kp.patches[0].strips) EXPECT_DOUBLE_EQ(s.contact_angle, -0.05);
  // Vertical load = sum N_i cos(angle_i) for STRIPES: slightly more normal force than for a plane.
  EXPECT_GT(st.patches[0].normal_force, 78e3 / std::cos(0.05) * (1.0 - 1e-3));
}

}  // namespace
}  // namespace railtab
