// SPDX-License-Identifier: Apache-2.0
// Shared test helper: a profile's analytic derivatives against central finite differences.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "profile/curves/profile.hpp"

namespace railtab::test {

// Compare dz with (z(u+h) - z(u-h)) / 2h and d2z with the same difference of dz at `count`
// points spread over the whole range, skipping points within 2h of `kinks` (joints where the
// curvature jumps, so a difference across them means nothing). Tolerances are relative to
// the size of the derivative.
inline void expect_derivatives_match_differences(const Profile& p, const std::vector<double>& kinks,
                                                 int count = 4001, double h = 1e-6) {
  int checked = 0;
  for (int i = 0; i < count; ++i) {
    const double u = p.u_min() + 2.0 * h + (p.u_max() - p.u_min() - 4.0 * h) * i / (count - 1);
    bool near_kink = false;
    for (double k : kinks) near_kink = near_kink || std::fabs(u - k) < 3.0 * h;
    if (near_kink) continue;
    const ProfileSample s = p.eval(u);
    // Fourth-order central stencil: the steep end of the rail's R13 arc (slope 20) has large
    // third derivatives, where the plain 2-point difference is off by 1e-4 relative.
    const ProfileSample m2 = p.eval(u - 2.0 * h);
    const ProfileSample m1 = p.eval(u - h);
    const ProfileSample p1 = p.eval(u + h);
    const ProfileSample p2 = p.eval(u + 2.0 * h);
    const double dz_fd = (m2.z - 8.0 * m1.z + 8.0 * p1.z - p2.z) / (12.0 * h);
    const double d2z_fd = (m2.dz - 8.0 * m1.dz + 8.0 * p1.dz - p2.dz) / (12.0 * h);
    EXPECT_NEAR(s.dz, dz_fd, 1e-6 * (1.0 + std::fabs(s.dz))) << p.name() << " at u = " << u;
    EXPECT_NEAR(s.d2z, d2z_fd, 1e-5 * (1.0 + std::fabs(s.d2z))) << p.name() << " at u = " << u;
    ++checked;
  }
  EXPECT_GT(checked, count * 9 / 10);
}

}  // namespace railtab::test
