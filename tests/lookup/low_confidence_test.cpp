// SPDX-License-Identifier: Apache-2.0
// The low_confidence bit (docs/lookup.md, "Low confidence"): set where the query's cell spans a
// contact appearing or vanishing between its nodes, where a slot's force has no rigid point of its
// own, or where a node's forces and angles miss the wheel load; nowhere else.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>

#include "lookup/lookup_test_util.hpp"
#include "lookup/table_fixture.hpp"
#include "railtab/lookup.hpp"

namespace railtab::lookup {
namespace {

using testing::FixtureSpec;
using testing::linspace;
using testing::TempFile;

constexpr int kGeometryPart = 0, kNormalPart = 1;
constexpr int kContactAngleOut = 0, kRollingRadiusOut = 1, kNormalForceOut = 0;
constexpr double kLoad = 78500.0;

// y nodes -10 .. 10 mm every 2.5 mm; xi 3 nodes. Slot 0 (tread): a contact everywhere. Slot 1
// (flange): a normal force from y = 2.5 mm on, a rigid point only from y = 7.5 mm on, so
//   (0, 2.5) mm: the force appears inside the cell (presence mixed in the normal block);
//   (2.5, 5) mm: force at both nodes, no rigid point at either (unpaired);
//   (5, 7.5) mm: the rigid point appears inside the cell (presence mixed in the geometry block);
//   (7.5, 10) mm and every y < 0: clean.
FixtureSpec onset_spec() {
  FixtureSpec spec;
  spec.axes = {{0, linspace(-0.01, 0.01, 9)}, {3, linspace(-0.002, 0.002, 3)}};
  spec.fixed = {{1, 0.0}, {2, kLoad}, {4, 0.0}, {5, 0.0}};
  // The slots' forces carry the load with the angles served (sum N cos(angle) = load) at every
  // node, so the load-balance rule stays silent here.
  spec.value = [](int, int part, int out, int slot, const double* x) {
    const double y = x[0];
    const bool flange_force = y > 0.0024, flange_point = y > 0.0074;
    const double flange_angle = flange_point ? 1.0 : 0.0;
    const double flange_n = flange_force ? 50000.0 : 0.0;
    if (part == kNormalPart && out == kNormalForceOut)
      return slot == 0 ? kLoad - flange_n * std::cos(flange_angle) : flange_n;
    if (part == kGeometryPart && out == kRollingRadiusOut) return slot == 0 ? 0.46 : (flange_point ? 0.45 : 0.0);
    if (part == kGeometryPart && out == kContactAngleOut) return slot == 0 ? 0.0 : flange_angle;
    return 1.0 + 0.1 * out + slot;
  };
  // Statuses as a table stores them: an empty slot has status 0 in that part.
  spec.status = [](int, int part, int slot, const double* x) -> std::uint32_t {
    if (slot == 0) return status::kConverged;
    if (part == kGeometryPart) return x[0] > 0.0074 ? status::kConverged | status::kFlangeContact : 0u;
    return x[0] > 0.0024 ? status::kConverged | status::kFlangeContact : 0u;
  };
  return spec;
}

bool low(const Contact& c) { return (c.status & status::kLowConfidence) != 0; }

TEST(LowConfidence, FlagsOnsetsAndUnpairedForcesOnly) {
  TempFile file("low_confidence");
  testing::write_fixture(file.path, onset_spec());
  for (Method method : {Method::kLinear, Method::kCubic}) {
    const Table t = Table::load(file.path, {method});
    State s = t.default_state();
    auto at = [&](double y, int slot) {
      s.y = y;
      s.xi = 0.0013;
      return t.query(Wheel::kLeft, s).contact[slot];
    };
    // (A cubic stencil at y = -1 mm reaches the flange force at 2.5 mm: a force without a rigid
    // point, flagged; linear interpolation keeps the slot empty there.)
    for (double y : {-0.009, -0.004, -0.001, 0.008, 0.0099}) {
      EXPECT_FALSE(low(at(y, 0))) << "y " << y;
      if (method == Method::kLinear || y != -0.001) {
        EXPECT_FALSE(low(at(y, 1))) << "y " << y;
      }
    }
    for (double y : {0.001, 0.006, 0.007}) {
      EXPECT_FALSE(low(at(y, 0))) << "tread, y " << y;
      EXPECT_TRUE(low(at(y, 1))) << "flange, y " << y;
    }
    // The onset cell: the normal part's cell status.
    EXPECT_TRUE(at(0.001, 1).part_status[kNormal] & status::kLowConfidence);
    // Unpaired: a contact at both nodes of the normal part's cell, none at the geometry's.
    EXPECT_TRUE(low(at(0.0045, 1)));
    if (method != Method::kLinear) continue;  // the values below: linear interpolation
    const Contact unpaired = at(0.003, 1);
    EXPECT_FALSE(unpaired.part_status[kNormal] & status::kLowConfidence);
    EXPECT_TRUE(unpaired.part_status[kGeometry] & status::kLowConfidence);
    EXPECT_EQ(unpaired.value[kRollingRadius], 0.0);
    EXPECT_EQ(unpaired.value[kNormalForce], 50000.0);
    // query_slot gives the same bits.
    s.y = 0.003;
    EXPECT_EQ(t.query_slot(Wheel::kLeft, s, 1).status, unpaired.status);
  }
}

// Load balance: at one node the force served with the angle carries 1.5 times the load (a patch
// that lags its rigid point): the two cells beside it are low confidence, the others not.
TEST(LowConfidence, FlagsCellsBesideANodeThatMissesTheLoadBalance) {
  TempFile file("low_confidence_balance");
  FixtureSpec spec;
  spec.format_version = "2.1";  // the rule trusts the balance of railtab generate's tables (2.1 on)
  spec.fixed_as_datasets = true;
  spec.axes = {{0, linspace(-0.01, 0.01, 9)}, {2, {60000.0, 100000.0}}, {3, linspace(-0.002, 0.002, 3)}};
  spec.fixed = {{1, 0.0}, {4, 0.0}, {5, 0.0}};
  spec.n_slots = 1;
  spec.value = [](int, int part, int out, int, const double* x) {
    const double angle = 0.3;
    if (part == kGeometryPart && out == kContactAngleOut) return angle;
    if (part == kGeometryPart && out == kRollingRadiusOut) return 0.46;
    if (part == kNormalPart && out == kNormalForceOut)
      return x[2] / std::cos(angle) * (std::abs(x[0] - 0.005) < 1e-9 ? 1.5 : 1.0);
    return 1.0 + 0.1 * out;
  };
  testing::write_fixture(file.path, spec);
  const Table t = Table::load(file.path);
  State s = t.default_state();
  s.load = kLoad;
  for (double y : {0.0026, 0.004, 0.006, 0.0074}) {
    s.y = y;
    const Contact c = t.query(Wheel::kRight, s).contact[0];
    EXPECT_TRUE(c.status & status::kLowConfidence) << "y " << y;
    EXPECT_TRUE(c.part_status[kNormal] & status::kLowConfidence) << "y " << y;
    EXPECT_TRUE(c.part_status[kCreep] & status::kLowConfidence) << "y " << y;
    EXPECT_FALSE(c.part_status[kGeometry] & status::kLowConfidence) << "y " << y;
  }
  for (double y : {-0.009, -0.001, 0.001, 0.0024, 0.0076, 0.0099}) {
    s.y = y;
    EXPECT_FALSE(t.query(Wheel::kRight, s).contact[0].status & status::kLowConfidence) << "y " << y;
  }
  // A table before 2.1 is not held to the balance.
  TempFile old_file("low_confidence_balance_20");
  spec.format_version = "2.0";
  testing::write_fixture(old_file.path, spec);
  s.y = 0.004;
  EXPECT_FALSE(Table::load(old_file.path).query(Wheel::kRight, s).contact[0].status & status::kLowConfidence);
}

}  // namespace
}  // namespace railtab::lookup
