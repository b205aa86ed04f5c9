// SPDX-License-Identifier: Apache-2.0
// Status flags (status.hpp): their names and the text of a set of bits.
#include "core/status.hpp"

#include <array>
#include <utility>

namespace railtab::status {

std::string describe(StatusBits bits) {
  static constexpr std::array<std::pair<StatusBits, const char*>, 19> kNames{{
      {kConverged, "converged"},
      {kNotConverged, "not_converged"},
      {kTwoPoint, "two_point"},
      {kLiftOff, "lift_off"},
      {kCurvatureClipped, "curvature_clipped"},
      {kCurvatureShifted, "curvature_shifted"},
      {kFallbackModel, "fallback_model"},
      {kFlangeContact, "flange_contact"},
      {kNonHertzian, "non_hertzian"},
      {kFullSlip, "full_slip"},
      {kOutOfRange, "out_of_range"},
      {kInvalidInput, "invalid_input"},
      {kProfileEdge, "profile_edge"},
      {kFailed, "failed"},
      {kAreaTooSmall, "area_too_small"},
      {kNotPlanar, "not_planar"},
      {kNearEqualMinima, "near_equal_minima"},
      {kCurvatureStep, "curvature_step"},
      {kLowConfidence, "low_confidence"},
  }};
  std::string out;
  for (const auto& [bit, name] : kNames) {
    if (bits & bit) {
      if (!out.empty()) out += ',';
      out += name;
    }
  }
  return out.empty() ? "none" : out;
}

}  // namespace railtab::status
