// SPDX-License-Identifier: Apache-2.0
// Query semantics of Table: clamping and flags, NaN handling, fixed axes, status combination,
// batch = single, wheels, and 8 threads = 1 thread.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <thread>
#include <vector>

#include "lookup/lookup_test_util.hpp"
#include "lookup/table_fixture.hpp"
#include "railtab/lookup.hpp"

namespace railtab::lookup {
namespace {

using testing::FixtureSpec;
using testing::linspace;
using testing::TempFile;

// Affine in y and xi, different per wheel/part/output/slot, so a mix-up shows.
double value_fn(int wheel, int part, int out, int slot, const double* x) {
  return 1.0 + wheel * 10.0 + part * 100.0 + out * 1000.0 + slot * 1e4 + 50.0 * x[0] + 7.0 * x[3];
}

FixtureSpec small_spec() {
  FixtureSpec spec;
  spec.axes = {{0, linspace(-0.01, 0.01, 11)}, {3, linspace(-0.01, 0.01, 5)}};
  spec.fixed = {{1, 0.0}, {2, 78500.0}, {4, 0.0}, {5, 0.0}};
  spec.value = value_fn;
  return spec;
}

class TableTest : public ::testing::Test {
 protected:
  void SetUp() override {
    file_ = std::make_unique<TempFile>("table");
    spec_ = small_spec();
    testing::write_fixture(file_->path, spec_);
    table_ = std::make_unique<Table>(Table::load(file_->path));
  }
  std::unique_ptr<TempFile> file_;
  FixtureSpec spec_;
  std::unique_ptr<Table> table_;
};

TEST_F(TableTest, DescribesItself) {
  const Table& t = *table_;
  EXPECT_EQ(t.format_version(), "1.0");
  EXPECT_EQ(t.scene_name(), "fixture");
  EXPECT_EQ(t.n_slots(), 2);
  ASSERT_EQ(t.axes().size(), 2u);
  EXPECT_EQ(t.axes()[0].name, "y");
  EXPECT_EQ(t.axes()[1].name, "xi");
  EXPECT_EQ(t.axes()[1].nodes.size(), 5u);
  ASSERT_EQ(t.fixed_axes().size(), 4u);
  EXPECT_EQ(t.fixed_axes()[1].first, "load");
  const State d = t.default_state();
  EXPECT_EQ(d.load, 78500.0);
  EXPECT_EQ(d.y, 0.0);
  for (int p = 0; p < kNumParts; ++p) EXPECT_TRUE(t.has_part(static_cast<Part>(p)));
  EXPECT_GT(t.memory_bytes(), 0u);
  EXPECT_STREQ(output_name(kSemiAxisA), "a");
  EXPECT_EQ(output_part(kMz), kCreep);
  EXPECT_EQ(output_part(kWearRate), kWear);
  EXPECT_STREQ(part_name(kNormal), "normal");
}

TEST_F(TableTest, EveryOutputOfEverySlotAndWheel) {
  State s = table_->default_state();
  s.y = 0.0031;
  s.xi = -0.0042;
  for (int wheel = 0; wheel < 2; ++wheel) {
    const Result r = table_->query(static_cast<Wheel>(wheel), s);
    EXPECT_EQ(r.status, 0u);
    ASSERT_EQ(r.n_slots, 2);
    for (int part = 0; part < kNumParts; ++part)
      for (int o = 0; o < testing::part_outputs(part); ++o)
        for (int slot = 0; slot < 2; ++slot) {
          double x[6] = {s.y, 0, 0, part >= kCreep ? s.xi : 0.0, 0, 0};
          EXPECT_NEAR(r.contact[slot].value[testing::output_index(part, o)],
                      value_fn(wheel, part, o, slot, x), 1e-9)
              << "wheel " << wheel << " part " << part << " output " << o << " slot " << slot;
        }
    EXPECT_EQ(r.contact[0].status, status::kConverged);
  }
}

TEST_F(TableTest, OutOfRangeIsClampedAndFlagged) {
  State s = table_->default_state();
  s.y = 0.05;  // 5x beyond the last node
  s.xi = -1.0;
  const Result r = table_->query(Wheel::kLeft, s);
  EXPECT_EQ(r.status, status::kOutOfRange);
  double edge[6] = {0.01, 0, 0, -0.01, 0, 0};
  EXPECT_NEAR(r.contact[1].value[kFx], value_fn(0, kCreep, 0, 1, edge), 1e-9);  // clamped
  for (int slot = 0; slot < 2; ++slot) {
    EXPECT_TRUE(r.contact[slot].status & status::kOutOfRange);
    EXPECT_TRUE(r.contact[slot].status & status::kConverged);  // the edge values are good
  }
  // Exactly on the edge is inside.
  s.y = 0.01;
  s.xi = -0.01;
  EXPECT_EQ(table_->query(Wheel::kLeft, s).status, 0u);
}

TEST_F(TableTest, FixedAxisMustBeQueriedAtItsValue) {
  State s = table_->default_state();
  s.roll = 0.002;  // roll is fixed at 0 in this table
  EXPECT_EQ(table_->query(Wheel::kLeft, s).status, status::kOutOfRange);
  s.roll = 1e-14;  // round-off is not a mismatch
  EXPECT_EQ(table_->query(Wheel::kLeft, s).status, 0u);
  s = table_->default_state();
  s.load = 78500.0 * (1 + 1e-6);
  EXPECT_EQ(table_->query(Wheel::kLeft, s).status, status::kOutOfRange);
}

TEST_F(TableTest, NanAndInfAreFlaggedNotInterpolated) {
  const double bad[3] = {std::numeric_limits<double>::quiet_NaN(),
                         std::numeric_limits<double>::infinity(),
                         -std::numeric_limits<double>::infinity()};
  for (double b : bad) {
    for (int var = 0; var < 6; ++var) {
      State s = table_->default_state();
      double* fields[6] = {&s.y, &s.roll, &s.load, &s.xi, &s.eta, &s.phi};
      *fields[var] = b;
      const Result r = table_->query(Wheel::kRight, s);
      EXPECT_TRUE(r.status & status::kInvalidInput) << "variable " << var;
      for (int slot = 0; slot < 2; ++slot) {
        EXPECT_EQ(r.contact[slot].status, status::kInvalidInput);
        for (double v : r.contact[slot].value) EXPECT_EQ(v, 0.0);
      }
    }
  }
  // An invalid wheel value is invalid input too, not a crash.
  EXPECT_TRUE(table_->query(static_cast<Wheel>(7), table_->default_state()).status &
              status::kInvalidInput);
}

TEST(TableStatus, CornerStatusesCombineConservatively) {
  // Slot 1 (flange) converged at nodes y >= 0.004, lift-off (no converged bit) below; creep of
  // slot 0 saturates (full slip) at nodes xi >= 0.005.
  TempFile file("status");
  FixtureSpec spec = small_spec();
  spec.status = [](int, int part, int slot, const double* x) -> std::uint32_t {
    if (slot == 1) return x[0] > 0.003 ? status::kConverged | status::kFlangeContact : status::kLiftOff;
    if (part == kCreep && x[3] > 0.0025) return status::kConverged | status::kFullSlip;
    return status::kConverged;
  };
  testing::write_fixture(file.path, spec);
  const Table t = Table::load(file.path);
  State s = t.default_state();
  s.y = 0.003;  // cell [0.002, 0.004]: one corner in flange contact, one lifted off
  s.xi = 0.0;   // cell [0, 0.005]: creep corners at 0.005 in full slip, at 0 not
  const Result r = t.query(Wheel::kLeft, s);
  // no kConverged; low_confidence: the flange contact appears inside the cell
  EXPECT_EQ(r.contact[1].status, status::kFlangeContact | status::kLiftOff | status::kLowConfidence);
  EXPECT_EQ(r.contact[0].part_status[kGeometry], status::kConverged);
  // full_slip only where every corner saturates: not at zero creepage (docs/lookup.md)
  EXPECT_EQ(r.contact[0].part_status[kCreep], status::kConverged);
  EXPECT_EQ(r.contact[0].status, status::kConverged);
  s.xi = 0.0075;  // cell [0.005, 0.01]: every creep corner in full slip
  EXPECT_EQ(t.query(Wheel::kLeft, s).contact[0].part_status[kCreep], status::kConverged | status::kFullSlip);
  s.y = 0.005;  // all corners at y >= 0.004
  s.xi = -0.004;
  const Result r2 = t.query(Wheel::kLeft, s);
  EXPECT_EQ(r2.contact[1].status, status::kConverged | status::kFlangeContact);
  EXPECT_EQ(r2.contact[0].status, status::kConverged);
}

TEST(TablePartial, AbsentPartsGiveZerosAndNoStatus) {
  TempFile file("geometry_only");
  FixtureSpec spec;
  spec.axes = {{0, linspace(-0.01, 0.01, 5)}};
  spec.fixed = {{1, 0.0}};
  spec.parts = {0};
  spec.value = value_fn;
  testing::write_fixture(file.path, spec);
  const Table t = Table::load(file.path);
  EXPECT_TRUE(t.has_part(kGeometry));
  EXPECT_FALSE(t.has_part(kCreep));
  Result r;
  r.contact[0].value[kFx] = 123.0;  // must be overwritten
  State s = t.default_state();  // every untabulated variable is in fixed_axes (at 0 here)
  s.y = 0.001;
  t.query(Wheel::kLeft, s, r);
  EXPECT_EQ(r.status, 0u);
  EXPECT_EQ(r.contact[0].value[kFx], 0.0);
  EXPECT_EQ(r.contact[0].part_status[kCreep], 0u);
  EXPECT_EQ(r.contact[0].status, status::kConverged);
  double x[6] = {0.001, 0, 0, 0, 0, 0};
  EXPECT_NEAR(r.contact[0].value[kRollingRadius], value_fn(0, 0, 1, 0, x), 1e-12);
}

std::vector<Query> random_queries(const Table& t, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> y(-0.012, 0.012), xi(-0.012, 0.012);
  std::vector<Query> q(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    q[k].wheel = static_cast<Wheel>(k % 2);
    q[k].state = t.default_state();
    q[k].state.y = y(rng);
    q[k].state.xi = xi(rng);
  }
  return q;
}

TEST_F(TableTest, BatchEqualsSingleQueries) {
  const auto q = random_queries(*table_, 100, 1);
  std::vector<Result> batch(q.size());
  table_->query(q, batch);
  for (std::size_t k = 0; k < q.size(); ++k) {
    const Result single = table_->query(q[k].wheel, q[k].state);
    EXPECT_EQ(std::memcmp(&single.contact[0], &batch[k].contact[0], 2 * sizeof(Contact)), 0);
    EXPECT_EQ(single.status, batch[k].status);
  }
}

TEST(TableThreads, EightThreadsGiveTheSameAnswersAsOne) {
  for (Method method : {Method::kLinear, Method::kMonotoneCubic}) {
    TempFile file("threads");
    testing::FixtureSpec spec = testing::scene_sized_spec();
    testing::write_fixture(file.path, spec);
    const Table t = Table::load(file.path, {method});
    const auto q = random_queries(t, 4000, 7);
    std::vector<Result> reference(q.size());
    t.query(q, reference);
    std::vector<std::vector<Result>> got(8, std::vector<Result>(q.size()));
    std::vector<std::thread> threads;
    for (int th = 0; th < 8; ++th)
      threads.emplace_back([&, th] {
        // Each thread walks the queries in its own order, one at a time.
        for (std::size_t k = 0; k < q.size(); ++k) {
          const std::size_t i = (k * 7 + th * 997) % q.size();
          t.query(q[i].wheel, q[i].state, got[th][i]);
        }
      });
    for (auto& th : threads) th.join();
    for (int th = 0; th < 8; ++th)
      for (std::size_t k = 0; k < q.size(); ++k)
        ASSERT_EQ(std::memcmp(&reference[k].contact[0], &got[th][k].contact[0], 2 * sizeof(Contact)), 0)
            << "thread " << th << " query " << k;
  }
}

}  // namespace
}  // namespace railtab::lookup
