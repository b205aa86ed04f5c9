// SPDX-License-Identifier: Apache-2.0
// Interpolation accuracy through the public API: exact polynomial reproduction (multilinear:
// affine; cubic: quadratics), convergence order on a smooth non-polynomial function, and no
// overshoot for the monotone cubic.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "lookup/lookup_test_util.hpp"
#include "lookup/table_fixture.hpp"
#include "railtab/lookup.hpp"

namespace railtab::lookup {
namespace {

using testing::FixtureSpec;
using testing::linspace;
using testing::TempFile;

// Scaled coordinates so every variable contributes O(1): y/1cm, roll/10mrad, load/100kN, ...
double scaled(int var, const double* x) {
  static const double scale[6] = {0.01, 0.01, 1e5, 0.01, 0.01, 1.0};
  return x[var] / scale[var];
}

// A different coefficient for every (wheel, part, output, slot, term).
double coef(int wheel, int part, int out, int slot, int term) {
  return std::sin(1.0 + wheel * 0.37 + part * 1.1 + out * 0.53 + slot * 2.3 + term * 0.71);
}

double affine(int wheel, int part, int out, int slot, const double* x) {
  double f = coef(wheel, part, out, slot, 0);
  for (int v = 0; v < 6; ++v) f += coef(wheel, part, out, slot, v + 1) * scaled(v, x);
  return f;
}

// Full quadratic in the scaled variables, cross terms included.
double quadratic(int wheel, int part, int out, int slot, const double* x) {
  double f = affine(wheel, part, out, slot, x);
  int term = 10;
  for (int i = 0; i < 6; ++i)
    for (int j = i; j < 6; ++j) f += coef(wheel, part, out, slot, term++) * scaled(i, x) * scaled(j, x);
  return f;
}

// A 4-D table: y (non-uniform), load, xi, phi swept; roll and eta fixed.
FixtureSpec four_d_spec(int nodes) {
  FixtureSpec spec;
  std::vector<double> y = linspace(-0.01, 0.01, nodes + 1);
  for (std::size_t i = 1; i + 1 < y.size(); ++i) y[i] += 0.3 * (0.02 / nodes) * std::sin(7.0 * i);
  spec.axes = {{0, y},
               {2, linspace(40e3, 120e3, nodes)},
               {3, linspace(-0.01, 0.01, nodes)},
               {5, linspace(-0.5, 0.5, nodes)}};
  spec.fixed = {{1, 0.0}, {4, 0.002}};
  return spec;
}

// Queries `samples` random states inside the table and returns the largest |error| relative to
// 1 + |exact| over every output of every slot and wheel.
template <typename F>
double max_error(const Table& table, const FixtureSpec& spec, F exact, int samples) {
  std::mt19937 rng(42);
  double worst = 0.0;
  for (int k = 0; k < samples; ++k) {
    double x[6] = {0, 0, 0, 0, 0, 0};
    for (const auto& [var, value] : spec.fixed) x[var] = value;
    for (const auto& [var, nodes] : spec.axes)
      x[var] = std::uniform_real_distribution<double>(nodes.front(), nodes.back())(rng);
    const State s{x[0], x[1], x[2], x[3], x[4], x[5]};
    for (int wheel = 0; wheel < 2; ++wheel) {
      const Result r = table.query(static_cast<Wheel>(wheel), s);
      EXPECT_EQ(r.status, 0u);
      for (int part : spec.parts)
        for (int o = 0; o < testing::part_outputs(part); ++o)
          for (int slot = 0; slot < spec.n_slots; ++slot) {
            // Parts see only their own variables: evaluate exact at the part's state.
            double xp[6];
            for (int v = 0; v < 6; ++v) xp[v] = x[v];
            const auto& pf = testing::part_formats()[part];
            for (const auto& [var, nodes] : spec.axes)
              if (!pf.uses[var]) xp[var] = 0.0;
            const double e = exact(wheel, part, o, slot, xp);
            const double got = r.contact[slot].value[testing::output_index(part, o)];
            worst = std::max(worst, std::abs(got - e) / (1.0 + std::abs(e)));
          }
    }
  }
  return worst;
}

// The fixture evaluates each part at its grid state, where variables the part does not use are
// not set by the sweep: make the value functions ignore them the same way.
template <typename F>
testing::ValueFn restricted(const FixtureSpec& spec, F f) {
  return [spec, f](int wheel, int part, int out, int slot, const double* x) {
    double xp[6];
    for (int v = 0; v < 6; ++v) xp[v] = x[v];
    const auto& pf = testing::part_formats()[part];
    for (const auto& [var, nodes] : spec.axes)
      if (!pf.uses[var]) xp[var] = 0.0;
    return f(wheel, part, out, slot, xp);
  };
}

TEST(Interpolate, MultilinearReproducesAffineFunctions) {
  TempFile file("affine");
  FixtureSpec spec = four_d_spec(4);
  spec.value = restricted(spec, affine);
  testing::write_fixture(file.path, spec);
  const Table table = Table::load(file.path);
  EXPECT_LT(max_error(table, spec, affine, 300), 1e-12);
}

TEST(Interpolate, CubicReproducesQuadratics) {
  TempFile file("quadratic");
  FixtureSpec spec = four_d_spec(4);
  spec.value = restricted(spec, quadratic);
  testing::write_fixture(file.path, spec);
  const Table table = Table::load(file.path, {Method::kCubic});
  EXPECT_LT(max_error(table, spec, quadratic, 200), 1e-11);
  // Multilinear cannot: a sanity check that the test would catch a wrong method.
  EXPECT_GT(max_error(Table::load(file.path), spec, quadratic, 50), 1e-4);
}

TEST(Interpolate, MonotoneCubicReproducesMonotoneQuadratics) {
  // Quadratics whose vertex lies far outside the table: monotone along every axis, and the
  // limiter (slope <= 3 x secant) stays inactive, so the result must be exact.
  auto monotone_quadratic = [](int wheel, int part, int out, int slot, const double* x) {
    double f = coef(wheel, part, out, slot, 0);
    for (int v = 0; v < 6; ++v) {
      const double u = scaled(v, x) + 4.0;  // scaled axes span about [-1, 1]: u in [3, 5]
      f += (0.5 + 0.4 * coef(wheel, part, out, slot, v + 1)) * u * u;
    }
    return f;
  };
  TempFile file("monotone");
  FixtureSpec spec = four_d_spec(4);
  spec.axes[1].second = linspace(-100e3, 100e3, 4);  // load scaled to [-1, 1] like the others
  spec.value = restricted(spec, monotone_quadratic);
  testing::write_fixture(file.path, spec);
  const Table table = Table::load(file.path, {Method::kMonotoneCubic});
  EXPECT_LT(max_error(table, spec, monotone_quadratic, 200), 1e-11);
}

// Error of a smooth non-polynomial function on grids of n and 2n-1 nodes per axis: halving the
// spacing must divide it by ~2^order.
double observed_order(Method method, int n) {
  auto smooth = [](int, int, int, int, const double* x) {
    return std::sin(2.0 * scaled(0, x) + 0.3) * std::cos(1.5 * scaled(3, x)) + std::exp(0.5 * scaled(5, x));
  };
  double err[2];
  for (int level = 0; level < 2; ++level) {
    const int nodes = level == 0 ? n : 2 * n - 1;
    TempFile file("order" + std::to_string(level));
    FixtureSpec spec;
    spec.axes = {{0, linspace(-0.01, 0.01, nodes)},
                 {3, linspace(-0.01, 0.01, nodes)},
                 {5, linspace(-1.0, 1.0, nodes)}};
    spec.fixed = {{1, 0.0}, {2, 78500.0}, {4, 0.0}};
    spec.parts = {2};  // creep: tabulated over all three
    spec.n_slots = 1;
    spec.value = smooth;
    testing::write_fixture(file.path, spec);
    // Interior points only: the one-sided edge slopes of the cubic are a lower order.
    spec.axes = {{0, linspace(-0.008, 0.008, 2)}, {3, linspace(-0.008, 0.008, 2)},
                 {5, linspace(-0.8, 0.8, 2)}};
    err[level] = max_error(Table::load(file.path, {method}), spec, smooth, 400);
  }
  return std::log2(err[0] / err[1]);
}

TEST(Interpolate, MultilinearConvergesAtSecondOrder) {
  const double order = observed_order(Method::kLinear, 9);
  EXPECT_GT(order, 1.8);
  EXPECT_LT(order, 2.3);
}

TEST(Interpolate, CubicConvergesAtThirdOrderOrBetter) {
  EXPECT_GT(observed_order(Method::kCubic, 9), 2.7);
}

TEST(Interpolate, MonotoneCubicConvergesAtLeastLikeLinear) {
  // The test function has extrema inside the table, where the limiter sets the slope to 0: the
  // local error there is O(h^2), the known price of monotonicity.
  EXPECT_GT(observed_order(Method::kMonotoneCubic, 9), 1.8);
}

// The monotone cubic of one axis, written out plainly (divisions, no weights tables) on uniform
// nodes: the parabola slopes (centred, else one-sided), limited to [0, 3] x the secants on both
// sides (0 at an extremum), then the Hermite basis.
double reference_monotone(const std::vector<double>& x, const std::vector<double>& f, double q) {
  const int n = static_cast<int>(x.size());
  int i = 0;
  while (i + 2 < n && q >= x[i + 1]) ++i;
  const double h = x[i + 1] - x[i], t = (q - x[i]) / h;
  const bool left = i >= 1, right = i + 2 <= n - 1;
  const double delta = (f[i + 1] - f[i]) / h;
  double m0 = left ? (f[i + 1] - f[i - 1]) / (2 * h) : right ? (-3 * f[i] + 4 * f[i + 1] - f[i + 2]) / (2 * h) : delta;
  double m1 = right ? (f[i + 2] - f[i]) / (2 * h) : left ? (3 * f[i + 1] - 4 * f[i] + f[i - 1]) / (2 * h) : delta;
  auto limit = [](double m, double a, double b) {
    if (a * b <= 0.0) return 0.0;
    const double sign = b > 0.0 ? 1.0 : -1.0;
    return sign * std::min(std::max(m * sign, 0.0), 3.0 * std::min(std::abs(a), std::abs(b)));
  };
  m0 = limit(m0, left ? (f[i] - f[i - 1]) / h : delta, delta);
  m1 = limit(m1, delta, right ? (f[i + 2] - f[i + 1]) / h : delta);
  const double t2 = t * t, t3 = t2 * t;
  return (2 * t3 - 3 * t2 + 1) * f[i] + (-2 * t3 + 3 * t2) * f[i + 1] + (t3 - 2 * t2 + t) * h * m0 +
         (t3 - t2) * h * m1;
}

TEST(Interpolate, MonotoneCubicEqualsAPlainReference) {
  // Two axes (y, xi) with extrema and steep steps inside, so the limiter acts on many stencils:
  // the lookup (secants by reciprocal widths, two or four values per instruction) against the
  // plain reference above, xi first (the last axis), then y, at random states.
  auto f = [](int wheel, int part, int out, int slot, const double* x) {
    return std::sin(3.0 * scaled(0, x) + out + wheel) * std::tanh(4.0 * scaled(3, x) - 0.5 * out + slot) +
           0.3 * part;
  };
  TempFile file("monotone_reference");
  FixtureSpec spec;
  spec.axes = {{0, linspace(-0.01, 0.01, 9)}, {3, linspace(-0.01, 0.01, 7)}};
  spec.fixed = {{1, 0.0}, {2, 78500.0}, {4, 0.0}, {5, 0.0}};
  spec.parts = {2};
  spec.n_slots = 2;
  spec.value = f;
  testing::write_fixture(file.path, spec);
  const Table table = Table::load(file.path, {Method::kMonotoneCubic});
  const std::vector<double>& ys = spec.axes[0].second;
  const std::vector<double>& xis = spec.axes[1].second;
  std::mt19937 rng(31);
  double worst = 0.0;
  for (int k = 0; k < 300; ++k) {
    const double y = std::uniform_real_distribution<double>(ys.front(), ys.back())(rng);
    const double xi = std::uniform_real_distribution<double>(xis.front(), xis.back())(rng);
    State s = table.default_state();
    s.y = y, s.xi = xi;
    for (int wheel = 0; wheel < 2; ++wheel) {
      const Result r = table.query(static_cast<Wheel>(wheel), s);
      for (int slot = 0; slot < spec.n_slots; ++slot)
        for (int o = 0; o < testing::part_outputs(2); ++o) {
          std::vector<double> along_y;  // the xi line at every y node
          for (double yn : ys) {
            std::vector<double> line;
            for (double xn : xis) {
              const double x[6] = {yn, 0.0, 78500.0, xn, 0.0, 0.0};
              line.push_back(f(wheel, 2, o, slot, x));
            }
            along_y.push_back(reference_monotone(xis, line, xi));
          }
          const double expected = reference_monotone(ys, along_y, y);
          const double got = r.contact[slot].value[testing::output_index(2, o)];
          worst = std::max(worst, std::abs(got - expected) / (1.0 + std::abs(expected)));
        }
    }
  }
  EXPECT_LT(worst, 1e-12);
  std::printf("monotone cubic against the plain reference: worst %.2e of 1 + |value|\n", worst);
}

TEST(Interpolate, MonotoneCubicDoesNotOvershootASteep) {
  // A step along y (tread -> flange style jump): cubic rings, monotone cubic stays in [0, 1].
  TempFile file("step");
  FixtureSpec spec;
  spec.axes = {{0, linspace(-0.01, 0.01, 11)}};
  spec.fixed = {{1, 0.0}};
  spec.parts = {0};
  spec.n_slots = 1;
  spec.value = [](int, int, int, int, const double* x) { return x[0] > 0.001 ? 1.0 : 0.0; };
  testing::write_fixture(file.path, spec);
  const Table mono = Table::load(file.path, {Method::kMonotoneCubic});
  const Table cubic = Table::load(file.path, {Method::kCubic});
  double lo = 0, hi = 0, cubic_hi = 0;
  for (int k = 0; k <= 1000; ++k) {
    const State s{-0.01 + 0.02 * k / 1000.0, 0, 0, 0, 0, 0};
    const double v = mono.query(Wheel::kLeft, s).contact[0].value[kContactAngle];
    lo = std::min(lo, v);
    hi = std::max(hi, v);
    cubic_hi = std::max(cubic_hi, cubic.query(Wheel::kLeft, s).contact[0].value[kContactAngle]);
  }
  EXPECT_GE(lo, 0.0);
  EXPECT_LE(hi, 1.0);
  EXPECT_GT(cubic_hi, 1.01);  // the unlimited cubic does overshoot: the limiter is doing work
}

// A y-only geometry table holding `value` (one slot): for the double-range tests below.
std::string write_y_table(TempFile& file, testing::ValueFn value) {
  FixtureSpec spec;
  spec.axes = {{0, linspace(-0.01, 0.01, 9)}};
  spec.fixed = {{1, 0.0}};
  spec.parts = {0};
  spec.n_slots = 1;
  spec.value = std::move(value);
  testing::write_fixture(file.path, spec);
  return file.path;
}

// Values near the top of the double range: the monotone cubic's secants and slopes (differences
// over a 2.5 mm spacing, about 400 x the values) overflowed to inf, inf - inf gave NaN, and the
// query returned NaN flagged converged. Now it interpolates them like any others.
TEST(Interpolate, MonotoneCubicOfValuesNearTheDoubleRangeIsFinite) {
  TempFile file("huge");
  const auto line = [](int, int, int, int, const double* x) { return 1e307 * (1.0 + 10.0 * x[0]); };
  const Table mono = Table::load(write_y_table(file, line), {Method::kMonotoneCubic});
  for (const double y : {-0.0093, -0.0012, 0.0, 0.0031, 0.0099}) {
    const Contact c = mono.query(Wheel::kLeft, State{y, 0, 0, 0, 0, 0}).contact[0];
    EXPECT_NEAR(c.value[kContactAngle], 1e307 * (1.0 + 10.0 * y), 1e-12 * 1e307) << "y = " << y;
    EXPECT_TRUE(c.status & status::kConverged) << "y = " << y;
  }
  // The same values a millionth as large give the same digits: the scaling is exact.
  TempFile small_file("huge_scaled");
  const auto small = [](int, int, int, int, const double* x) { return 1e301 * (1.0 + 10.0 * x[0]); };
  const Table mono_small = Table::load(write_y_table(small_file, small), {Method::kMonotoneCubic});
  const double v = mono.query(Wheel::kLeft, State{0.0031, 0, 0, 0, 0, 0}).contact[0].value[kContactAngle];
  const double w = mono_small.query(Wheel::kLeft, State{0.0031, 0, 0, 0, 0, 0}).contact[0].value[kContactAngle];
  EXPECT_NEAR(v / w, 1e6, 1e-9);
}

// A cubic overshooting beyond the largest double: the contact is failed with zero outputs, never
// an infinity flagged converged.
TEST(Interpolate, CubicOvershootBeyondTheDoubleRangeIsFailed) {
  TempFile file("overshoot");
  const auto bump = [](int, int, int, int, const double* x) { return std::abs(x[0]) < 0.003 ? 1.7e308 : 0.0; };
  const Table cubic = Table::load(write_y_table(file, bump), {Method::kCubic});
  bool overshoot_seen = false;
  for (int k = 0; k <= 200; ++k) {
    const Contact c = cubic.query(Wheel::kLeft, State{-0.01 + 0.02 * k / 200.0, 0, 0, 0, 0, 0}).contact[0];
    for (const double v : c.value) ASSERT_TRUE(std::isfinite(v)) << k;
    if (c.status & status::kFailed) {
      overshoot_seen = true;
      EXPECT_FALSE(c.status & status::kConverged);
      EXPECT_EQ(c.value[kContactAngle], 0.0);
    }
  }
  EXPECT_TRUE(overshoot_seen);  // the bump does overshoot somewhere
}

// The table the hostile probe found (a well-formed table, rolling radius near 1e306): every
// method answers finite values at the probe's state.
TEST(Interpolate, HostileTableNearTheDoubleRangeAnswersFinite) {
  std::string path = RAILTAB_TEST_DATA_DIR;  // += rather than operator+: GCC 12 bug 109299 warns of the latter
  path += "/monotone_cubic_rr1e306.h5";
  for (Method method : {Method::kLinear, Method::kCubic, Method::kMonotoneCubic}) {
    const Table table = Table::load(path, {method});
    State s = table.default_state();
    s.y = -0.004;
    s.load = 60000.0;
    s.xi = -0.002;
    s.eta = -0.001;
    const Result r = table.query(Wheel::kLeft, s);
    for (int slot = 0; slot < r.n_slots; ++slot) {
      for (const double v : r.contact[slot].value) EXPECT_TRUE(std::isfinite(v)) << static_cast<int>(method);
      if (!(r.contact[slot].status & status::kFailed)) {
        EXPECT_NE(r.contact[slot].value[kRollingRadius], 0.0);
      }
    }
  }
}

}  // namespace
}  // namespace railtab::lookup
