// SPDX-License-Identifier: Apache-2.0
// The continuity measure's confirmation by refinement (stability_common.hpp: first_jump with
// refined_jump): on synthetic functions sampled like the sweeps (0.05 mm steps), a discontinuity
// is still reported wherever it falls in the step, and a steep but smooth change that the
// neighbour-slope measure alone reports (a narrow tanh) is not.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "stability_common.hpp"

namespace railtab::stability {
namespace {

constexpr double kStep = 0.05e-3;  // [m], the sweeps' step

const std::vector<double>& ys() {
  static const std::vector<double> y = grid(-1e-3, 1e-3, kStep);
  return y;
}

// first_jump over f sampled on ys(), without and with the refinement.
template <class F>
int suspected(F f) {
  std::vector<double> q;
  for (double y : ys()) q.push_back(f(y));
  return first_jump(q, [](int) { return false; });
}
template <class F>
int confirmed(F f) {
  std::vector<double> q;
  for (double y : ys()) q.push_back(f(y));
  return first_jump(q, [](int) { return false; }, [&](int k) {
    return refined_jump(f, ys()[k], ys()[k + 1], [](double, double) { return false; });
  });
}

// A unit step on a smooth slope (1/10 of the step's height per sample step) at several places
// inside one sample step, including exactly at the first bisection point with the value there
// halfway between the sides (the case a 50 % rule would miss: each half keeps half the jump).
TEST(JumpRefinement, StepFunctionIsAJump) {
  const int k = 20;  // the step [ys[20], ys[21]]
  const double a = ys()[k], b = ys()[k + 1];
  for (double t : {0.013, 0.25, 0.4999, 0.77, 0.999}) {
    const double y0 = a + t * (b - a);
    auto f = [&](double y) { return 2.0 * y / kStep + (y >= y0 ? 1.0 : 0.0) * 10.0; };
    EXPECT_EQ(suspected(f), k) << "t = " << t;
    EXPECT_EQ(confirmed(f), k) << "t = " << t;
  }
  const double mid = 0.5 * (a + b);  // refined_jump's first midpoint, bit for bit
  auto f = [&](double y) { return 2.0 * y / kStep + (y > mid ? 10.0 : y == mid ? 5.0 : 0.0); };
  EXPECT_EQ(confirmed(f), k);
  const double r = refined_step_ratio(f, a, b, [](double, double) { return false; });
  EXPECT_GT(r, 0.375);  // the half of the jump each side keeps, plus a sliver of slope
  EXPECT_LT(r, 0.5);
}

// tanh of width w centred in a step. w = 10 um (1/5 of the step): the neighbour-slope measure
// alone reports it (the step across the centre is 1.97 A, its neighbours < 0.02 A), the
// refinement (1/32 of the step, 1.6 um) resolves it and does not. w = 0.2 um (1/250 of the step,
// below the resolution) is a step at this resolution and is reported.
TEST(JumpRefinement, SteepSmoothFunctionIsNotAJump) {
  const int k = 20;
  for (double t : {0.35, 0.5, 0.63}) {  // nearer a sample the neighbours see the slope: not suspected
    const double y0 = ys()[k] + t * kStep;
    auto smooth = [&](double y) { return 3.0 * std::tanh((y - y0) / 10e-6); };
    EXPECT_GE(suspected(smooth), 0) << "t = " << t;
    EXPECT_EQ(confirmed(smooth), -1) << "t = " << t;
    auto sharp = [&](double y) { return 3.0 * std::tanh((y - y0) / 0.2e-6); };
    EXPECT_EQ(confirmed(sharp), suspected(sharp)) << "t = " << t;
    EXPECT_GE(confirmed(sharp), 0) << "t = " << t;
  }
}

// A kind of change the refinement must leave to the exemptions: when the kept half is exempt
// (the samples at its ends differ in character), the step is exempt, not a jump.
TEST(JumpRefinement, ExemptSubIntervalExemptsTheStep) {
  const double y0 = ys()[20] + 0.3 * kStep;
  auto f = [&](double y) { return y >= y0 ? 1.0 : 0.0; };
  const double r = refined_step_ratio(f, ys()[20], ys()[21],
                                      [&](double a, double b) { return a < y0 && b >= y0; });
  EXPECT_EQ(r, 0.0);
  EXPECT_EQ(refined_step_ratio(f, ys()[20], ys()[21], [](double, double) { return false; }), 1.0);
}

}  // namespace
}  // namespace railtab::stability
