// SPDX-License-Identifier: Apache-2.0
// 3. Concave (negative) relative curvature and 4. near-conformal contact (FACTS 8 rows 3, 5).
#include <numbers>

#include "../normal/synthetic_geometry.hpp"
#include "stability_common.hpp"

namespace railtab::stability {
namespace {

// S1002's tread near y = 0 is concave (R ~ -320 mm at S = 0) against the R300 crown: B at the band
// samples around the contact falls to ~0 or below. Every STRIPES variant treats it and says so:
// shift -> kCurvatureShifted, clip-and-smooth -> kCurvatureClipped (and not the other).
TEST(Concave, StripesFlagTheirTreatmentNearCentre) {
  for (const Variant& v : all_variants()) {
    if (v.model != NormalModel::stripes_a && v.model != NormalModel::stripes_ab) continue;
    for (Side side : {Side::left, Side::right}) {
      for (const Sample& s : sweep(s1002_uic60(), side, v, grid(-0.5e-3, 0.5e-3, 0.25e-3))) {
        const bool shift = v.treatment == NegativeCurvature::shift;
        EXPECT_TRUE(s.normal.status & (shift ? status::kCurvatureShifted : status::kCurvatureClipped))
            << v.label << " y " << s.y;
        EXPECT_FALSE(s.normal.status & (shift ? status::kCurvatureClipped : status::kCurvatureShifted))
            << v.label << " y " << s.y;
      }
    }
  }
}

// A point with B <= 0 (a flat or slightly concave-at-the-point gap, gap = c s^4): Hertz cannot run
// and falls back (kFallbackModel + kNonHertzian); every model returns a finite, loaded answer.
TEST(Concave, HertzFallsBackWhenBIsNotPositive) {
  for (double B0 : {0.0, -0.5, -1e-9}) {
    test::BandSpec spec;
    spec.step = 0.05e-3;
    spec.half_width = 30e-3;
    const double c = 2e3;  // [1/m^3]: gap 1.6 um at 5 mm
    spec.gap = [c](double s) { return c * s * s * s * s; };
    spec.B_local = [c](double s) { return 6.0 * c * s * s; };  // gap''/2
    WheelContactGeometry g = test::make_band(spec);
    g.points.push_back(test::make_point(0.0, 0.0, spec.A, B0, 0.0));
    g.points.front().status = status::kNonHertzian;
    for (const Variant& v : all_variants()) {
      const WheelNormalResult r = solve_normal_for_load(g, kLoad, Material{}, options_for(v));
      EXPECT_EQ(normal_violation(g, r), "") << v.label << " B0 " << B0;
      EXPECT_TRUE(r.status & status::kConverged) << v.label << " B0 " << B0;
      EXPECT_NEAR(r.carried_load, kLoad, 1e-6 * kLoad) << v.label;
      EXPECT_TRUE(r.status & status::kNonHertzian) << v.label << " B0 " << B0;
      if (v.model == NormalModel::hertz) {
        EXPECT_TRUE(r.status & status::kFallbackModel) << "B0 " << B0;
      }
      EXPECT_TRUE(bitwise_equal(r, solve_normal_for_load(g, kLoad, Material{}, options_for(v))));
      for (const ContactPatch& p : r.patches) {
        const CreepWear cw = creep_and_wear(g, p, Creepage{1e-3, 1e-3, 0.5});
        EXPECT_EQ(creep_violation(p, cw, 0.3), "") << v.label;
      }
    }
  }
}

// A worn-like wheel: S1002 with its tread replaced, from u = -10 mm to the field side, by a hollow
// arc of radius R = 301.5 mm tangent to S1002 at -10 mm (value and slope continuous; the curvature
// jumps there, as at S1002's own joints). Where its slope meets the inclined R300 crown the contact
// is nearly conformal: B = (1/300 - 1/301.5)/2 = 0.0083 1/m, below the STRIPES floor.
class WornWheel final : public Profile {
 public:
  explicit WornWheel(double radius)
      : Profile("S1002 worn", ProfileKind::wheel, kS1002UMin, kS1002UMax),
        base_(make_s1002_profile()),
        r_(radius) {
    const ProfileSample j = base_->eval(kJoint);
    // z = z0 + sqrt(R^2 - (u - uc)^2) - R, slope -(u - uc)/sqrt(...) = j.dz at the joint.
    uc_ = kJoint + j.dz * r_ / std::sqrt(1.0 + j.dz * j.dz);
    z0_ = j.z - (std::sqrt(r_ * r_ - (kJoint - uc_) * (kJoint - uc_)) - r_);
  }

 protected:
  ProfileSample eval_unchecked(double u) const override {
    if (u < kJoint) return base_->eval(u);
    const double d = u - uc_;
    const double w = std::sqrt(r_ * r_ - d * d);
    return {z0_ + w - r_, -d / w, -r_ * r_ / (w * w * w)};
  }

 private:
  static constexpr double kJoint = -0.010;
  ProfilePtr base_;
  double r_, uc_ = 0.0, z0_ = 0.0;
};

TEST(NearConformal, WornTreadIsFiniteAndFlagged) {
  const ProfilePtr wheel = std::make_shared<WornWheel>(0.3015);
  const ProfilePtr rail = make_uic60_profile();
  const ContactGeometrySolver solver(wheel, rail, wheel, rail, TrackGeometry{}, WheelsetGeometry{});
  // Near-conformal indeed: B at the primary point gets tiny inside the swept range.
  double b_min = 1e9;
  for (double y : grid(-2e-3, 2e-3, 0.25e-3))
    b_min = std::min(b_min, std::abs(solver.solve_wheel(Side::left, WheelsetState{y, 0.0})
                                         .points.front().curvature_b));
  EXPECT_LT(b_min, 0.02);  // below the STRIPES floor 0.02 A ~ 0.02 1/m somewhere
  for (const Variant& v : all_variants()) {
    for (Side side : {Side::left, Side::right}) {
      // Finite, bounded, repeatable, FASTSIM with spin on the wide conformal patch (sweep()).
      const auto s = sweep(solver, side, v, grid(-2e-3, 2e-3, 0.25e-3), 0.0, kLoad,
                           Creepage{2e-3, 1e-3, 1.0});
      for (const Sample& x : s) {
        EXPECT_FALSE(x.normal.patches.empty()) << v.label << " y " << x.y;
        // Converged, or a clear flag when not.
        EXPECT_TRUE(x.normal.status & (status::kConverged | status::kNotConverged));
        // STRIPES must treat (and flag) a point whose B is below its floor min_curvature_ratio*A.
        const ContactPoint& p0 = x.geometry.points.front();
        const bool below = p0.curvature_b < NormalOptions{}.min_curvature_ratio * p0.curvature_a;
        if ((v.model == NormalModel::stripes_a || v.model == NormalModel::stripes_ab) && below) {
          EXPECT_TRUE(x.normal.status & (status::kCurvatureShifted | status::kCurvatureClipped))
              << v.label << " y " << x.y;
        }
      }
    }
  }
}

}  // namespace
}  // namespace railtab::stability
