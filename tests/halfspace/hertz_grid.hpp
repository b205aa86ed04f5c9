// SPDX-License-Identifier: Apache-2.0
// Test helper: a quadratic gap h = A x^2 + B y^2 on a grid around its Hertz ellipse.
#pragma once

#include <cmath>
#include <vector>

#include "halfspace/grid.hpp"

namespace railtab::test {

// Grid of element size dx * dy covering |x| <= margin a, |y| <= margin b, centred on the origin
// (an odd count, so an element sits on the centre).
inline halfspace::Grid grid_around(double a, double b, double dx, double dy, double margin = 1.25) {
  halfspace::Grid g;
  g.nx = 2 * static_cast<int>(std::ceil(margin * a / dx)) + 1;
  g.ny = 2 * static_cast<int>(std::ceil(margin * b / dy)) + 1;
  g.dx = dx;
  g.dy = dy;
  g.x0 = -(g.nx / 2) * dx;
  g.y0 = -(g.ny / 2) * dy;
  return g;
}

inline std::vector<double> quadratic_gap(const halfspace::Grid& g, double A, double B) {
  std::vector<double> h(g.size());
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) h[g.index(i, j)] = A * g.x(i) * g.x(i) + B * g.y(j) * g.y(j);
  return h;
}

}  // namespace railtab::test
