// SPDX-License-Identifier: Apache-2.0
// Table::query_derivatives on the STRIPES scene's table (normalised creep coordinates, located
// contact jumps, two slots: tread and flange), linear and cubic: the derivatives agree with
// central differences of query() itself inside cells, in every tabulated variable (y, load, and
// the physical creepages xi, eta, phi through the normalised coordinates), for both slots; beside
// a located jump the y derivative is the one-sided one of the query's side (central differences
// on that side), not the secant across the jump. A kink of the interpolant (a cell face) between
// the difference points shows as different forward and backward differences: the derivative
// then matches one of them (the cell the query is in) and the state is counted as a kink.
//
// The linear lookup sums the table's float records in float (lookup/src/weighted_sum.hpp): its
// values move in steps of a float rounding (~1e-7 of a value), far above what the differences
// below resolve, so the linear derivatives are differenced on the same table loaded with double
// records (RAILTAB_LOOKUP_NO_FLOAT_RECORDS=1: the same interpolant in double), and they must be
// that table's derivatives to the byte (the chain reads the block's double sums). The float sums
// themselves stay within a millionth of mu N of the double ones (test StoragePrecision.*).
//
// Run: build/<dir>/tests/test_table_accuracy --gtest_filter='Derivatives*' (prints the numbers).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>

#include "accuracy_util.hpp"
#include "adaptive/jump_locator.hpp"

