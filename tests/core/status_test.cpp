// SPDX-License-Identifier: Apache-2.0
// Tests of the status flags (src/core/status.hpp): names, text, bit values.
#include "core/status.hpp"

#include <gtest/gtest.h>

#include "core/check.hpp"

namespace railtab {
namespace {

TEST(Status, DescribeNamesEverySetBit) {
  EXPECT_EQ(status::describe(0), "none");
  EXPECT_EQ(status::describe(status::kConverged | status::kTwoPoint), "converged,two_point");
  EXPECT_EQ(status::describe(status::kOutOfRange), "out_of_range");
}

TEST(Check, ThrowsErrorWithFormattedMessage) {
  try {
    RAILTAB_CHECK(1 + 1 == 3, "value {} is not {}", 2, 3);
    FAIL() << "RAILTAB_CHECK did not throw";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "value 2 is not 3");
  }
}

}  // namespace
}  // namespace railtab
