// SPDX-License-Identifier: Apache-2.0
// Brent's bracketed root finder (Brent 1973, "Algorithms for minimization without derivatives",
// ch. 4): inverse quadratic interpolation safeguarded by bisection, so it never leaves the bracket
// and converges for any continuous function with a sign change. Header-only, allocation-free.
// One copy for the library: the normal load control and Hertz shape (src/normal) and the
// equilibrium roll (src/geometry) use it.
#pragma once

#include <algorithm>
#include <cmath>
#include <utility>

namespace railtab {

struct RootResult {
  double x;        // best root estimate
  double fx;       // function value there
  int iterations;  // function evaluations after the two bracket ends
  bool converged;  // |bracket| <= tolerance or f(x) == 0 (or f_tol met by the caller's f)
};

// f(lo) and f(hi) must have opposite signs (or one be zero); fa, fb are f(lo), f(hi) already known.
// Stops when the bracket is shorter than x_tol or |f| <= f_tol.
template <class F>
RootResult brent_root(F&& f, double a, double b, double fa, double fb, double x_tol, double f_tol,
                      int max_iterations) {
  if (fa == 0.0) return {a, fa, 0, true};
  if (fb == 0.0) return {b, fb, 0, true};
  double c = a, fc = fa, d = b - a, e = d;
  int it = 0;
  for (; it < max_iterations; ++it) {
    if ((fb > 0.0) == (fc > 0.0)) {
      c = a;
      fc = fa;
      d = e = b - a;
    }
    if (std::abs(fc) < std::abs(fb)) {
      a = b;
      b = c;
      c = a;
      fa = fb;
      fb = fc;
      fc = fa;
    }
    const double tol = 2.0 * 2.2e-16 * std::abs(b) + 0.5 * x_tol;
    const double m = 0.5 * (c - b);
    if (std::abs(m) <= tol || std::abs(fb) <= f_tol) return {b, fb, it, true};
    if (std::abs(e) >= tol && std::abs(fa) > std::abs(fb)) {
      double p, q, r;
      const double s = fb / fa;
      if (a == c) {
        p = 2.0 * m * s;
        q = 1.0 - s;
      } else {
        q = fa / fc;
        r = fb / fc;
        p = s * (2.0 * m * q * (q - r) - (b - a) * (r - 1.0));
        q = (q - 1.0) * (r - 1.0) * (s - 1.0);
      }
      if (p > 0.0) q = -q; else p = -p;
      if (2.0 * p < std::min(3.0 * m * q - std::abs(tol * q), std::abs(e * q))) {
        e = d;
        d = p / q;
      } else {
        d = m;
        e = m;
      }
    } else {
      d = m;
      e = m;
    }
    a = b;
    fa = fb;
    b += (std::abs(d) > tol) ? d : (m > 0.0 ? tol : -tol);
    fb = f(b);
  }
  return {b, fb, it, false};
}

}  // namespace railtab
