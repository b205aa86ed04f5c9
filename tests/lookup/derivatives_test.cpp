// SPDX-License-Identifier: Apache-2.0
// Table::query_derivatives (lookup/src/derivatives.cpp) on synthetic tables over all six state
// variables: exact reproduction (multilinear: the gradient of an affine function; cubic: of a
// quadratic, cross terms too), central finite differences of the same interpolant inside cells,
// the node-face rule, zeros for fixed and clamped variables, the values of query() unchanged, the
// monotone cubic refused, and the C API. The default scene's table (normalised creep coordinates,
// contact jumps): tests/table_accuracy/derivatives_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>

#include "lookup/lookup_test_util.hpp"
#include "lookup/table_fixture.hpp"
#include "railtab/lookup.hpp"
#include "railtab_lookup.h"

namespace railtab::lookup::derivatives_test {  // own namespace: unity builds compile several test files as one
namespace {

using testing::FixtureSpec;
using testing::TempFile;

// Non-uniform y and creepage axes, roll and load tabulated: every variable is an axis.
FixtureSpec six_axis_spec(testing::ValueFn value) {
  FixtureSpec spec;
  spec.axes = {{0, {-0.01, -0.006, -0.001, 0.002, 0.0045, 0.01}},
               {1, {-0.004, -0.001, 0.0015, 0.004}},
               {2, {40e3, 75e3, 120e3}},
               {3, {-0.006, -0.002, 0.0005, 0.003, 0.006}},
               {4, {-0.006, -0.001, 0.002, 0.006}},
               {5, {-0.6, 0.1, 0.6}}};
  spec.value = std::move(value);
  return spec;
}

// The fixture tables' variables (table_fixture.hpp): every one but yaw, which they do not hold (its
// derivative is 0, like any untabulated variable's).
constexpr int kFixtureVars = 6;
// Scale of each variable so that the test functions vary by O(1) over the table.
constexpr double kScale[kNumVariables] = {100.0, 250.0, 1e-5, 150.0, 150.0, 1.5, 1.0};

// The (part, output) index mixed into a test function, so every output differs.
double tag(int wheel, int part, int out, int slot) { return 1.0 + 0.3 * part + 0.07 * out + 0.5 * slot - 0.2 * wheel; }

double affine(int wheel, int part, int out, int slot, const double* x) {
  const double c = tag(wheel, part, out, slot);
  double f = 3.0 * c;
  for (int v = 0; v < kFixtureVars; ++v) f += c * (v + 1) * kScale[v] * x[v];
  return f;
}

double affine_slope(int wheel, int part, int out, int slot, int v) {
  return tag(wheel, part, out, slot) * (v + 1) * kScale[v];
}

// A quadratic with squares and cross terms of every pair.
double quadratic(int wheel, int part, int out, int slot, const double* x) {
  const double c = tag(wheel, part, out, slot);
  double s[kFixtureVars], f = c;
  for (int v = 0; v < kFixtureVars; ++v) s[v] = kScale[v] * x[v];
  for (int v = 0; v < kFixtureVars; ++v) {
    f += c * (v + 1) * s[v] + 0.5 * c * s[v] * s[v];
    for (int u = v + 1; u < kFixtureVars; ++u) f += 0.25 * c * s[u] * s[v];
  }
  return f;
}

double quadratic_slope(int wheel, int part, int out, int slot, int v, const double* x) {
  const double c = tag(wheel, part, out, slot);
  double s[kFixtureVars];
  for (int u = 0; u < kFixtureVars; ++u) s[u] = kScale[u] * x[u];
  double g = c * (v + 1) + c * s[v];
  for (int u = 0; u < kFixtureVars; ++u)
    if (u != v) g += 0.25 * c * s[u];
  return g * kScale[v];
}

double smooth(int wheel, int part, int out, int slot, const double* x) {
  const double c = tag(wheel, part, out, slot);
  return c * (std::sin(200.0 * x[0] + 0.3 * slot) + std::cos(300.0 * x[1]) * (1.0 + 1e-5 * x[2]) +
              std::sin(400.0 * x[3]) * std::cos(250.0 * x[4]) + 0.4 * x[5] * x[5] + (wheel ? 0.2 : -0.1) * x[0] * x[3] * 1e4);
}

void set(State& s, int v, double x) {
  double* p[kNumVariables] = {&s.y, &s.roll, &s.load, &s.xi, &s.eta, &s.phi, &s.yaw};
  *p[v] = x;
}
double get(const State& s, int v) {
  const double p[kNumVariables] = {s.y, s.roll, s.load, s.xi, s.eta, s.phi, s.yaw};
  return p[v];
}

// Random states strictly inside the table's range.
std::vector<State> random_states(const Table& t, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<State> out;
  for (int k = 0; k < n; ++k) {
    State s = t.default_state();
    for (const AxisInfo& a : t.axes())
      for (int v = 0; v < kNumVariables; ++v)
        if (a.name == variable_name(v)) {
          std::uniform_real_distribution<double> x(a.nodes.front(), a.nodes.back());
          set(s, v, x(rng));
        }
    out.push_back(s);
  }
  return out;
}

// The part of output o (geometry: y, roll; normal: + load; creep, wear: all).
int part_of(int o) { return static_cast<int>(output_part(static_cast<Output>(o))); }
int part_local(int o) {
  static const int first[kNumParts] = {kContactAngle, kNormalForce, kFx, kWearRate};
  return o - first[part_of(o)];
}
bool part_uses(int part, int v) {
  static const bool uses[kNumParts][kNumVariables] = {{true, true, false, false, false, false, false},
                                                      {true, true, true, false, false, false, false},
                                                      {true, true, true, true, true, true, false},
                                                      {true, true, true, true, true, true, false}};
  return uses[part][v];
}

TEST(Derivatives, LinearGivesTheGradientOfAnAffineFunctionExactly) {
  TempFile file("affine");
  testing::write_fixture(file.path, six_axis_spec(affine));
  const Table t = Table::load(file.path);
  Result r;
  Derivatives d;
  int checked = 0;
  for (const State& s : random_states(t, 200, 1))
    for (int w = 0; w < 2; ++w) {
      ASSERT_TRUE(t.query_derivatives(static_cast<Wheel>(w), s, r, d));
      for (int slot = 0; slot < r.n_slots; ++slot)
        for (int o = 0; o < kNumOutputs; ++o)
          for (int v = 0; v < kNumVariables; ++v) {
            const int p = part_of(o);
            const double expected = part_uses(p, v) ? affine_slope(w, p, part_local(o), slot, v) : 0.0;
            ASSERT_NEAR(d.d[slot][o][v], expected, 1e-9 * std::abs(affine_slope(w, p, part_local(o), slot, v)))
                << "wheel " << w << " slot " << slot << " " << output_name(static_cast<Output>(o)) << " d/d"
                << variable_name(v);
            ++checked;
          }
    }
  EXPECT_EQ(checked, 200 * 2 * 2 * kNumOutputs * kNumVariables);
}

TEST(Derivatives, CubicGivesTheGradientOfAQuadraticExactly) {
  TempFile file("quadratic");
  testing::write_fixture(file.path, six_axis_spec(quadratic));
  const Table t = Table::load(file.path, {Method::kCubic});
  Result r;
  Derivatives d;
  for (const State& s : random_states(t, 100, 2)) {
    const double x[kNumVariables] = {s.y, s.roll, s.load, s.xi, s.eta, s.phi, s.yaw};
    for (int w = 0; w < 2; ++w) {
      ASSERT_TRUE(t.query_derivatives(static_cast<Wheel>(w), s, r, d));
      for (int slot = 0; slot < r.n_slots; ++slot)
        for (int o = 0; o < kNumOutputs; ++o)
          for (int v = 0; v < kNumVariables; ++v) {
            const int p = part_of(o);
            if (!part_uses(p, v)) {
              ASSERT_EQ(d.d[slot][o][v], 0.0);
              continue;
            }
            // The quadratic restricted to the part's variables (the others at their fixed 0).
            double xp[kNumVariables];
            for (int u = 0; u < kNumVariables; ++u) xp[u] = part_uses(p, u) ? x[u] : 0.0;
            const double expected = quadratic_slope(w, p, part_local(o), slot, v, xp);
            ASSERT_NEAR(d.d[slot][o][v], expected, 1e-8 * (std::abs(expected) + kScale[v]))
                << "wheel " << w << " slot " << slot << " " << output_name(static_cast<Output>(o)) << " d/d"
                << variable_name(v);
          }
    }
  }
}

// Central differences of query() itself against query_derivatives, at random states with the
// two difference points in the query's cell (a step of 1e-6 of the smallest cell).
void expect_finite_differences(Method method, double tolerance) {
  TempFile file("smooth");
  testing::write_fixture(file.path, six_axis_spec(smooth));
  const Table t = Table::load(file.path, {method});
  double min_width[kNumVariables] = {};
  for (const AxisInfo& a : t.axes())
    for (int v = 0; v < kNumVariables; ++v)
      if (a.name == variable_name(v)) {
        min_width[v] = a.nodes.back() - a.nodes.front();
        for (std::size_t i = 0; i + 1 < a.nodes.size(); ++i) min_width[v] = std::min(min_width[v], a.nodes[i + 1] - a.nodes[i]);
      }
  Result r, rp, rm;
  Derivatives d;
  double worst = 0.0;
  for (const State& s : random_states(t, 100, 3))
    for (int w = 0; w < 2; ++w) {
      const Wheel wheel = static_cast<Wheel>(w);
      ASSERT_TRUE(t.query_derivatives(wheel, s, r, d));
      for (int v = 0; v < kNumVariables; ++v) {
        if (min_width[v] == 0.0) continue;  // not an axis of the fixture (yaw)
        const double h = 1e-6 * min_width[v];
        State plus = s, minus = s;
        set(plus, v, get(s, v) + h);
        set(minus, v, get(s, v) - h);
        t.query(wheel, plus, rp);
        t.query(wheel, minus, rm);
        for (int slot = 0; slot < r.n_slots; ++slot)
          for (int o = 0; o < kNumOutputs; ++o) {
            const double fd = (rp.contact[slot].value[o] - rm.contact[slot].value[o]) / (2.0 * h);
            const double scale = std::abs(fd) + 1.0 / min_width[v];  // values are O(1)
            const double err = std::abs(d.d[slot][o][v] - fd) / scale;
            worst = std::max(worst, err);
            ASSERT_LT(err, tolerance) << output_name(static_cast<Output>(o)) << " d/d" << variable_name(v)
                                      << ": derivative " << d.d[slot][o][v] << ", central difference " << fd;
          }
      }
    }
  std::printf("worst |derivative - central difference| / scale: %.2e\n", worst);
}

TEST(Derivatives, LinearAgreesWithCentralDifferencesInsideCells) { expect_finite_differences(Method::kLinear, 1e-6); }
TEST(Derivatives, CubicAgreesWithCentralDifferencesInsideCells) { expect_finite_differences(Method::kCubic, 1e-6); }

TEST(Derivatives, ValuesAreTheQuerysAndNodeFacesTakeTheCellAbove) {
  TempFile file("faces");
  testing::write_fixture(file.path, six_axis_spec(smooth));
  const Table t = Table::load(file.path);
  State s = random_states(t, 1, 4)[0];
  const std::vector<double>& y = t.axes()[0].nodes;
  ASSERT_EQ(t.axes()[0].name, "y");
  Result r, plain, up;
  Derivatives d;
  for (std::size_t i = 0; i < y.size(); ++i) {
    s.y = y[i];
    ASSERT_TRUE(t.query_derivatives(Wheel::kLeft, s, r, d));
    t.query(Wheel::kLeft, s, plain);
    ASSERT_EQ(std::memcmp(&r, &plain, sizeof r), 0);  // the same bytes as query()
    // Interior and first nodes: the cell above (forward difference); the last node: the last cell.
    const bool last = i + 1 == y.size();
    State other = s;
    other.y = last ? y[i - 1] : y[i + 1];
    t.query(Wheel::kLeft, other, up);
    for (int o = 0; o < kNumOutputs; ++o) {
      const double secant = (up.contact[0].value[o] - r.contact[0].value[o]) / (other.y - s.y);
      EXPECT_NEAR(d.d[0][o][kY], secant, 1e-9 * (std::abs(secant) + 1.0)) << "node " << i << " " << output_name(static_cast<Output>(o));
    }
  }
}

TEST(Derivatives, FixedAndClampedVariablesGiveZero) {
  TempFile file("fixed");
  FixtureSpec spec = testing::scene_sized_spec();  // y, xi, eta, phi; roll and load fixed
  testing::write_fixture(file.path, spec);
  const Table t = Table::load(file.path);
  State s = t.default_state();
  s.y = 0.0013, s.xi = 0.0021, s.eta = -0.0017, s.phi = 0.3;
  Result r;
  Derivatives d;
  ASSERT_TRUE(t.query_derivatives(Wheel::kRight, s, r, d));
  bool any_y = false;
  for (int slot = 0; slot < r.n_slots; ++slot)
    for (int o = 0; o < kNumOutputs; ++o) {
      EXPECT_EQ(d.d[slot][o][kRoll], 0.0);
      EXPECT_EQ(d.d[slot][o][kLoad], 0.0);
      any_y |= d.d[slot][o][kY] != 0.0;
    }
  EXPECT_TRUE(any_y);
  s.y = 0.5;  // beyond the y axis: clamped to its edge, flagged, and constant in y there
  ASSERT_TRUE(t.query_derivatives(Wheel::kRight, s, r, d));
  EXPECT_TRUE(r.status & status::kOutOfRange);
  bool any_xi = false;
  for (int slot = 0; slot < r.n_slots; ++slot)
    for (int o = 0; o < kNumOutputs; ++o) {
      EXPECT_EQ(d.d[slot][o][kY], 0.0);
      any_xi |= d.d[slot][o][kXi] != 0.0;
    }
  EXPECT_TRUE(any_xi);
  s.xi = std::nan("");  // invalid input: zeros everywhere
  ASSERT_TRUE(t.query_derivatives(Wheel::kRight, s, r, d));
  for (int slot = 0; slot < r.n_slots; ++slot)
    for (int o = 0; o < kNumOutputs; ++o)
      for (int v = 0; v < kNumVariables; ++v) EXPECT_EQ(d.d[slot][o][v], 0.0);
}

TEST(Derivatives, MonotoneCubicIsRefused) {
  TempFile file("monotone");
  testing::write_fixture(file.path, testing::scene_sized_spec());
  const Table t = Table::load(file.path, {Method::kMonotoneCubic});
  EXPECT_FALSE(t.derivatives_supported());
  State s = t.default_state();
  s.y = 0.001;
  Result r, plain;
  Derivatives d;
  d.d[0][kFx][kY] = 1.0;
  EXPECT_FALSE(t.query_derivatives(Wheel::kLeft, s, r, d));
  EXPECT_EQ(d.d[0][kFx][kY], 0.0);
  t.query(Wheel::kLeft, s, plain);
  EXPECT_EQ(std::memcmp(&r, &plain, sizeof r), 0);

  railtab_lookup_table* c = nullptr;
  ASSERT_EQ(railtab_lookup_open(file.path.c_str(), RAILTAB_LOOKUP_MONOTONE_CUBIC, &c), RAILTAB_LOOKUP_OK);
  railtab_lookup_state cs{0.001, 0.0, 78500.0, 0.0, 0.0, 0.0, 0.0};
  railtab_lookup_result cr;
  railtab_lookup_derivatives cd;
  EXPECT_EQ(railtab_lookup_query_derivatives(c, RAILTAB_LOOKUP_LEFT, &cs, &cr, &cd), RAILTAB_LOOKUP_ERROR_ARGUMENT);
  EXPECT_NE(std::string(railtab_lookup_last_error()).find("MONOTONE_CUBIC"), std::string::npos) << railtab_lookup_last_error();
  railtab_lookup_close(c);
}

TEST(Derivatives, CApiGivesTheCppNumbers) {
  TempFile file("c_api");
  testing::write_fixture(file.path, six_axis_spec(smooth));
  const Table t = Table::load(file.path, {Method::kCubic});
  railtab_lookup_table* c = nullptr;
  ASSERT_EQ(railtab_lookup_open(file.path.c_str(), RAILTAB_LOOKUP_CUBIC, &c), RAILTAB_LOOKUP_OK);
  EXPECT_STREQ(railtab_lookup_var_name(RAILTAB_LOOKUP_VAR_ETA), "eta");
  EXPECT_STREQ(railtab_lookup_var_name(RAILTAB_LOOKUP_NUM_VARS), "?");
  for (const State& s : random_states(t, 20, 5)) {
    Result r;
    Derivatives d;
    ASSERT_TRUE(t.query_derivatives(Wheel::kRight, s, r, d));
    const railtab_lookup_state cs{s.y, s.roll, s.load, s.xi, s.eta, s.phi, s.yaw};
    railtab_lookup_result cr;
    railtab_lookup_derivatives cd;
    ASSERT_EQ(railtab_lookup_query_derivatives(c, RAILTAB_LOOKUP_RIGHT, &cs, &cr, &cd), RAILTAB_LOOKUP_OK);
    EXPECT_EQ(std::memcmp(&cr, &r, sizeof cr), 0);
    EXPECT_EQ(std::memcmp(&cd, &d, sizeof cd), 0);
    EXPECT_EQ(cd.d[1][RAILTAB_LOOKUP_FY][RAILTAB_LOOKUP_VAR_XI], d.d[1][kFy][kXi]);
    for (int slot = 0; slot < t.n_slots(); ++slot) {  // the one-slot twin: that slot's bytes
      railtab_lookup_contact cc;
      railtab_lookup_slot_derivatives csd;
      ASSERT_EQ(railtab_lookup_query_slot_derivatives(c, RAILTAB_LOOKUP_RIGHT, &cs, slot, &cc, &csd), RAILTAB_LOOKUP_OK);
      EXPECT_EQ(std::memcmp(&cc, &r.contact[slot], sizeof cc), 0);
      EXPECT_EQ(std::memcmp(csd.d, d.d[slot], sizeof csd.d), 0);
    }
  }
  railtab_lookup_state cs{0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  railtab_lookup_result cr;
  EXPECT_EQ(railtab_lookup_query_derivatives(c, 2, &cs, &cr, nullptr), RAILTAB_LOOKUP_ERROR_ARGUMENT);
  railtab_lookup_contact cc;
  railtab_lookup_slot_derivatives csd;
  EXPECT_EQ(railtab_lookup_query_slot_derivatives(c, RAILTAB_LOOKUP_LEFT, &cs, t.n_slots(), &cc, &csd),
            RAILTAB_LOOKUP_ERROR_ARGUMENT);
  EXPECT_NE(std::string(railtab_lookup_last_error()).find("slot outside"), std::string::npos) << railtab_lookup_last_error();
  railtab_lookup_close(c);
}

}  // namespace
}  // namespace railtab::lookup::derivatives_test
