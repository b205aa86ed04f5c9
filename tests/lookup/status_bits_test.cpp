// SPDX-License-Identifier: Apache-2.0
// The lookup mirrors the core's status bits (it must not link the core): the values must match.
#include <gtest/gtest.h>

#include "core/status.hpp"
#include "railtab/lookup.hpp"
#include "railtab_lookup.h"

namespace railtab::lookup {
namespace {

TEST(StatusBits, MatchTheCore) {
  EXPECT_EQ(status::kConverged, railtab::status::kConverged);
  EXPECT_EQ(status::kNotConverged, railtab::status::kNotConverged);
  EXPECT_EQ(status::kTwoPoint, railtab::status::kTwoPoint);
  EXPECT_EQ(status::kLiftOff, railtab::status::kLiftOff);
  EXPECT_EQ(status::kCurvatureClipped, railtab::status::kCurvatureClipped);
  EXPECT_EQ(status::kCurvatureShifted, railtab::status::kCurvatureShifted);
  EXPECT_EQ(status::kFallbackModel, railtab::status::kFallbackModel);
  EXPECT_EQ(status::kFlangeContact, railtab::status::kFlangeContact);
  EXPECT_EQ(status::kNonHertzian, railtab::status::kNonHertzian);
  EXPECT_EQ(status::kFullSlip, railtab::status::kFullSlip);
  EXPECT_EQ(status::kOutOfRange, railtab::status::kOutOfRange);
  EXPECT_EQ(status::kInvalidInput, railtab::status::kInvalidInput);
  EXPECT_EQ(status::kProfileEdge, railtab::status::kProfileEdge);
  EXPECT_EQ(status::kFailed, railtab::status::kFailed);
  EXPECT_EQ(RAILTAB_LOOKUP_CONVERGED, railtab::status::kConverged);
  EXPECT_EQ(RAILTAB_LOOKUP_LIFT_OFF, railtab::status::kLiftOff);
  EXPECT_EQ(RAILTAB_LOOKUP_FLANGE_CONTACT, railtab::status::kFlangeContact);
  EXPECT_EQ(RAILTAB_LOOKUP_FULL_SLIP, railtab::status::kFullSlip);
  EXPECT_EQ(RAILTAB_LOOKUP_OUT_OF_RANGE, railtab::status::kOutOfRange);
  EXPECT_EQ(RAILTAB_LOOKUP_INVALID_INPUT, railtab::status::kInvalidInput);
  EXPECT_EQ(RAILTAB_LOOKUP_NOT_CONVERGED, railtab::status::kNotConverged);
  EXPECT_EQ(RAILTAB_LOOKUP_TWO_POINT, railtab::status::kTwoPoint);
  EXPECT_EQ(RAILTAB_LOOKUP_CURVATURE_CLIPPED, railtab::status::kCurvatureClipped);
  EXPECT_EQ(RAILTAB_LOOKUP_CURVATURE_SHIFTED, railtab::status::kCurvatureShifted);
  EXPECT_EQ(RAILTAB_LOOKUP_FALLBACK_MODEL, railtab::status::kFallbackModel);
  EXPECT_EQ(RAILTAB_LOOKUP_NON_HERTZIAN, railtab::status::kNonHertzian);
  EXPECT_EQ(RAILTAB_LOOKUP_PROFILE_EDGE, railtab::status::kProfileEdge);
  EXPECT_EQ(RAILTAB_LOOKUP_FAILED, railtab::status::kFailed);
  EXPECT_EQ(status::kAreaTooSmall, railtab::status::kAreaTooSmall);
  EXPECT_EQ(status::kNotPlanar, railtab::status::kNotPlanar);
  EXPECT_EQ(RAILTAB_LOOKUP_AREA_TOO_SMALL, railtab::status::kAreaTooSmall);
  EXPECT_EQ(RAILTAB_LOOKUP_NOT_PLANAR, railtab::status::kNotPlanar);
  EXPECT_EQ(status::kNearEqualMinima, railtab::status::kNearEqualMinima);
  EXPECT_EQ(RAILTAB_LOOKUP_NEAR_EQUAL_MINIMA, railtab::status::kNearEqualMinima);
  EXPECT_EQ(status::kCurvatureStep, railtab::status::kCurvatureStep);
  EXPECT_EQ(RAILTAB_LOOKUP_CURVATURE_STEP, railtab::status::kCurvatureStep);
  EXPECT_EQ(status::kLowConfidence, railtab::status::kLowConfidence);
  EXPECT_EQ(RAILTAB_LOOKUP_LOW_CONFIDENCE, railtab::status::kLowConfidence);
  // Every bit has the core's name, and the core names no bit beyond the lookup's count.
  for (int b = 0; b < status::kNumBits; ++b) {
    EXPECT_EQ(status::bit_name(1u << b), railtab::status::describe(1u << b)) << "bit " << b;
  }
  EXPECT_EQ(railtab::status::describe(1u << status::kNumBits), "none");
}

}  // namespace
}  // namespace railtab::lookup
