// SPDX-License-Identifier: Apache-2.0
// Complete elliptic integrals and the Hertz ellipse shape (elliptic.hpp).
#include "normal/elliptic.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/check.hpp"
#include "core/root_find.hpp"
#include "normal/normal_internal.hpp"

namespace railtab {
namespace {

// Arithmetic-geometric mean started at (1, kc) with the Gauss sum
//   S = sum_{n>=0} 2^(n-1) c_n^2,  K = pi / (2 AGM),  E = K (1 - S)   (Abramowitz & Stegun 17.6).
// S is returned split: s0 = c_0^2/2 = k^2/2 and the tail sum_{n>=1}, so that callers can form
// k^2 - S without cancellation.
struct Agm {
  double mean;  // AGM(1, kc)
  double tail;  // sum_{n>=2} 2^(n-1) c_n^2 (c_1 handled in closed form by the callers)
};

Agm agm(double kc) {
  double a = 1.0, b = kc;
  double tail = 0.0;
  double weight = 1.0;  // 2^(n-1) for n = 1 at the first step
  for (int n = 1; n < 64; ++n) {
    const double c = 0.5 * (a - b);
    if (n >= 2) tail += weight * c * c;
    const double a_next = 0.5 * (a + b);
    b = std::sqrt(a * b);
    a = a_next;
    weight *= 2.0;
    if (std::abs(c) <= 1e-17 * a) break;
  }
  return {a, tail};
}

}  // namespace

EllipticKE complete_elliptic_complementary(double kc) {
  RAILTAB_CHECK(kc > 0.0 && kc <= 1.0, "complete_elliptic: complementary modulus {} not in (0, 1]",
                kc);
  const Agm m = agm(kc);
  const double K = std::numbers::pi / (2.0 * m.mean);
  // S = k^2/2 + c_1^2 + tail, c_1 = (1 - kc)/2.
  const double k2 = (1.0 - kc) * (1.0 + kc);
  const double c1 = 0.5 * (1.0 - kc);
  const double s = 0.5 * k2 + c1 * c1 + m.tail;
  return {K, K * (1.0 - s)};
}

EllipticKE complete_elliptic(double k) {
  RAILTAB_CHECK(k >= 0.0 && k < 1.0, "complete_elliptic: modulus {} not in [0, 1)", k);
  return complete_elliptic_complementary(std::sqrt((1.0 - k) * (1.0 + k)));
}

double hertz_curvature_ratio(double g) {
  RAILTAB_CHECK(g > 0.0 && g <= 1.0, "hertz_curvature_ratio: axis ratio {} not in (0, 1]", g);
  if (g == 1.0) return 1.0;
  // (K - E)/(E/g^2 - K) = g^2 S / (k^2 - S); with S = k^2/2 + c1^2 + tail,
  // k^2 - S = k^2/2 - c1^2 - tail = (1 - g)(1 + 3g)/4 - tail: no cancellation near g -> 1.
  const Agm m = agm(g);
  const double k2 = (1.0 - g) * (1.0 + g);
  const double c1 = 0.5 * (1.0 - g);
  const double s = 0.5 * k2 + c1 * c1 + m.tail;
  const double d = 0.25 * (1.0 - g) * (1.0 + 3.0 * g) - m.tail;
  return g * g * s / d;
}

namespace {
double fast_log_axis_ratio(double ratio, bool* ok);
}  // namespace

namespace {

HertzShape hertz_shape_impl(double ratio, bool use_table) {
  RAILTAB_CHECK(ratio > 0.0 && ratio <= 1.0, "hertz_shape: curvature ratio {} not in (0, 1]",
                ratio);
  ratio = std::max(ratio, 1e-12);
  double g = 1.0;
  if (ratio < 1.0) {
    // Root of ln ratio(g) - ln ratio in u = ln g; ratio(g) increases monotonically from 0 to 1.
    // Start: the interpolation table (error < 1e-9) gives a bracket of +-1e-8 that Brent closes in
    // two or three evaluations; while the table is built, Greenwood's g ~ ratio^(2/3) (FACTS 1.2,
    // within 20 % down to 1e-2) with widening.
    const double target = std::log(ratio);
    auto f = [&](double u) { return std::log(hertz_curvature_ratio(std::exp(u))) - target; };
    bool table_ok = false;
    const double ut = use_table ? fast_log_axis_ratio(ratio, &table_ok) : 0.0;
    const double u0 = table_ok ? ut : (2.0 / 3.0) * target;
    const double half = table_ok ? 1e-8 : 0.5;
    double lo = u0 - half, hi = std::min(0.0, u0 + half);
    double flo = f(lo), fhi = hi < 0.0 ? f(hi) : -target;
    while (flo > 0.0) {
      lo -= 1.0;
      flo = f(lo);
    }
    while (fhi < 0.0 && hi < 0.0) {
      hi = std::min(0.0, hi + 1.0);
      fhi = hi < 0.0 ? f(hi) : -target;
    }
    const auto root = brent_root(f, lo, hi, flo, fhi, 1e-14, 0.0, 200);
    g = std::exp(root.x);
  }
  const EllipticKE ke = complete_elliptic_complementary(g);
  const double e = std::sqrt((1.0 - g) * (1.0 + g));
  const double m = std::cbrt(2.0 * ke.E / (std::numbers::pi * g * g));
  const double n = std::cbrt(2.0 * ke.E * g / std::numbers::pi);
  const double r = 2.0 * ke.K / (std::numbers::pi * m);
  return {ratio, g, e, ke.K, ke.E, m, n, r};
}

}  // namespace

HertzShape hertz_shape(double ratio) { return hertz_shape_impl(ratio, true); }

namespace {

// ln g over x = ln ratio on [x_min, 0], uniform, with slopes dy/dx for cubic Hermite interpolation.
struct ShapeTable {
  static constexpr int kNodes = 2049;
  static constexpr double kXMin = -20.0;  // ratio 2e-9
  double h = -kXMin / (kNodes - 1);
  std::vector<double> y, dy;
  ShapeTable() : y(kNodes), dy(kNodes) {
    for (int i = 0; i < kNodes; ++i) {
      const double x = kXMin + i * h;
      if (i == kNodes - 1) {
        y[i] = 0.0;
        dy[i] = 2.0 / 3.0;  // g = 1: ln ratio ~ -3k^2/4, ln g ~ -k^2/2
        continue;
      }
      const double u = std::log(hertz_shape_impl(std::exp(x), false).g);
      y[i] = u;
      // d ln ratio / d ln g by a central difference of the exact ratio (step 1e-5: error ~1e-10).
      const double du = 1e-5;
      const double up = std::min(u + du, 0.0);
      const double dlr = (std::log(hertz_curvature_ratio(std::exp(up))) -
                          std::log(hertz_curvature_ratio(std::exp(u - du)))) /
                         (up - (u - du));
      dy[i] = 1.0 / dlr;
    }
  }
};

const ShapeTable& shape_table() {
  static const ShapeTable table;  // thread-safe one-time initialisation
  return table;
}

inline double table_at(const ShapeTable& t, double pos);

double fast_log_axis_ratio(double ratio, bool* ok) {
  *ok = false;
  if (!(ratio > 0.0) || ratio >= 1.0) return 0.0;
  const ShapeTable& t = shape_table();
  const double x = detail::fast_log(ratio);  // within an ulp of std::log, without the call
  if (x < ShapeTable::kXMin) return 0.0;
  *ok = true;
  return table_at(t, (x - ShapeTable::kXMin) / t.h);
}

inline double table_at(const ShapeTable& t, double pos) {
  int i = static_cast<int>(pos);
  if (i >= ShapeTable::kNodes - 1) i = ShapeTable::kNodes - 2;
  const double s = pos - i;
  const double s2 = s * s, s3 = s2 * s;
  const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2,
               h11 = s3 - s2;
  return h00 * t.y[i] + h10 * t.h * t.dy[i] + h01 * t.y[i + 1] + h11 * t.h * t.dy[i + 1];
}

}  // namespace

double hertz_axis_ratio_fast(double ratio) {
  if (ratio >= 1.0) return 1.0;
  bool ok = false;
  const double y = fast_log_axis_ratio(ratio, &ok);
  return ok ? std::exp(y) : hertz_shape_impl(ratio, false).g;
}

namespace detail {

void hertz_axis_ratio_fast_n(double* x, int n) {
  // In chunks: the table lookups first (no calls, independent), then the exponentials.
  // The logarithms and table positions two at a time (fast_log_pd: the same operations as
  // fast_log), then the table (fast_log_axis_ratio's steps) and the exponentials.
  constexpr int kChunk = 64;
  double y[kChunk];
  unsigned char state[kChunk];  // 0: ratio >= 1, 1: table, 2: exact shape
  const ShapeTable& t = shape_table();
  for (int c0 = 0; c0 < n; c0 += kChunk) {
    const int m = std::min(kChunk, n - c0);
    double* xc = x + c0;
    double lx[kChunk], pos[kChunk];
    int i = 0;
#if defined(__SSE2__)
    const __m128d xmin = _mm_set1_pd(ShapeTable::kXMin), vh = _mm_set1_pd(t.h);
    for (; i + 1 < m; i += 2) {
      const __m128d l = fast_log_pd(_mm_loadu_pd(xc + i));
      _mm_storeu_pd(lx + i, l);
      _mm_storeu_pd(pos + i, _mm_div_pd(_mm_sub_pd(l, xmin), vh));
    }
#endif
    for (; i < m; ++i) {
      lx[i] = fast_log(xc[i]);
      pos[i] = (lx[i] - ShapeTable::kXMin) / t.h;
    }
    for (i = 0; i < m; ++i) {
      const double ratio = xc[i];
      if (ratio >= 1.0) {
        state[i] = 0;
      } else if (!(ratio > 0.0) || lx[i] < ShapeTable::kXMin) {
        state[i] = 2;
      } else {
        state[i] = 1;
        y[i] = table_at(t, pos[i]);
      }
    }
    for (i = 0; i < m; ++i) {
      if (state[i] == 1) [[likely]]
        xc[i] = std::exp(y[i]);
      else
        xc[i] = state[i] == 0 ? 1.0 : hertz_shape_impl(xc[i], false).g;
    }
  }
}

}  // namespace detail

}  // namespace railtab
