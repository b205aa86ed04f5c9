// SPDX-License-Identifier: Apache-2.0
#include "halfspace/influence.hpp"

#include <cmath>
#include <numbers>

namespace railtab::halfspace {
namespace {

// X asinh(Y / |X|) (= X ln(Y + r) up to a function of X alone, which cancels between the
// corners), continuous (-> 0) at X = 0.
double x_asinh(double X, double Y) { return X == 0.0 ? 0.0 : X * std::asinh(Y / std::abs(X)); }

struct Corner {  // the antiderivatives at one corner
  double a;      // X asinh(Y/|X|): int int Y^2/r^3
  double b;      // Y asinh(X/|Y|): int int X^2/r^3
  double r;      // -int int X Y/r^3
};
Corner corner(double X, double Y) { return {x_asinh(X, Y), x_asinh(Y, X), std::hypot(X, Y)}; }

// F(x + hx, y + hy) - F(x - hx, y + hy) - F(x + hx, y - hy) + F(x - hx, y - hy) for each part.
Corner rectangle(double x, double y, double hx, double hy) {
  const Corner pp = corner(x + hx, y + hy), mp = corner(x - hx, y + hy);
  const Corner pm = corner(x + hx, y - hy), mm = corner(x - hx, y - hy);
  return {pp.a - mp.a - pm.a + mm.a, pp.b - mp.b - pm.b + mm.b, pp.r - mp.r - pm.r + mm.r};
}

}  // namespace

double normal_influence(double x, double y, double hx, double hy, const Material& material) {
  const Corner c = rectangle(x, y, hx, hy);
  return (c.a + c.b) / (std::numbers::pi * material.contact_modulus());
}

TangentialInfluence tangential_influence(double x, double y, double hx, double hy,
                                         const Material& material) {
  const Corner c = rectangle(x, y, hx, hy);
  const double nu = material.poisson_ratio;
  const double k = 1.0 / (std::numbers::pi * material.shear_modulus());
  TangentialInfluence t;
  t.xx = k * ((1.0 - nu) * (c.a + c.b) + nu * c.b);
  t.yy = k * ((1.0 - nu) * (c.a + c.b) + nu * c.a);
  t.xy = -k * nu * c.r;
  return t;
}

}  // namespace railtab::halfspace
