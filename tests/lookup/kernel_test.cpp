// SPDX-License-Identifier: Apache-2.0
// The query path's internals against brute force (docs/lookup-speed.md): the bucket search on
// non-uniform axes finds exactly the cells of the binary search, the per-cell statuses of the
// query layout equal the fold over the cell's corner nodes, and the AVX2 and SSE2 kernels give
// the same bytes, as do their float corner sums on records whose status lanes hold any bits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <random>
#include <vector>

#include "grid.hpp"
#include "lookup/lookup_test_util.hpp"
#include "lookup/table_fixture.hpp"
#include "railtab/lookup.hpp"
#include "weighted_sum.hpp"

namespace railtab::lookup {
namespace {

using testing::FixtureSpec;
using testing::linspace;
using testing::TempFile;

// Probes over and beyond an axis: random, every node, and a few ulps either side of each node.
std::vector<double> probes(const std::vector<double>& x, unsigned seed) {
  std::vector<double> p;
  const double w = x.back() - x.front();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(x.front() - 0.1 * w, x.back() + 0.1 * w);
  for (int k = 0; k < 5000; ++k) p.push_back(u(rng));
  for (double node : x) {
    double lo = node, hi = node;
    for (int k = 0; k < 4; ++k) {
      p.push_back(lo);
      p.push_back(hi);
      lo = std::nextafter(lo, -1e300);
      hi = std::nextafter(hi, 1e300);
    }
  }
  return p;
}

TEST(Kernel, BucketSearchFindsTheCellsOfTheBinarySearch) {
  // The STRIPES scene's y axis (0.25 mm steps at the ends, 0.5 mm between), a geometric axis
  // (spacings over a factor 30), three unequal nodes (that scene's load axis) and xi.
  std::vector<double> y;
  for (int i = 0; i <= 16; ++i) y.push_back(-0.010 + 0.00025 * i);
  for (int i = 0; i <= 22; ++i) y.push_back(-0.0055 + 0.0005 * i);
  for (int i = 0; i <= 16; ++i) y.push_back(0.006 + 0.00025 * i);
  std::vector<double> geometric = {0.0};
  for (int i = 0; i < 12; ++i) geometric.push_back(geometric.back() + 1e-3 * std::pow(1.35, i));
  const std::vector<std::vector<double>> axes = {
      y, geometric, {60e3, 78.5e3, 100e3}, {-0.004, -0.002, -0.001, 0.0, 0.001, 0.002, 0.004}};
  unsigned seed = 1;
  for (const auto& x : axes) {
    const detail::Axis a(x);
    for (double q : probes(x, seed++)) {
      detail::AxisLoc exact, fast;
      const bool clamped = a.locate(q, exact);
      ASSERT_EQ(a.locate_fast(q, fast), clamped) << q;
      ASSERT_EQ(fast.i, exact.i) << q;
      ASSERT_EQ(fast.t, exact.t) << q;
    }
  }
}

// Status bits that differ from node to node (a hash of the node's coordinates).
std::uint32_t node_status(int wheel, int part, int slot, const double* x) {
  std::uint64_t h = 1469598103934665603ull ^ static_cast<std::uint64_t>(wheel * 7 + part * 3 + slot);
  for (int v = 0; v < 6; ++v) {
    std::uint64_t bits;
    std::memcpy(&bits, &x[v], sizeof bits);
    h = (h ^ bits) * 1099511628211ull;
  }
  h ^= h >> 29;
  // Mostly converged (so the AND matters), sometimes a trouble bit or two.
  std::uint32_t s = (h & 7) ? status::kConverged : 0u;
  if ((h >> 3) % 5 == 0) s |= status::kFullSlip;
  if ((h >> 7) % 7 == 0) s |= status::kTwoPoint;
  if ((h >> 11) % 11 == 0) s |= status::kNotConverged;
  return s;
}

FixtureSpec status_spec() {
  FixtureSpec spec;
  spec.axes = {{0, {-0.01, -0.007, -0.002, 0.0, 0.0045, 0.01}},
               {2, {60e3, 78.5e3, 100e3}},
               {3, {-0.004, -0.001, 0.0, 0.002, 0.004}},
               {5, linspace(-0.3, 0.3, 3)}};
  spec.fixed = {{1, 0.0}, {4, 0.001}};
  spec.status = node_status;
  spec.value = [](int, int, int, int, const double*) { return 1.0; };
  return spec;
}

TEST(Kernel, CellStatusIsTheFoldOfItsCornerNodes) {
  TempFile file("cell_status");
  const FixtureSpec spec = status_spec();
  testing::write_fixture(file.path, spec);
  const Table t = Table::load(file.path);
  std::mt19937 rng(5);
  for (int k = 0; k < 3000; ++k) {
    double x[6] = {0, 0, 0, 0, 0, 0};
    for (const auto& [var, value] : spec.fixed) x[var] = value;
    for (const auto& [var, nodes] : spec.axes)
      x[var] = std::uniform_real_distribution<double>(nodes.front(), nodes.back())(rng);
    const State s{x[0], x[1], x[2], x[3], x[4], x[5]};
    const int wheel = k % 2;
    const Result r = t.query(static_cast<Wheel>(wheel), s);
    for (int part = 0; part < kNumParts; ++part) {
      const auto& pf = testing::part_formats()[part];
      // The part's cell: lower node index along each of its axes, then the 2^D corners.
      std::vector<std::pair<int, std::vector<double>>> cell;
      for (const auto& [var, nodes] : spec.axes) {
        if (!pf.uses[var]) continue;
        const int i = static_cast<int>(
            std::upper_bound(nodes.begin() + 1, nodes.end() - 1, x[var]) - nodes.begin() - 1);
        cell.push_back({var, {nodes[i], nodes[i + 1]}});
      }
      for (int slot = 0; slot < spec.n_slots; ++slot) {
        std::uint32_t any = 0, all = ~0u;
        for (int c = 0; c < (1 << cell.size()); ++c) {
          double corner[6] = {0, 0, 0, 0, 0, 0};  // the fixture evaluates unused axes at 0
          for (const auto& [var, value] : spec.fixed) corner[var] = value;
          for (const auto& [var, nodes] : spec.axes)
            if (!pf.uses[var]) corner[var] = 0.0;
          for (std::size_t d = 0; d < cell.size(); ++d)
            corner[cell[d].first] = cell[d].second[(c >> d) & 1];
          const std::uint32_t st = node_status(wheel, part, slot, corner);
          any |= st;
          all &= st;
        }
        constexpr std::uint32_t every = status::kConverged | status::kFullSlip;  // ANDed, the rest ORed
        const std::uint32_t expected = (any & ~every) | (all & every);
        // low_confidence is derived from the corners' presence across the block's parts and the
        // slot's other parts (low_confidence_test.cpp checks it): not part of this fold.
        ASSERT_EQ(r.contact[slot].part_status[part] & ~status::kLowConfidence, expected)
            << "part " << part << " slot " << slot << " query " << k;
      }
    }
  }
}

TEST(Kernel, Avx2AndSse2KernelsGiveTheSameBytes) {
  // The kernels are chosen at load; RAILTAB_LOOKUP_NO_AVX2 forces SSE2. On a CPU without AVX2
  // both loads run SSE2 and the test compares SSE2 with itself.
  TempFile file("simd");
  FixtureSpec spec = status_spec();
  spec.value = [](int wheel, int part, int out, int slot, const double* x) {
    return std::sin(1.0 + wheel + 0.3 * part + 0.7 * out + slot + 50.0 * x[0] + 1e-5 * x[2] +
                    300.0 * x[3]) * std::exp(2.0 * x[5]);
  };
  testing::write_fixture(file.path, spec);
  for (Method method : {Method::kLinear, Method::kCubic, Method::kMonotoneCubic}) {
    ::setenv("RAILTAB_LOOKUP_NO_AVX2", "1", 1);
    const Table sse2 = Table::load(file.path, {method});
    ::unsetenv("RAILTAB_LOOKUP_NO_AVX2");
    const Table best = Table::load(file.path, {method});
    std::mt19937 rng(9);
    for (int k = 0; k < 500; ++k) {
      State s = best.default_state();
      s.y = std::uniform_real_distribution<double>(-0.011, 0.011)(rng);
      s.load = std::uniform_real_distribution<double>(55e3, 105e3)(rng);
      s.xi = std::uniform_real_distribution<double>(-0.005, 0.005)(rng);
      s.phi = std::uniform_real_distribution<double>(-0.35, 0.35)(rng);
      const Result a = sse2.query(static_cast<Wheel>(k % 2), s);
      const Result b = best.query(static_cast<Wheel>(k % 2), s);
      ASSERT_EQ(std::memcmp(&a, &b, sizeof a), 0) << "method " << static_cast<int>(method);
    }
  }
}

// The float corner sum of a D-dimensional cell of records of NV floats and two statuses (query
// layout), SSE2 against AVX2 where the CPU has it: the same bytes, and within float roundings of
// the multilinear interpolant summed in double (a bound of 10 D 2^-24 of the largest |value|:
// a + t (b - a) rounds t and three results per level, |b - a| up to twice the largest; a status
// lane or a corner out of place moves the sum by far more). The statuses are random
// bits (denormals and NaNs as floats: they must not enter the sums), the records scattered with
// every stride of the cell different. The table-level tests sum float records of 6 values over 5
// or 6 dimensions only (FastPath.*, YawTable.*); this covers the other shapes of the kernel tables.
template <int D, int NV>
void expect_same_float_corner_sums(std::mt19937& rng) {
  constexpr int kRecord = detail::record_bytes(NV, sizeof(float), 2);
  std::size_t stride[D > 0 ? D : 1];
  std::size_t bytes = kRecord;
  for (int d = D - 1; d >= 0; --d) {
    stride[d] = bytes + static_cast<std::size_t>(kRecord) * static_cast<std::size_t>(d);  // gaps between the nodes
    bytes = 2 * stride[d];
  }
  detail::RecordBytes data(bytes + 64);
  std::uniform_real_distribution<float> value(-3.0f, 3.0f);
  for (std::size_t at = 0; at + kRecord <= data.size(); at += kRecord) {
    for (int k = 0; k < NV; ++k) {
      const float v = value(rng);
      std::memcpy(&data[at + k * sizeof v], &v, sizeof v);
    }
    for (int k = NV; k < kRecord / 4; ++k) {
      const std::uint32_t bits = static_cast<std::uint32_t>(rng());
      std::memcpy(&data[at + k * sizeof bits], &bits, sizeof bits);
    }
  }
  const bool avx2 = __builtin_cpu_supports("avx2");
  std::uniform_real_distribution<double> fraction(0.0, 1.0);
  for (int k = 0; k < 200; ++k) {
    double t[D > 0 ? D : 1], u[D > 0 ? D : 1];
    for (int d = 0; d < D; ++d) t[d] = k == 0 ? 0.0 : k == 1 ? 1.0 : fraction(rng), u[d] = 1.0 - t[d];
    double sse2[NV], other[NV], exact[NV] = {};
    detail::corner_sum_sse2<D, NV, float>(data.data(), t, u, stride, sse2);
    for (int c = 0; c < (1 << D); ++c) {
      double w = 1.0;
      std::size_t at = 0;
      for (int d = 0; d < D; ++d) {
        const bool upper = (c >> d) & 1;
        w *= upper ? t[d] : u[d];
        at += upper ? stride[d] : 0;
      }
      for (int v = 0; v < NV; ++v) exact[v] += w * detail::record_value<float>(data.data() + at, v);
    }
    for (int v = 0; v < NV; ++v)
      ASSERT_NEAR(sse2[v], exact[v], 10.0 * D * 3.0 * 0x1p-24) << "D " << D << " NV " << NV << " value " << v;
    if (avx2) {
      detail::corner_sum_avx2<D, NV, float>(data.data(), t, u, stride, other);
      ASSERT_EQ(std::memcmp(sse2, other, sizeof other), 0) << "AVX2, D " << D << " NV " << NV << " state " << k;
    }
  }
}

TEST(Kernel, FloatCornerSumsGiveTheSameBytesInAvx2AndSse2) {
  std::mt19937 rng(12);
  expect_same_float_corner_sums<1, 6>(rng);
  expect_same_float_corner_sums<2, 5>(rng);
  expect_same_float_corner_sums<3, 8>(rng);
  expect_same_float_corner_sums<4, 7>(rng);
  expect_same_float_corner_sums<5, 6>(rng);  // the creep and wear block of a yaw-free table
  expect_same_float_corner_sums<6, 6>(rng);  // of a yaw table
  expect_same_float_corner_sums<6, 4>(rng);  // 4 values: vectors of 4 in every instruction set
  expect_same_float_corner_sums<7, 5>(rng);
}

}  // namespace
}  // namespace railtab::lookup
