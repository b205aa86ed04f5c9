// SPDX-License-Identifier: Apache-2.0
// The documented range of every wheelset-state number a user types (eval, query, the charts, the
// Python module), for core/number_input.hpp; the scene grids use the same limits (scene.hpp).
#pragma once

#include "core/number_input.hpp"
#include "scene/scene.hpp"

namespace railtab {

// Wheelset roll beyond this (5.7 degrees) is no rail vehicle on track: a roll typed in mrad.
inline constexpr double kMaxRoll = 0.1;  // [rad]
// A wheel load beyond this (100 t on one wheel, 4x the heaviest axle loads) is a typo.
inline constexpr double kMaxWheelLoad = 1e6;  // [N]
// A friction coefficient beyond this is no wheel-rail contact.
inline constexpr double kMaxFriction = 10.0;  // [-]

inline constexpr NumberRule kLateralShiftRule{-kMaxLateralShift, kMaxLateralShift, false, "m"};
inline constexpr NumberRule kRollRule{-kMaxRoll, kMaxRoll, false, "rad"};
// Yaw up to the contact search's limit (geometry/contact_geometry.hpp, 11.5 degrees).
inline constexpr NumberRule kYawRule{-kMaxYaw, kMaxYaw, false, "rad"};
inline constexpr NumberRule kWheelLoadRule{0.0, kMaxWheelLoad, false, "N"};
inline constexpr NumberRule kCreepageRule{-kMaxCreepage, kMaxCreepage, false, ""};
inline constexpr NumberRule kSpinCreepageRule{-kMaxSpinCreepage, kMaxSpinCreepage, false, "1/m"};
inline constexpr NumberRule kFrictionRule{0.0, kMaxFriction, false, ""};

}  // namespace railtab
