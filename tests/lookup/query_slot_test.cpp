// SPDX-License-Identifier: Apache-2.0
// Table::query_slot and railtab_lookup_query_slot: one contact slot gives exactly what the
// all-slots query puts in that slot (values, part statuses, status with the query bits), for
// every method, both wheels, in and out of range, NaN, absent parts, odd slot counts; bad slots
// and wheels give zeros + kInvalidInput (C: an argument error). Also the query path's axis search
// (Axis::locate_fast) against the exact one.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <thread>
#include <vector>

#include "grid.hpp"
#include "lookup/lookup_test_util.hpp"
#include "lookup/table_fixture.hpp"
#include "railtab/lookup.hpp"
#include "railtab_lookup.h"

namespace railtab::lookup {
namespace {

using testing::TempFile;

// Random states over and beyond the table (about 1 in 4 clamped on some axis).
std::vector<Query> wide_queries(const Table& t, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> y(-0.012, 0.012), c(-0.012, 0.012), phi(-1.1, 1.1);
  std::vector<Query> q(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    q[k].wheel = static_cast<Wheel>(k % 2);
    q[k].state = t.default_state();
    q[k].state.y = y(rng);
    q[k].state.xi = c(rng);
    q[k].state.eta = c(rng);
    q[k].state.phi = phi(rng);
  }
  return q;
}

void expect_slots_match(const Table& t, const Query& q, const char* what) {
  const Result all = t.query(q.wheel, q.state);
  for (int slot = 0; slot < t.n_slots(); ++slot) {
    Contact one;
    std::memset(static_cast<void*>(&one), 0xab, sizeof one);  // every field must be written
    t.query_slot(q.wheel, q.state, slot, one);
    ASSERT_EQ(std::memcmp(&one, &all.contact[slot], sizeof(Contact)), 0)
        << what << ": slot " << slot << ", y " << q.state.y << ", xi " << q.state.xi;
    const Contact by_value = t.query_slot(q.wheel, q.state, slot);
    ASSERT_EQ(std::memcmp(&by_value, &all.contact[slot], sizeof(Contact)), 0) << what;
  }
}

TEST(QuerySlot, EqualsTheAllSlotsQueryForEveryMethod) {
  TempFile file("slot");
  testing::write_fixture(file.path, testing::scene_sized_spec());
  for (Method method : {Method::kLinear, Method::kCubic, Method::kMonotoneCubic}) {
    const Table t = Table::load(file.path, {method});
    int clamped = 0;
    for (const Query& q : wide_queries(t, method == Method::kLinear ? 2000 : 200, 3)) {
      expect_slots_match(t, q, "scene-sized fixture");
      clamped += (t.query(q.wheel, q.state).status & status::kOutOfRange) != 0;
    }
    EXPECT_GT(clamped, 0);  // the out-of-range path was exercised
  }
}

TEST(QuerySlot, AbsentPartsOddSlotCountAndNonUniformAxes) {
  testing::FixtureSpec spec = testing::scene_sized_spec();
  spec.parts = {0, 2};  // geometry and creep: normal and wear outputs are 0
  spec.n_slots = 3;
  spec.axes[0].second = {-0.01, -0.006, -0.001, 0.0, 0.002, 0.01};  // non-uniform y
  TempFile file("slot_parts");
  testing::write_fixture(file.path, spec);
  const Table t = Table::load(file.path);
  ASSERT_EQ(t.n_slots(), 3);
  ASSERT_FALSE(t.has_part(kNormal));
  for (const Query& q : wide_queries(t, 500, 5)) expect_slots_match(t, q, "parts 0, 2");
}

TEST(QuerySlot, MonotoneCubicVectorLanesEqualTheScalarOnes) {
  // Seven values per slot: alone, a slot's last value goes through the scalar limiter; with
  // three slots, it shares a vector pair with the next slot's first value. Equal bytes say the
  // vector limiter computes exactly what the scalar one does.
  testing::FixtureSpec spec = testing::scene_sized_spec();
  spec.parts = {0, 2, 3};  // 2 geometry + 4 creep + 1 wear values
  spec.n_slots = 3;
  TempFile file("slot_monotone");
  testing::write_fixture(file.path, spec);
  const Table t = Table::load(file.path, {Method::kMonotoneCubic});
  ASSERT_EQ(t.n_slots(), 3);
  for (const Query& q : wide_queries(t, 300, 9)) expect_slots_match(t, q, "parts 0, 2, 3");
}

TEST(QuerySlot, InvalidInputBadSlotAndBadWheel) {
  TempFile file("slot_bad");
  testing::write_fixture(file.path, testing::scene_sized_spec());
  const Table t = Table::load(file.path);
  State s = t.default_state();
  s.y = 0.003;
  // NaN and inf: as the all-slots query (zeros, kInvalidInput).
  for (double bad : {std::numeric_limits<double>::quiet_NaN(),
                     std::numeric_limits<double>::infinity()}) {
    for (int var = 0; var < 6; ++var) {
      Query q{Wheel::kRight, s};
      double* fields[6] = {&q.state.y, &q.state.roll, &q.state.load,
                           &q.state.xi, &q.state.eta, &q.state.phi};
      *fields[var] = bad;
      expect_slots_match(t, q, "non-finite");
      EXPECT_EQ(t.query_slot(q.wheel, q.state, 1).status, status::kInvalidInput);
    }
  }
  // Fixed axis off its value: kOutOfRange, values still interpolated.
  Query off{Wheel::kLeft, s};
  off.state.load = 80000.0;
  expect_slots_match(t, off, "fixed axis off");
  EXPECT_TRUE(t.query_slot(off.wheel, off.state, 0).status & status::kOutOfRange);
  // Slot or wheel out of range: zeros and kInvalidInput, never a read outside the table.
  for (int slot : {-1, 2, kMaxSlots, 1000}) {
    const Contact c = t.query_slot(Wheel::kLeft, s, slot);
    EXPECT_EQ(c.status, status::kInvalidInput) << "slot " << slot;
    for (double v : c.value) EXPECT_EQ(v, 0.0);
    for (StatusBits p : c.part_status) EXPECT_EQ(p, 0u);
  }
  const Contact c = t.query_slot(static_cast<Wheel>(2), s, 0);
  EXPECT_EQ(c.status, status::kInvalidInput);
  EXPECT_EQ(c.value[kFx], 0.0);
}

TEST(QuerySlot, ThreadsGiveTheSameAnswers) {
  TempFile file("slot_threads");
  testing::write_fixture(file.path, testing::scene_sized_spec());
  const Table t = Table::load(file.path);
  const auto q = wide_queries(t, 3000, 9);
  std::vector<Contact> reference(q.size());
  for (std::size_t k = 0; k < q.size(); ++k)
    t.query_slot(q[k].wheel, q[k].state, static_cast<int>(k % 2), reference[k]);
  std::vector<std::vector<Contact>> got(4, std::vector<Contact>(q.size()));
  std::vector<std::thread> threads;
  for (int th = 0; th < 4; ++th)
    threads.emplace_back([&, th] {
      for (std::size_t k = 0; k < q.size(); ++k) {
        const std::size_t i = (k * 7 + th * 997) % q.size();
        t.query_slot(q[i].wheel, q[i].state, static_cast<int>(i % 2), got[th][i]);
      }
    });
  for (auto& th : threads) th.join();
  for (int th = 0; th < 4; ++th)
    for (std::size_t k = 0; k < q.size(); ++k)
      ASSERT_EQ(std::memcmp(&reference[k], &got[th][k], sizeof(Contact)), 0) << th << " " << k;
}

TEST(QuerySlot, CApiMatchesTheCppApi) {
  TempFile file("slot_capi");
  testing::write_fixture(file.path, testing::scene_sized_spec());
  railtab_lookup_table* t = nullptr;
  ASSERT_EQ(railtab_lookup_open(file.path.c_str(), RAILTAB_LOOKUP_LINEAR, &t), RAILTAB_LOOKUP_OK);
  const Table cpp = Table::load(file.path);
  railtab_lookup_state s;
  ASSERT_EQ(railtab_lookup_default_state(t, &s), RAILTAB_LOOKUP_OK);
  s.y = -0.0047, s.xi = 0.0021, s.eta = 0.003, s.phi = -0.4;
  railtab_lookup_result all;
  ASSERT_EQ(railtab_lookup_query(t, RAILTAB_LOOKUP_LEFT, &s, &all), RAILTAB_LOOKUP_OK);
  for (int slot = 0; slot < 2; ++slot) {
    railtab_lookup_contact c;
    ASSERT_EQ(railtab_lookup_query_slot(t, RAILTAB_LOOKUP_LEFT, &s, slot, &c), RAILTAB_LOOKUP_OK);
    EXPECT_EQ(std::memcmp(&c, &all.contact[slot], sizeof c), 0) << "slot " << slot;
  }
  railtab_lookup_contact c;
  EXPECT_EQ(railtab_lookup_query_slot(t, RAILTAB_LOOKUP_LEFT, &s, 2, &c),
            RAILTAB_LOOKUP_ERROR_ARGUMENT);
  EXPECT_NE(std::string(railtab_lookup_last_error()).find("slot"), std::string::npos);
  EXPECT_EQ(railtab_lookup_query_slot(t, 5, &s, 0, &c), RAILTAB_LOOKUP_ERROR_ARGUMENT);
  EXPECT_EQ(railtab_lookup_query_slot(nullptr, 0, &s, 0, &c), RAILTAB_LOOKUP_ERROR_ARGUMENT);
  EXPECT_EQ(railtab_lookup_query_slot(t, 0, &s, 0, nullptr), RAILTAB_LOOKUP_ERROR_ARGUMENT);
  railtab_lookup_close(t);
}

// The query path's search: t in [0, 1], and the point it describes is the query to rounding
// (a query within rounding of a node may land in the neighbouring cell at t = 0 or 1).
TEST(QuerySlot, FastAxisSearchDescribesTheSamePoint) {
  std::vector<double> x(41);
  for (int i = 0; i < 41; ++i) x[i] = -0.01 + 0.02 * i / 40;
  const detail::Axis a(x);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.0125, 0.0125);
  std::vector<double> probes;
  for (int i = 0; i < 41; ++i)
    for (double t : {0.0, 1e-15, 0.5, 1.0 - 1e-15}) probes.push_back(x[i] + t * (x[1] - x[0]));
  for (int k = 0; k < 2000; ++k) probes.push_back(u(rng));
  for (double q : probes) {
    detail::AxisLoc exact, fast;
    const bool clamped = a.locate(q, exact);
    EXPECT_EQ(a.locate_fast(q, fast), clamped) << q;
    ASSERT_GE(fast.i, 0);
    ASSERT_LE(fast.i, 39);
    EXPECT_GE(fast.t, 0.0);
    EXPECT_LE(fast.t, 1.0);
    EXPECT_LE(std::abs(fast.i - exact.i), 1) << q;
    const double p_exact = x[exact.i] + exact.t * (x[exact.i + 1] - x[exact.i]);
    const double p_fast = x[fast.i] + fast.t * (x[fast.i + 1] - x[fast.i]);
    EXPECT_NEAR(p_fast, p_exact, 1e-15) << q;
  }
  // Non-uniform axes: locate_fast is locate.
  const detail::Axis b({0.0, 1.0, 1.5, 4.0});
  for (double q : {-1.0, 0.5, 1.0, 1.25, 3.0, 4.0, 5.0}) {
    detail::AxisLoc l1, l2;
    EXPECT_EQ(b.locate(q, l1), b.locate_fast(q, l2));
    EXPECT_EQ(l1.i, l2.i);
    EXPECT_EQ(l1.t, l2.t);
  }
}

}  // namespace
}  // namespace railtab::lookup
