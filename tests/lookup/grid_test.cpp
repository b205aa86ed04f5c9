// SPDX-License-Identifier: Apache-2.0
// Axis::locate (lookup/src/grid.hpp): cells and fractions on uniform and non-uniform axes.
#include "grid.hpp"

#include <gtest/gtest.h>

namespace railtab::lookup::detail {
namespace {

void expect_cell(const Axis& a, double x, int i, double t, bool clamped) {
  AxisLoc loc;
  EXPECT_EQ(a.locate(x, loc), clamped) << "x = " << x;
  EXPECT_EQ(loc.i, i) << "x = " << x;
  EXPECT_NEAR(loc.t, t, 1e-12) << "x = " << x;
}

TEST(Grid, UniformAxis) {
  const Axis a({-0.01, -0.005, 0.0, 0.005, 0.01});
  expect_cell(a, -0.01, 0, 0.0, false);
  expect_cell(a, -0.0075, 0, 0.5, false);
  expect_cell(a, 0.0, 2, 0.0, false);  // a node starts its cell
  expect_cell(a, 0.00999, 3, 0.998, false);
  expect_cell(a, 0.01, 3, 1.0, false);  // last node closes the last cell
  expect_cell(a, 0.02, 3, 1.0, true);
  expect_cell(a, -1.0, 0, 0.0, true);
}

TEST(Grid, NonUniformAxis) {
  const Axis a({0.0, 1.0, 1.5, 4.0});
  expect_cell(a, 0.5, 0, 0.5, false);
  expect_cell(a, 1.0, 1, 0.0, false);
  expect_cell(a, 1.25, 1, 0.5, false);
  expect_cell(a, 3.0, 2, 0.6, false);
  expect_cell(a, 4.0, 2, 1.0, false);
  expect_cell(a, 5.0, 2, 1.0, true);
}

TEST(Grid, TwoNodes) {
  const Axis a({2.0, 3.0});
  expect_cell(a, 2.25, 0, 0.25, false);
  expect_cell(a, 1.0, 0, 0.0, true);
}

TEST(Grid, UniformRoundingNeverPicksAWrongCell) {
  std::vector<double> x(41);
  for (int i = 0; i < 41; ++i) x[i] = -0.01 + 0.02 * i / 40;
  const Axis a(x);
  for (int i = 0; i + 1 < 41; ++i) {
    for (double t : {0.0, 1e-15, 0.5, 1.0 - 1e-15}) {
      const double q = x[i] + t * (x[i + 1] - x[i]);
      AxisLoc loc;
      a.locate(q, loc);
      EXPECT_GE(q, x[loc.i]);
      EXPECT_LE(q, x[loc.i + 1]);
    }
  }
}

}  // namespace
}  // namespace railtab::lookup::detail
