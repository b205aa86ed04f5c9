// SPDX-License-Identifier: Apache-2.0
// A result with a NaN or an inf in any output is failed, never converged: the status a table
// point and `railtab eval` carry for it (the lookup refuses tables with non-finite values, so the
// table stores zeros there). docs/reliability.md.
#pragma once

#include <cmath>
#include <initializer_list>

#include "core/status.hpp"

namespace railtab {

// The status of a result whose outputs include a non-finite number: kFailed, without kConverged
// or kNotConverged; the other flags (two_point, flange, ...) stay as information.
inline StatusBits non_finite_status(StatusBits bits) {
  return (bits & ~(status::kConverged | status::kNotConverged)) | status::kFailed;
}

inline bool all_finite(std::initializer_list<double> values) {
  for (double v : values) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

}  // namespace railtab
