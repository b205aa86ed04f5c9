// SPDX-License-Identifier: Apache-2.0
// The fused query of the STRIPES table's shape (lookup/src/fast_path.cpp, docs/lookup-speed.md)
// gives the same bytes as the generic path (RAILTAB_LOOKUP_NO_FAST_PATH=1 at load), for query and
// query_slot of every slot, both wheels, at random states in and out of range, on grid nodes,
// within 0.1 and 0.6 mm of every located jump (cut cells: the fast path has its own fused one-sided
// query for them, cut_slot) and with non-finite variables; with the AVX2 and the SSE2 kernels. And
// the derivative query's fused path against the generic one (DerivativesAgreeWithTheGenericPath).
//
// Run: build/<dir>/tests/test_table_accuracy --gtest_filter='FastPath*'
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>
#include <random>

#include "accuracy_util.hpp"
#include "adaptive/jump_locator.hpp"

namespace railtab::accuracy {
namespace {

struct Tables {
  std::vector<double> jump_y;  // every located jump, both wheels and loads
  std::optional<lk::Table> generic, fast, generic_sse2, fast_sse2;
};

const Tables& tables() {
  static const Tables t = [] {
    Tables x;
    const StripesSweep& d = stripes_sweep();
    const Scene& scene = d.scene;
    const ContactJumps& jumps = d.jumps;
    Table with_jumps = d.table;
    add_jumps(with_jumps, scene, jumps);  // as railtab generate (format 2.1)
    for (const auto& wheel : jumps.wheel)
      for (const auto& list : wheel)
        for (const ContactJump& j : list) x.jump_y.push_back(j.y);
    const std::filesystem::path path = temp_table_path("fast_path");
    write_for_lookup(with_jumps, path);
    auto load = [&](bool generic, bool sse2) {
      if (generic) ::setenv("RAILTAB_LOOKUP_NO_FAST_PATH", "1", 1);
      if (sse2) ::setenv("RAILTAB_LOOKUP_NO_AVX2", "1", 1);
      lk::Table table = lk::Table::load(path.string());
      ::unsetenv("RAILTAB_LOOKUP_NO_FAST_PATH");
      ::unsetenv("RAILTAB_LOOKUP_NO_AVX2");
      return table;
    };
    x.generic.emplace(load(true, false));
    x.fast.emplace(load(false, false));
    x.generic_sse2.emplace(load(true, true));
    x.fast_sse2.emplace(load(false, true));
    std::filesystem::remove(path);
    return x;
  }();
  return t;
}

void set(lk::State& s, const std::string& name, double x) {
  if (name == "y") s.y = x;
  else if (name == "load") s.load = x;
  else if (name == "xi") s.xi = x;
  else if (name == "eta") s.eta = x;
  else if (name == "phi") s.phi = x;
}

// States of kind k % 6: in range, 5 % beyond every axis, on grid nodes, within 0.1 or 0.6 mm of
// a jump, on a jump, a non-finite variable.
lk::State state(const lk::Table& t, const std::vector<double>& jump_y, int k, std::mt19937& rng) {
  lk::State s = t.default_state();
  const int kind = k % 6;
  for (const lk::AxisInfo& a : t.axes()) {
    const double lo = a.nodes.front(), hi = a.nodes.back(), w = hi - lo;
    double x = std::uniform_real_distribution<double>(lo, hi)(rng);
    if (kind == 1) x = std::uniform_real_distribution<double>(lo - 0.05 * w, hi + 0.05 * w)(rng);
    if (kind == 2) x = a.nodes[std::uniform_int_distribution<std::size_t>(0, a.nodes.size() - 1)(rng)];
    set(s, a.name, x);
  }
  if (kind == 3 || kind == 4) {
    const double y = jump_y[std::uniform_int_distribution<std::size_t>(0, jump_y.size() - 1)(rng)];
    // Within 0.1 mm of the jump, or (every other such state) within 0.6 mm, more than the y
    // step of 0.25-0.5 mm: every kind of piece of a cut cell (jump_piece.hpp), not only those
    // that reach the jump.
    const double reach = (k / 6) % 2 ? 6e-4 : 1e-4;
    s.y = y + (kind == 3 ? std::uniform_real_distribution<double>(-reach, reach)(rng) : 0.0);
  }
  if (kind == 5) {
    const double bad[3] = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                           -std::numeric_limits<double>::infinity()};
    const double v = bad[k % 3];
    switch ((k / 6) % 6) {
      case 0: s.y = v; break;
      case 1: s.load = v; break;
      case 2: s.xi = v; break;
      case 3: s.eta = v; break;
      case 4: s.phi = v; break;
      default: s.roll = v; break;
    }
  }
  return s;
}

void expect_same_bytes(const lk::Table& generic, const lk::Table& fast, const std::vector<double>& jump_y) {
  std::mt19937 rng(4);
  std::size_t compared = 0;
  for (int k = 0; k < 12000; ++k) {
    const lk::State s = state(fast, jump_y, k, rng);
    for (int w = 0; w < 2; ++w) {
      const lk::Wheel wheel = static_cast<lk::Wheel>(w);
      lk::Result a{}, b{};  // no padding: every byte is a field
      generic.query(wheel, s, a);
      fast.query(wheel, s, b);
      ASSERT_EQ(std::memcmp(&a, &b, sizeof a), 0) << "query, wheel " << w << " state " << k;
      for (int slot = 0; slot < fast.n_slots(); ++slot) {
        lk::Contact c{}, d{};
        generic.query_slot(wheel, s, slot, c);
        fast.query_slot(wheel, s, slot, d);
        ASSERT_EQ(std::memcmp(&c, &d, sizeof c), 0) << "query_slot " << slot << ", wheel " << w << " state " << k;
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 40000u);
}

TEST(FastPath, SameBytesAsTheGenericPath) {
  const Tables& t = tables();
  expect_same_bytes(*t.generic, *t.fast, t.jump_y);
}

TEST(FastPath, SameBytesAsTheGenericPathWithSse2Kernels) {
  const Tables& t = tables();
  expect_same_bytes(*t.generic_sse2, *t.fast_sse2, t.jump_y);
  expect_same_bytes(*t.generic, *t.fast_sse2, t.jump_y);
}

// Table::query_derivatives through the fused path (fast_derivatives in fast_path.cpp) against the
// generic one (derivatives.cpp) at the states above, both wheels: the same Result bytes, and
// derivatives that differ only by rounding (the two paths order a few sums differently: the
// bilinear cells' slopes). The bound: 1e-12 of the largest magnitude
// of that output's derivative with respect to that variable over all the states (a row's terms
// can cancel, so not of the value itself); measured 3.6e-15.
void expect_close_derivatives(const lk::Table& generic, const lk::Table& fast, const std::vector<double>& jump_y) {
  std::mt19937 rng(5);
  double scale[lk::kNumOutputs][lk::kNumVariables] = {}, diff[lk::kNumOutputs][lk::kNumVariables] = {};
  std::size_t nonzero = 0;
  for (int k = 0; k < 6000; ++k) {
    const lk::State s = state(fast, jump_y, k, rng);
    for (int w = 0; w < 2; ++w) {
      const lk::Wheel wheel = static_cast<lk::Wheel>(w);
      lk::Result ra{}, rb{};
      lk::Derivatives a, b;
      const bool oka = generic.query_derivatives(wheel, s, ra, a);
      const bool okb = fast.query_derivatives(wheel, s, rb, b);
      ASSERT_TRUE(oka && okb);
      ASSERT_EQ(std::memcmp(&ra, &rb, sizeof ra), 0) << "query_derivatives values, wheel " << w << " state " << k;
      for (int slot = 0; slot < fast.n_slots(); ++slot)
        for (int o = 0; o < lk::kNumOutputs; ++o)
          for (int v = 0; v < lk::kNumVariables; ++v) {
            const double x = a.d[slot][o][v], y = b.d[slot][o][v];
            nonzero += x != 0.0 || y != 0.0;
            scale[o][v] = std::max({scale[o][v], std::abs(x), std::abs(y)});
            diff[o][v] = std::max(diff[o][v], std::abs(x - y));
          }
    }
  }
  double worst = 0.0;
  for (int o = 0; o < lk::kNumOutputs; ++o)
    for (int v = 0; v < lk::kNumVariables; ++v)
      if (scale[o][v] > 0.0) worst = std::max(worst, diff[o][v] / scale[o][v]);
  std::printf("fast against generic derivatives: %zu nonzero compared, worst |fast - generic| = %.2g of the "
              "largest |derivative| of that output and variable\n",
              nonzero, worst);
  EXPECT_GT(nonzero, 300000u);
  EXPECT_LE(worst, 1e-12);
}

TEST(FastPath, DerivativesAgreeWithTheGenericPath) {
  const Tables& t = tables();
  expect_close_derivatives(*t.generic, *t.fast, t.jump_y);
  expect_close_derivatives(*t.generic_sse2, *t.fast_sse2, t.jump_y);
}

}  // namespace
}  // namespace railtab::accuracy
