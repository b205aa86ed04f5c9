// SPDX-License-Identifier: Apache-2.0
// Tests of the KTH wear map (src/wear/kth_wear_map.hpp).
#include "wear/kth_wear_map.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/check.hpp"

namespace railtab {
namespace {

TEST(KthWearMap, RegionsAndBoundaries) {
  const KthWearMap m;  // defaults: 0.8 H = 2.2 GPa, 0.2 and 0.7 m/s
  const double p_low = 1.0e9, p_seize = 0.8 * m.hardness;
  EXPECT_EQ(kth_region(m, p_low, 0.0), KthRegion::mild);
  EXPECT_EQ(kth_region(m, p_low, 0.1), KthRegion::mild);
  EXPECT_EQ(kth_region(m, p_low, std::nextafter(0.2, 0.0)), KthRegion::mild);
  EXPECT_EQ(kth_region(m, p_low, 0.2), KthRegion::severe);  // severe from 0.2 m/s on
  EXPECT_EQ(kth_region(m, p_low, 0.45), KthRegion::severe);
  EXPECT_EQ(kth_region(m, p_low, 0.7), KthRegion::severe);  // up to and including 0.7 m/s
  EXPECT_EQ(kth_region(m, p_low, std::nextafter(0.7, 1.0)), KthRegion::oxidative);
  EXPECT_EQ(kth_region(m, p_low, 3.0), KthRegion::oxidative);
  EXPECT_EQ(kth_region(m, std::nextafter(p_seize, 0.0), 0.1), KthRegion::mild);
  EXPECT_EQ(kth_region(m, p_seize, 0.1), KthRegion::seizure);  // seizure from 0.8 H on
  EXPECT_EQ(kth_region(m, p_seize, 0.5), KthRegion::seizure);
  EXPECT_EQ(kth_region(m, 5e9, 2.0), KthRegion::seizure);
  EXPECT_NEAR(p_seize, 2.2e9, 1e-3);  // Enblom & Berg: seizure above about 2.2 GPa
  EXPECT_EQ(kth_region(m, p_low, -0.45), KthRegion::severe);  // magnitudes
}

TEST(KthWearMap, CoefficientsAndLubrication) {
  KthWearMap m;
  m.k1 = 1e-4;
  m.k2 = 2e-3;
  m.k3 = 3e-4;
  m.k4 = 4e-2;
  EXPECT_EQ(kth_wear_coefficient(m, 1e9, 0.1), 1e-4);
  EXPECT_EQ(kth_wear_coefficient(m, 1e9, 0.5), 2e-3);
  EXPECT_EQ(kth_wear_coefficient(m, 1e9, 1.0), 3e-4);
  EXPECT_EQ(kth_wear_coefficient(m, 2.5e9, 1.0), 4e-2);
  EXPECT_DOUBLE_EQ(kth_wear_coefficient(m, 1e9, 0.5, Lubrication::natural), 2e-3 / 5.5);
  EXPECT_DOUBLE_EQ(kth_wear_coefficient(m, 1e9, 0.5, Lubrication::lubricated), 2e-3 / 11.0);
  m.factor_natural = 4.0;  // configurable
  EXPECT_DOUBLE_EQ(kth_wear_coefficient(m, 1e9, 0.1, Lubrication::natural), 1e-4 / 4.0);
  // Defaults are the unverified range midpoints.
  const KthWearMap d;
  EXPECT_DOUBLE_EQ(d.k1, 5.5e-4);
  EXPECT_DOUBLE_EQ(d.k2, 35e-4);
  EXPECT_DOUBLE_EQ(d.k3, 5.5e-4);
  EXPECT_DOUBLE_EQ(d.k4, 350e-4);
}

TEST(KthWearMap, ValidationAndNames) {
  KthWearMap m;
  EXPECT_NO_THROW(validate(m));
  m.velocity_severe = 1.0;  // above the oxidative threshold
  EXPECT_THROW(validate(m), Error);
  m = KthWearMap{};
  m.hardness = 0.0;
  EXPECT_THROW(validate(m), Error);
  EXPECT_EQ(parse_lubrication("natural"), Lubrication::natural);
  EXPECT_STREQ(to_string(Lubrication::lubricated), "lubricated");
  EXPECT_THROW(parse_lubrication("wet"), Error);
}

}  // namespace
}  // namespace railtab
