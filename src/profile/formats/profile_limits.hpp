// SPDX-License-Identifier: Apache-2.0
// Limits on profile input, checked before anything is allocated (docs/profiles.md "Limits").
// They are far above any real wheel or rail profile and keep hostile or broken files (a device,
// a FIFO, coordinates in the wrong unit or scaled by 1e300) from exhausting memory or time.
#pragma once

#include <cstddef>

namespace railtab::limits {

inline constexpr std::size_t kMaxProfileFileBytes = 16u << 20;  // 16 MiB read at most
inline constexpr std::size_t kMaxProfileLines = 1'000'000;      // lines of one profile file
inline constexpr std::size_t kMaxProfilePoints = 100'000;       // points of one profile
inline constexpr double kMaxProfileCoordinate = 1.0;            // |y|, |z| after units [m]

}  // namespace railtab::limits
