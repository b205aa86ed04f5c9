// SPDX-License-Identifier: Apache-2.0
// Tests of the track a simulated wheelset runs on (src/vehicle/track_layout.hpp).
#include "vehicle/track_layout.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/check.hpp"
#include "error_message.hpp"

namespace railtab::vehicle {
namespace {

std::string error_of(const std::vector<TrackSection>& sections, Irregularity irregularity = {}) {
  return test::error_message([&] { TrackLayout layout(sections, irregularity); });
}

TEST(TrackLayout, CurvatureAndCantRampLinearlyThroughTransitions) {
  // Tangent 50 m, transition 40 m into a left curve R = 400 m with 0.12 m cant, curve 100 m.
  const double k = 1.0 / 400.0;
  const TrackLayout track({{50, 0, 0, 0, 0}, {40, 0, k, 0, 0.12}, {100, k, k, 0.12, 0.12}}, {});
  EXPECT_DOUBLE_EQ(track.length(), 190.0);
  EXPECT_EQ(track.at(25.0).curvature, 0.0);
  EXPECT_NEAR(track.at(60.0).curvature, 0.25 * k, 1e-15);
  EXPECT_NEAR(track.at(60.0).curvature_rate, k / 40.0, 1e-15);
  EXPECT_NEAR(track.at(60.0).cant_angle, std::asin(0.03 / 1.5), 1e-15);
  EXPECT_NEAR(track.at(150.0).curvature, k, 1e-15);
  EXPECT_EQ(track.at(150.0).curvature_rate, 0.0);
  // Clamped beyond both ends.
  EXPECT_NEAR(track.at(1e6).cant_angle, std::asin(0.12 / 1.5), 1e-15);
  EXPECT_EQ(track.at(-5.0).curvature, 0.0);
}

TEST(TrackLayout, CantInARightCurvePullsGravityTowardsMinusY) {
  const TrackLayout left({{10, 0.002, 0.002, 0.1, 0.1}}, {});
  const TrackLayout right({{10, -0.002, -0.002, 0.1, 0.1}}, {});
  EXPECT_GT(left.at(5).cant_angle, 0.0);  // right rail raised: gravity pulls towards +y
  EXPECT_NEAR(right.at(5).cant_angle, -left.at(5).cant_angle, 1e-15);
}

TEST(TrackLayout, ReverseTransitionTurnsTheCantOverThroughZero) {
  // Left curve R = 500 m with 0.1 m cant into a right curve R = 250 m with 0.15 m cant.
  const TrackLayout track({{60, 0.002, -0.004, 0.1, 0.15}}, {});
  EXPECT_NEAR(track.at(0).cant_angle, std::asin(0.1 / 1.5), 1e-15);
  EXPECT_NEAR(track.at(60).cant_angle, -std::asin(0.15 / 1.5), 1e-15);
  EXPECT_NEAR(track.at(24).cant_angle, 0.0, 1e-15);  // signed cant 0.1 - 0.4 * 0.25 = 0
  // A transition out of a right curve keeps the left rail up until the cant is gone.
  const TrackLayout exit({{40, -0.004, 0.0, 0.15, 0.0}}, {});
  EXPECT_NEAR(exit.at(20).cant_angle, -std::asin(0.075 / 1.5), 1e-15);
}

TEST(TrackLayout, IrregularityReachesItsAmplitudeAndDependsOnlyOnTheSeed) {
  Irregularity irr;
  irr.amplitude = 4e-3;
  irr.seed = 7;
  const TrackLayout a({{300, 0, 0, 0, 0}}, irr);
  const TrackLayout b({{300, 0, 0, 0, 0}}, irr);
  irr.seed = 8;
  const TrackLayout c({{300, 0, 0, 0, 0}}, irr);
  double largest = 0.0, difference = 0.0;
  for (double s = 0.0; s <= 300.0; s += 0.25) {
    largest = std::max(largest, std::abs(a.at(s).lateral_irregularity));
    EXPECT_EQ(a.at(s).lateral_irregularity, b.at(s).lateral_irregularity);
    difference = std::max(difference,
                          std::abs(a.at(s).lateral_irregularity - c.at(s).lateral_irregularity));
  }
  EXPECT_NEAR(largest, 4e-3, 1e-15);
  EXPECT_GT(difference, 1e-3);
  // Between samples it may exceed the amplitude, but only by the sampling error.
  for (double s = 0.0; s <= 300.0; s += 0.01) {
    EXPECT_LT(std::abs(a.at(s).lateral_irregularity), 4e-3 * 1.01);
  }
}

TEST(TrackLayout, BadInputsThrowNamingTheProblem) {
  EXPECT_NE(error_of({}).find("empty route"), std::string::npos);
  EXPECT_NE(error_of({{std::nan(""), 0, 0, 0, 0}}).find("length"), std::string::npos);
  EXPECT_NE(error_of({{-3, 0, 0, 0, 0}}).find("length"), std::string::npos);
  EXPECT_NE(error_of({{10, INFINITY, 0, 0, 0}}).find("curvature"), std::string::npos);
  EXPECT_NE(error_of({{10, 0, 0, 0.1, 0.1}}).find("without curvature"), std::string::npos);
  EXPECT_NE(error_of({{10, 0.002, 0.002, 2.0, 2.0}}).find("rail centre distance"),
            std::string::npos);
  Irregularity irr;
  irr.amplitude = 1e-3;
  irr.wavelength_min = 0.0;
  EXPECT_NE(error_of({{10, 0, 0, 0, 0}}, irr).find("wavelength"), std::string::npos);
  irr.wavelength_min = 10.0;
  irr.components = 0;
  EXPECT_NE(error_of({{10, 0, 0, 0, 0}}, irr).find("components"), std::string::npos);
  irr.amplitude = -1.0;
  EXPECT_NE(error_of({{10, 0, 0, 0, 0}}, irr).find("amplitude"), std::string::npos);
}

}  // namespace
}  // namespace railtab::vehicle
