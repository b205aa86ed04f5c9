// SPDX-License-Identifier: Apache-2.0
// Influence coefficients of the elastic half-space for uniform loads on a rectangle (influence.hpp).
#include "halfspace/influence.hpp"

#include <cmath>
#include <cstddef>
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

// Corner antiderivatives on the lattice X = (u + 1/2) dx, Y = (v + 1/2) dy, u in [-mx - 1, mx],
// v in [-my - 1, my], from one quadrant (u, v >= 0): a and b are odd in X and in Y, r even.
struct CornerLattice {
  int mx, my;
  std::vector<Corner> q;  // u, v >= 0: index v * (mx + 1) + u
  CornerLattice(int mx_, int my_, double dx, double dy) : mx(mx_), my(my_) {
    q.resize(static_cast<size_t>(mx + 1) * (my + 1));
    for (int v = 0; v <= my; ++v)
      for (int u = 0; u <= mx; ++u) q[static_cast<size_t>(v) * (mx + 1) + u] =
            corner((u + 0.5) * dx, (v + 0.5) * dy);
  }
  Corner at(int u, int v) const {
    const int uq = u >= 0 ? u : -u - 1, vq = v >= 0 ? v : -v - 1;
    const double s = (u >= 0) == (v >= 0) ? 1.0 : -1.0;
    const Corner& c = q[static_cast<size_t>(vq) * (mx + 1) + uq];
    return {s * c.a, s * c.b, c.r};
  }
  // The rectangle differences of element offset (di, dj), as rectangle().
  Corner element(int di, int dj) const {
    const Corner pp = at(di, dj), mp = at(di - 1, dj), pm = at(di, dj - 1), mm = at(di - 1, dj - 1);
    return {pp.a - mp.a - pm.a + mm.a, pp.b - mp.b - pm.b + mm.b, pp.r - mp.r - pm.r + mm.r};
  }
};

}  // namespace

void normal_influence_table(int mx, int my, double dx, double dy, const Material& material,
                            std::vector<double>& out) {
  const CornerLattice lattice(mx, my, dx, dy);
  const double k = 1.0 / (std::numbers::pi * material.contact_modulus());
  out.resize(static_cast<size_t>(2 * mx + 1) * (2 * my + 1));
  for (int dj = -my; dj <= my; ++dj)
    for (int di = -mx; di <= mx; ++di) {
      const Corner c = lattice.element(di, dj);
      out[static_cast<size_t>(dj + my) * (2 * mx + 1) + (di + mx)] = (c.a + c.b) * k;
    }
}

void tangential_influence_table(int mx, int my, double dx, double dy, const Material& material,
                                std::vector<TangentialInfluence>& out) {
  const CornerLattice lattice(mx, my, dx, dy);
  const double nu = material.poisson_ratio;
  const double k = 1.0 / (std::numbers::pi * material.shear_modulus());
  out.resize(static_cast<size_t>(2 * mx + 1) * (2 * my + 1));
  for (int dj = -my; dj <= my; ++dj)
    for (int di = -mx; di <= mx; ++di) {
      const Corner c = lattice.element(di, dj);
      TangentialInfluence& t = out[static_cast<size_t>(dj + my) * (2 * mx + 1) + (di + mx)];
      t.xx = k * ((1.0 - nu) * (c.a + c.b) + nu * c.b);
      t.yy = k * ((1.0 - nu) * (c.a + c.b) + nu * c.a);
      t.xy = -k * nu * c.r;
    }
}

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
