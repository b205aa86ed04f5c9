// SPDX-License-Identifier: Apache-2.0
// The potential contact area of the half-space solver: a rectangular grid of equal rectangular
// elements in the patch's tangent plane (x rolling direction, y lateral along s, as the contact
// frame of docs/conventions.md). Element (i, j) has its centre at (x0 + i dx, y0 + j dy) and
// index j * nx + i: rows run along x, so a row is one lateral position.
#pragma once

#include <cstddef>

namespace railtab::halfspace {

struct Grid {
  int nx = 0;        // elements along x [-]
  int ny = 0;        // elements along y [-]
  double dx = 0.0;   // element length along x [m]
  double dy = 0.0;   // element width along y [m]
  double x0 = 0.0;   // centre of element (0, 0), x [m]
  double y0 = 0.0;   // centre of element (0, 0), y [m]

  int size() const { return nx * ny; }
  int index(int i, int j) const { return j * nx + i; }
  double x(int i) const { return x0 + i * dx; }
  double y(int j) const { return y0 + j * dy; }
  double element_area() const { return dx * dy; }
};

}  // namespace railtab::halfspace
