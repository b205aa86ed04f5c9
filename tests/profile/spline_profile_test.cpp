// SPDX-License-Identifier: Apache-2.0
// Tests of spline profiles through measured points (src/profile/curves/spline_profile.hpp).
#include "profile/curves/spline_profile.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <numbers>
#include <random>
#include <vector>

#include "core/check.hpp"
#include "derivative_check.hpp"

namespace railtab {
namespace {

// Uneven knots over [-0.03, 0.04] m, spacing 0.3 .. 0.7 mm.
std::vector<double> uneven_knots() {
  std::vector<double> u;
  double x = -0.03;
  for (int i = 0; x <= 0.04; ++i) {
    u.push_back(x);
    x += 0.0003 + 0.0004 * std::fabs(std::sin(1.7 * i));
  }
  return u;
}

TEST(SplineProfile, InterpolatingReproducesCubicExactly) {
  // z = c0 + c1 u + c2 u^2 + c3 u^3 with profile-like sizes.
  const double c0 = 1e-3, c1 = -0.03, c2 = 2.0, c3 = -40.0;
  auto f = [&](double x) { return c0 + x * (c1 + x * (c2 + x * c3)); };
  auto df = [&](double x) { return c1 + x * (2.0 * c2 + 3.0 * c3 * x); };
  auto d2f = [&](double x) { return 2.0 * c2 + 6.0 * c3 * x; };
  std::vector<double> u = uneven_knots();
  std::vector<double> z;
  for (double x : u) z.push_back(f(x));
  const SplineProfile s("cubic", ProfileKind::rail, u, z);
  EXPECT_DOUBLE_EQ(s.u_min(), u.front());
  EXPECT_DOUBLE_EQ(s.u_max(), u.back());
  for (double x = s.u_min(); x <= s.u_max(); x += 1.3e-5) {
    const ProfileSample p = s.eval(x);
    EXPECT_NEAR(p.z, f(x), 1e-14) << x;
    EXPECT_NEAR(p.dz, df(x), 1e-11) << x;
    EXPECT_NEAR(p.d2z, d2f(x), 1e-7) << x;
  }
  EXPECT_NEAR(s.eval(s.u_max()).z, f(u.back()), 1e-14);
}

TEST(SplineProfile, FourPointsGiveTheCubicThroughThem) {
  const std::vector<double> u = {0.0, 0.001, 0.003, 0.004};
  std::vector<double> z;
  for (double x : u) z.push_back(x * x - 200.0 * x * x * x);
  const SplineProfile s("four", ProfileKind::wheel, u, z);
  EXPECT_NEAR(s.eval(0.002).z, 0.002 * 0.002 - 200.0 * 0.002 * 0.002 * 0.002, 1e-16);
  EXPECT_NEAR(s.eval(0.002).d2z, 2.0 - 1200.0 * 0.002, 1e-9);
}

TEST(SplineProfile, SmoothingKeepsStraightLinesAndPassesLongWaves) {
  // The penalty vanishes on lines: a smoothing spline of a line is the line.
  std::vector<double> u = uneven_knots();
  std::vector<double> z;
  for (double x : u) z.push_back(0.002 - 0.05 * x);
  const SplineProfile line("line", ProfileKind::rail, u, z, 0.005);
  for (double x : {-0.03, -0.01, 0.0, 0.02, u.back()}) {
    EXPECT_NEAR(line.eval(x).z, 0.002 - 0.05 * x, 1e-15);
    EXPECT_NEAR(line.eval(x).d2z, 0.0, 1e-9);
  }
}

TEST(SplineProfile, SmoothingFiltersNoiseOnACircleAndKeepsItsRadius) {
  // Arc of R = 80 mm (the rail shoulder) sampled every 0.4 mm, with 2 um Gaussian noise as from
  // a profile gauge. Interpolating through the noise gives curvature noise of order
  // noise / spacing^2, several times 1/R; smoothing must remove it while the radius stays.
  const double radius = 0.080;
  const double sigma = 2e-6;
  const double spacing = 0.0004;
  std::mt19937 rng(12345);
  std::normal_distribution<double> noise(0.0, sigma);
  std::vector<double> u;
  std::vector<double> z;
  for (double x = -0.025; x <= 0.025 + 1e-12; x += spacing) {
    u.push_back(x);
    z.push_back(std::sqrt(radius * radius - x * x) - radius + noise(rng));
  }
  // Compare away from the ends, where the natural end condition (zero curvature) of the
  // smoothing spline pulls the curvature over about one filter length.
  auto rms_curvature_error = [&](const Profile& p, double* mean_radius) {
    double sum2 = 0.0;
    double sum_k = 0.0;
    int count = 0;
    for (double x = -0.017; x <= 0.017; x += 0.00005) {
      const double k = p.curvature(x);
      sum2 += (k + 1.0 / radius) * (k + 1.0 / radius);
      sum_k += k;
      ++count;
    }
    *mean_radius = -count / sum_k;
    return std::sqrt(sum2 / count);
  };
  const SplineProfile raw("raw", ProfileKind::rail, u, z);
  double r_raw = 0.0;
  const double e_raw = rms_curvature_error(raw, &r_raw);
  EXPECT_GT(e_raw, 2.0 / radius);  // the noise is really there
  for (double filter : {0.004, 0.008}) {
    const SplineProfile smooth("smooth", ProfileKind::rail, u, z, filter);
    double r_smooth = 0.0;
    const double e_smooth = rms_curvature_error(smooth, &r_smooth);
    // Expected residual for a low-pass 1/(1 + (k/kc)^4), kc = 2 pi / L, on white noise of
    // density sigma^2 * spacing: var = sigma^2 spacing kc^5 / (2 pi) * int x^4/(1+x^4)^2 dx,
    // the integral over the real line being pi / (4 sqrt 2). This checks lambda = (L/2pi)^4
    // and the spacing-independent weights, not only "smoother".
    const double kc = 2.0 * std::numbers::pi / filter;
    const double expected = std::sqrt(sigma * sigma * spacing * std::pow(kc, 5) / (2.0 * std::numbers::pi) *
                                      std::numbers::pi / (4.0 * std::sqrt(2.0)));
    std::cout << "noisy R80, L_filt " << filter * 1e3 << " mm: rms curvature error raw " << e_raw
              << " 1/m, smoothed " << e_smooth << " 1/m (white-noise theory " << expected
              << "); mean radius raw " << r_raw * 1e3 << " mm, smoothed " << r_smooth * 1e3
              << " mm\n";
    EXPECT_LT(e_smooth, 0.1 * e_raw);
    EXPECT_GT(e_smooth, 0.6 * expected);
    EXPECT_LT(e_smooth, 1.5 * expected);
    EXPECT_NEAR(r_smooth, radius, 0.01 * radius);
    // The smoothed curve stays within a couple of noise levels of the true circle.
    for (double x = -0.02; x <= 0.02; x += 0.001) {
      EXPECT_NEAR(smooth.eval(x).z, std::sqrt(radius * radius - x * x) - radius, 2.0 * sigma) << x;
    }
  }
}

TEST(SplineProfile, DerivativesMatchFiniteDifferences) {
  std::vector<double> u = uneven_knots();
  std::vector<double> z;
  for (double x : u) z.push_back(0.01 * std::sin(60.0 * x) + 0.002 * std::cos(300.0 * x));
  const SplineProfile interp("interp", ProfileKind::rail, u, z);
  const SplineProfile smooth("smooth", ProfileKind::rail, u, z, 0.003);
  // The third derivative jumps at the knots: skip them as kinks.
  test::expect_derivatives_match_differences(interp, u);
  test::expect_derivatives_match_differences(smooth, u);
}

TEST(SplineProfile, RejectsBadPoints) {
  const std::vector<double> u = {0.0, 0.001, 0.002, 0.003};
  const std::vector<double> z = {0.0, 0.0, 0.0, 0.0};
  EXPECT_THROW(SplineProfile("few", ProfileKind::rail, {0.0, 0.001, 0.002}, {0.0, 0.0, 0.0}), Error);
  EXPECT_THROW(SplineProfile("sizes", ProfileKind::rail, u, {0.0, 0.0, 0.0}), Error);
  EXPECT_THROW(SplineProfile("order", ProfileKind::rail, {0.0, 0.002, 0.001, 0.003}, z), Error);
  EXPECT_THROW(SplineProfile("dup", ProfileKind::rail, {0.0, 0.001, 0.001, 0.003}, z), Error);
  EXPECT_THROW(SplineProfile("nan", ProfileKind::rail, u, {0.0, std::nan(""), 0.0, 0.0}), Error);
  EXPECT_THROW(SplineProfile("smooth", ProfileKind::rail, u, z, -1.0), Error);
  try {
    SplineProfile("order", ProfileKind::rail, {0.0, 0.002, 0.001, 0.003}, z);
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("point 2"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace railtab