namespace railtab::accuracy::derivatives_test {  // own namespace: unity builds compile several test files as one
namespace {

struct Tables {
  Scene scene;
  ContactJumps jumps;
  std::optional<lk::Table> linear, cubic;
  std::optional<lk::Table> linear_doubles;  // the linear table with double records (differenced)
};

const Tables& tables() {
  static const Tables t = [] {
    Tables x;
    const StripesSweep& d = stripes_sweep();
    x.scene = d.scene;
    x.jumps = d.jumps;
    Table table = d.table;
    add_jumps(table, x.scene, x.jumps);  // as railtab generate (format 2.1)
    const std::filesystem::path path = temp_table_path("derivatives");
    write_for_lookup(table, path);
    x.linear.emplace(lk::Table::load(path.string()));
    x.cubic.emplace(lk::Table::load(path.string(), {lk::Method::kCubic}));
    ::setenv("RAILTAB_LOOKUP_NO_FLOAT_RECORDS", "1", 1);
    x.linear_doubles.emplace(lk::Table::load(path.string()));
    ::unsetenv("RAILTAB_LOOKUP_NO_FLOAT_RECORDS");
    std::filesystem::remove(path);
    return x;
  }();
  return t;
}

// The lookup variable of each of this file's variables, and the difference step: far below every
// cell (y cells >= 0.1 mm, load cells 10s of kN, creepage cells >= 1e-5 in physical units), far
// above rounding (values up to 1e5 in double).
constexpr int kLookupVar[kNumVars] = {lk::kY, lk::kLoad, lk::kXi, lk::kEta, lk::kPhi};
constexpr double kStep[kNumVars] = {2e-9, 1e-3, 2e-10, 2e-10, 2e-8};

struct Tally {
  int checked = 0;        // (state, wheel, slot, output, variable) compared
  int kinks = 0;          // of them with a kink between the difference points
  int flange = 0;         // of them on the flange slot with a loaded flange contact
  int nonzero = 0;        // of them with a derivative above the tolerance
  double worst = 0.0;     // largest |derivative - central difference| / tolerance scale
};

double value(const lk::Table& t, lk::Wheel w, const lk::State& s, int slot, int o) {
  return t.query(w, s).contact[slot].value[o];
}

// Compares d output / d variable at s with differences of t.query() around s; true when it agrees.
bool agrees(const lk::Table& t, lk::Wheel w, const lk::State& s, int slot, int o, int var, double derivative,
            Tally& tally, std::string& why) {
  const double h = kStep[var];
  lk::State plus = s, minus = s;
  double* xp[kNumVars] = {&plus.y, &plus.load, &plus.xi, &plus.eta, &plus.phi};
  double* xm[kNumVars] = {&minus.y, &minus.load, &minus.xi, &minus.eta, &minus.phi};
  *xp[var] += h;
  *xm[var] -= h;
  const double f0 = value(t, w, s, slot, o), fp = value(t, w, plus, slot, o), fm = value(t, w, minus, slot, o);
  const double forward = (fp - f0) / h, backward = (f0 - fm) / h, central = (fp - fm) / (2.0 * h);
  // Rounding of the three values (double sums of values up to 1e5) plus 1e-5 of the derivative.
  const double tol = 1e-5 * std::abs(central) + 1e3 * 2.2e-16 * (std::abs(f0) + 1.0) / h;
  ++tally.checked;
  tally.nonzero += std::abs(derivative) > tol;
  const double err = std::abs(derivative - central);
  tally.worst = std::max(tally.worst, err / tol);
  if (err <= tol) return true;
  // A kink between the points: one-sided differences differ; the derivative is one of them
  // (their own error is first order: 1e-4 of the derivative).
  const double one_sided_tol = 1e-4 * std::max(std::abs(forward), std::abs(backward)) + tol;
  if (std::abs(forward - backward) > one_sided_tol &&
      (std::abs(derivative - forward) <= one_sided_tol || std::abs(derivative - backward) <= one_sided_tol)) {
    ++tally.kinks;
    return true;
  }
  why = "derivative " + std::to_string(derivative) + ", central " + std::to_string(central) + ", forward " +
        std::to_string(forward) + ", backward " + std::to_string(backward);
  return false;
}

// t's derivatives against differences of `differenced` (t itself, or t with double records: then
// the two tables' derivatives must be the same bytes).
void check_random_states(const lk::Table& t, const char* name, const lk::Table& differenced) {
  const Tables& x = tables();
  const std::vector<Point> points = random_states(x.scene, 300, 20240611);
  Tally tally;
  lk::Result r, r_differenced;
  lk::Derivatives d, d_differenced;
  for (const Point& p : points)
    for (int w = 0; w < 2; ++w) {
      const lk::Wheel wheel = static_cast<lk::Wheel>(w);
      const lk::State s = to_state(t, p);
      ASSERT_TRUE(t.query_derivatives(wheel, s, r, d));
      ASSERT_TRUE(differenced.query_derivatives(wheel, s, r_differenced, d_differenced));
      ASSERT_EQ(std::memcmp(&d, &d_differenced, sizeof d), 0) << name << ": float and double records' derivatives";
      for (int slot = 0; slot < r.n_slots; ++slot) {
        const bool flange = slot == 1 && r.contact[1].value[lk::kNormalForce] > 0.0;
        for (int o = 0; o < lk::kNumOutputs; ++o)
          for (int var = 0; var < kNumVars; ++var) {
            std::string why;
            const double derivative = d.d[slot][o][kLookupVar[var]];
            ASSERT_TRUE(agrees(differenced, wheel, s, slot, o, var, derivative, tally, why))
                << name << " wheel " << w << " slot " << slot << " y " << s.y << " load " << s.load << " xi " << s.xi
                << " eta " << s.eta << " phi " << s.phi << ": d " << lk::output_name(static_cast<lk::Output>(o)) << " / d "
                << kVarNames[var] << ": " << why;
            tally.flange += flange;
          }
      }
    }
  std::printf("%s: %d derivatives compared (%d nonzero, %d on loaded flange contacts), %d across a kink; "
              "worst |derivative - central difference| = %.3f of the tolerance\n",
              name, tally.checked, tally.nonzero, tally.flange, tally.kinks, tally.worst);
  // Not vacuous: geometry outputs depend on y alone and the normal part on y and load, so about
  // a fifth of the (output, variable) pairs have a derivative at all.
  EXPECT_GT(tally.nonzero, tally.checked / 8);
  EXPECT_GT(tally.flange, 1000);                 // flange contacts are among them
  EXPECT_LT(tally.kinks, tally.checked / 50);    // most comparisons inside one cell
}

TEST(Derivatives, LinearAgreesWithCentralDifferencesOnTheStripesTable) {
  check_random_states(*tables().linear, "linear", *tables().linear_doubles);
}

TEST(Derivatives, CubicAgreesWithCentralDifferencesOnTheStripesTable) {
  check_random_states(*tables().cubic, "cubic", *tables().cubic);
}

// Beside every located jump (30 um either side, at each load node): the y derivative of every
// output is the central difference on the query's side, and where the value steps across the jump
// by more than the derivative could carry over 60 um, it differs from the secant across it.
void check_jumps(const lk::Table& t, const char* name, const lk::Table& differenced) {
  const Tables& x = tables();
  const std::vector<double>& loads = x.scene.grids.load;
  Tally tally;
  int distinct = 0;
  lk::Result r;
  lk::Derivatives d;
  for (int w = 0; w < 2; ++w)
    for (std::size_t l = 0; l < loads.size(); ++l)
      for (const ContactJump& jump : x.jumps.wheel[w][l])
        for (double side : {-1.0, 1.0}) {
          const lk::Wheel wheel = static_cast<lk::Wheel>(w);
          lk::State s = t.default_state();
          s.load = loads[l];
          s.xi = 4e-4, s.eta = -3e-4, s.phi = 0.02;
          s.y = jump.y + side * 3e-5;
          lk::State across = s;
          across.y = jump.y - side * 3e-5;
          ASSERT_TRUE(t.query_derivatives(wheel, s, r, d));
          const lk::Result other = t.query(wheel, across);
          for (int slot = 0; slot < r.n_slots; ++slot)
            for (int o = 0; o < lk::kNumOutputs; ++o) {
              std::string why;
              const double derivative = d.d[slot][o][lk::kY];
              ASSERT_TRUE(agrees(differenced, wheel, s, slot, o, kY, derivative, tally, why))
                  << name << " wheel " << w << " load " << s.load << " jump at y " << jump.y << " side " << side << ": "
                  << lk::output_name(static_cast<lk::Output>(o)) << " slot " << slot << ": " << why;
              const double step = r.contact[slot].value[o] - other.contact[slot].value[o];
              const double secant = step / (s.y - across.y);
              if (std::abs(step) > 10.0 * std::abs(derivative) * 6e-5 + 1e-9) {
                EXPECT_GT(std::abs(secant - derivative), 0.5 * std::abs(secant));
                ++distinct;
              }
            }
        }
  std::printf("%s: %d y derivatives beside located jumps compared (%d across a kink), %d beside a value step "
              "differ from the secant across the jump; worst %.3f of the tolerance\n",
              name, tally.checked, tally.kinks, distinct, tally.worst);
  EXPECT_GT(distinct, 100);
}

TEST(Derivatives, LinearBesideAJumpIsOneSided) { check_jumps(*tables().linear, "linear", *tables().linear_doubles); }
TEST(Derivatives, CubicBesideAJumpIsOneSided) { check_jumps(*tables().cubic, "cubic", *tables().cubic); }

// Random states and states beside every located jump (cut cells).
std::vector<lk::State> byte_check_states(const lk::Table& t) {
  const Tables& x = tables();
  std::vector<lk::State> states;
  for (const Point& p : random_states(x.scene, 2000, 7)) states.push_back(to_state(t, p));
  for (int w = 0; w < 2; ++w)
    for (std::size_t l = 0; l < x.scene.grids.load.size(); ++l)
      for (const ContactJump& jump : x.jumps.wheel[w][l])
        for (double side : {-1.0, 1.0}) {
          lk::State s = t.default_state();
          s.load = x.scene.grids.load[l];
          s.xi = 4e-4, s.eta = -3e-4, s.phi = 0.02;
          s.y = jump.y + side * 3e-5;
          states.push_back(s);
        }
  return states;
}

// The values query_derivatives returns are query()'s, to the byte: at random states and beside
// every located jump (cut cells), both wheels, linear and cubic.
void check_same_bytes(const lk::Table& t) {
  const std::vector<lk::State> states = byte_check_states(t);
  lk::Result r, plain;
  lk::Derivatives d;
  int nonzero = 0;
  for (const lk::State& s : states)
    for (int w = 0; w < 2; ++w) {
      const lk::Wheel wheel = static_cast<lk::Wheel>(w);
      std::memset(static_cast<void*>(&r), 0xA5, sizeof r);  // the same bytes where neither call writes
      std::memset(static_cast<void*>(&plain), 0xA5, sizeof plain);
      ASSERT_TRUE(t.query_derivatives(wheel, s, r, d));
      t.query(wheel, s, plain);
      ASSERT_EQ(std::memcmp(&r, &plain, sizeof r), 0) << "wheel " << w << " y " << s.y << " load " << s.load;
      nonzero += plain.contact[0].value[lk::kFy] != 0.0;
    }
  EXPECT_GT(nonzero, static_cast<int>(states.size()));  // real states, forces on most
}

TEST(Derivatives, LinearValuesAreTheQuerysBytesOnTheStripesTable) { check_same_bytes(*tables().linear); }
TEST(Derivatives, CubicValuesAreTheQuerysBytesOnTheStripesTable) { check_same_bytes(*tables().cubic); }

// The one-slot derivative query gives query_derivatives' contact[slot] and d[slot] to the byte
// (the fast path's tables too: the linear STRIPES table takes it), at the same states; a slot
// outside the table gives zeros and kInvalidInput.
void check_one_slot(const lk::Table& t) {
  lk::Result r;
  lk::Derivatives d;
  lk::Contact c;
  lk::SlotDerivatives sd;
  int loaded_flange = 0;
  for (const lk::State& s : byte_check_states(t))
    for (int w = 0; w < 2; ++w) {
      const lk::Wheel wheel = static_cast<lk::Wheel>(w);
      ASSERT_TRUE(t.query_derivatives(wheel, s, r, d));
      for (int slot = 0; slot < t.n_slots(); ++slot) {
        std::memset(static_cast<void*>(&c), 0xA5, sizeof c);
        std::memset(static_cast<void*>(&sd), 0xA5, sizeof sd);
        ASSERT_TRUE(t.query_slot_derivatives(wheel, s, slot, c, sd));
        ASSERT_EQ(std::memcmp(&c, &r.contact[slot], sizeof c), 0) << "slot " << slot << " wheel " << w << " y " << s.y;
        ASSERT_EQ(std::memcmp(sd.d, d.d[slot], sizeof sd.d), 0) << "slot " << slot << " wheel " << w << " y " << s.y;
        loaded_flange += slot == 1 && c.value[lk::kNormalForce] > 0.0;
      }
    }
  EXPECT_GT(loaded_flange, 100);  // the flange slot's derivatives compared where it carries load
  ASSERT_TRUE(t.query_slot_derivatives(lk::Wheel::kLeft, t.default_state(), t.n_slots(), c, sd));
  EXPECT_EQ(c.status, lk::status::kInvalidInput);
  for (const auto& row : sd.d)
    for (double x : row) EXPECT_EQ(x, 0.0);
}

TEST(Derivatives, LinearOneSlotIsTheWholeQuerysSlotOnTheStripesTable) { check_one_slot(*tables().linear); }
TEST(Derivatives, CubicOneSlotIsTheWholeQuerysSlotOnTheStripesTable) { check_one_slot(*tables().cubic); }

}  // namespace
}  // namespace railtab::accuracy::derivatives_test
