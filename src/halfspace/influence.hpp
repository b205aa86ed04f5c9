// SPDX-License-Identifier: Apache-2.0
// Influence coefficients of the elastic half-space for uniform loads on a rectangle (Love 1929;
// Johnson, Contact Mechanics ch. 3; Kalker 1990 ch. 5): the displacement DIFFERENCE of two
// bodies of the same material (quasi-identical bodies: a pressure causes no tangential
// displacement difference and a traction none normal, so the normal and tangential problems
// decouple; that is where the "same material" assumption of the half-space layer is used).
//
// Point-load Green's functions of the two bodies together (r = distance, (x, y) field minus source):
//   normal from pressure:        (1 / (pi E*)) / r,                     E* = G / (1 - nu)
//   x from traction x:           (1 / (pi G)) ((1 - nu) / r + nu x^2 / r^3)
//   y from traction y:           (1 / (pi G)) ((1 - nu) / r + nu y^2 / r^3)
//   x from traction y (and y from x): (1 / (pi G)) nu x y / r^3
// Integrated over the rectangle |x'| <= hx, |y'| <= hy in closed form with the antiderivatives
//   int int 1/r = X asinh(Y/|X|) + Y asinh(X/|Y|),  int int X^2/r^3 = Y asinh(X/|Y|),
//   int int Y^2/r^3 = X asinh(Y/|X|),                int int X Y/r^3 = -r,
// (up to terms in X or Y alone, which cancel),
// evaluated at the four corners X = x -+ hx, Y = y -+ hy.
#pragma once

#include <vector>

#include "core/material.hpp"

namespace railtab::halfspace {

struct TangentialInfluence {
  double xx = 0.0;  // u_x per unit traction p_x [m/Pa]
  double xy = 0.0;  // u_x per unit p_y (= u_y per unit p_x) [m/Pa]
  double yy = 0.0;  // u_y per unit p_y [m/Pa]
};

// Normal displacement difference at (x, y) from unit pressure on the rectangle centred at the
// origin with half-sizes hx, hy [m/Pa].
double normal_influence(double x, double y, double hx, double hy, const Material& material);

// Tangential displacement differences at (x, y) from unit traction on the same rectangle.
TangentialInfluence tangential_influence(double x, double y, double hx, double hy,
                                         const Material& material);

// The same coefficients for every element offset (di, dj), |di| <= mx, |dj| <= my, of a grid of
// dx x dy elements (field minus source at (di dx, dj dy)), at index (dj + my) (2 mx + 1) + di + mx.
// Neighbouring offsets share corners, and the antiderivatives are odd (asinh parts) or even (r)
// in X and Y, so each is evaluated once per corner of one quadrant: (mx + 1)(my + 1) evaluations
// instead of four per offset, 16 times fewer. Equal to the functions above to rounding (the
// corner coordinates (di + 1/2) dx instead of di dx + dx / 2).
void normal_influence_table(int mx, int my, double dx, double dy, const Material& material,
                            std::vector<double>& out);
void tangential_influence_table(int mx, int my, double dx, double dy, const Material& material,
                                std::vector<TangentialInfluence>& out);

}  // namespace railtab::halfspace
