// SPDX-License-Identifier: Apache-2.0
// STRIPES' Boussinesq closure integral J (stripes.cpp, file comment): the logarithms of all strips
// collected first, then evaluated in one vectorised pass.
#pragma once

#include <cmath>

namespace railtab::detail {

// Boussinesq integral J = sum_k A_k int int_strip (a_k^2 - x^2) / r dx dy, reference point at y = 0,
// strip k centred at y_k with width w. Per strip along x in closed form,
//   int_{-a}^{a} (a^2 - x^2)/sqrt(x^2+y^2) dx = (2a^2 + y^2) asinh(a/|y|) - a sqrt(a^2 + y^2),
// midpoint rule along y for the far strips (|y| >= 6 w); for the near strips also along y with
//   F(y) = int_0^a (a^2 - x^2) asinh(y/x) dx
//        = (2a^3/3) asinh(|y|/a) + (a^2 |y| + |y|^3/6) asinh(a/|y|) - |y| a r / 6   (odd in y),
//   int_{y1}^{y2} int_{-a}^{a} (a^2-x^2)/r = 2 (F(y2) - F(y1)).
// The logarithms (asinh(z) = ln(z + sqrt(1 + z^2))) are collected first and evaluated in one
// vectorised pass: J = sum_i coef_i ln(arg_i) + rest.
class BoussinesqSum {
 public:
  // arg and coef: scratch for up to 4 terms per strip added.
  BoussinesqSum(double* arg, double* coef) : arg_(arg), coef_(coef) {}

  void add(double A, double a, double y, double w) {
    if (!(a > 0.0)) return;
    const double ay = std::abs(y);
    if (ay < 6.0 * w) {
      edge(2.0 * A, a, y + 0.5 * w);
      edge(-2.0 * A, a, y - 0.5 * w);
      return;
    }
    const double r = std::sqrt(a * a + ay * ay);
    push((a + r) / ay, A * w * (2.0 * a * a + ay * ay));
    rest_ -= A * w * a * r;
  }

  // add(A[k], a[k], s_lo + (k + 1/2) width - s_ref, width) for k = 0..n-1, with the square roots
  // and divisions of two strips (far) or of the two edges of a strip (near) on two SSE2 lanes: the
  // same IEEE operations, logarithm arguments, coefficients and order of the remainder sums.
  void add_strips(const double* A, const double* a, int n, double s_lo, double width,
                  double s_ref);

  // total() of two sums, their logarithms interleaved (two independent chains of additions, each
  // in its own order).
  static void total2(const BoussinesqSum& s1, const BoussinesqSum& s2, double* t1, double* t2);

  double total() const { return sum_from(0, rest_); }

 private:
  // sum + the terms i.. in order.
  double sum_from(int i, double sum) const;

  // factor * F(a, y).
  void edge(double factor, double a, double y) {
    if (y == 0.0) return;
    const double ay = std::abs(y);
    const double f = y > 0.0 ? factor : -factor;
    const double r = std::sqrt(a * a + ay * ay);
    push((ay + r) / a, f * (2.0 * a * a * a / 3.0));           // asinh(|y|/a)
    push((a + r) / ay, f * (a * a * ay + ay * ay * ay / 6.0));  // asinh(a/|y|)
    rest_ -= f * (ay * a * r / 6.0);
  }
  void push(double arg, double coef) {
    arg_[n_] = arg;
    coef_[n_] = coef;
    ++n_;
  }

  double* arg_;
  double* coef_;
  int n_ = 0;
  double rest_ = 0.0;
};

}  // namespace railtab::detail
