// SPDX-License-Identifier: Apache-2.0
// End to end against CONTACT (lookup accuracy target, docs/lookup.md "Accuracy"): a table of the
// STRIPES scene set up as the ../shared/reference CONTACT runs (nu 0.28, roll 0, Fz 78.5 kN),
// queried through the public lookup API at the creepage states of block C
// (blockC_sweep_integer_dy.csv), must differ from CONTACT by no more than a direct evaluation of
// the table's own model does, plus 0.5 % of mu N in the median and 1 % in the 90th percentile.
//
// The table: tables/default_stripes.toml with CONTACT's Poisson ratio, roll 0 (no equilibrium roll) and the
// one load 78.5 kN (a load node of the STRIPES scene, so the load axis adds nothing at these
// states); its model, creepage grids, normalised creep coordinates, knees and located jumps are the
// STRIPES scene's. The y nodes are the midpoints of the STRIPES scene's y nodes over the states'
// range (same spacing, 0.25 mm at the flange, 0.5 mm on the tread): the STRIPES grid has a node at
// every integer millimetre, i.e. at every block C state; mid-way between nodes is where the y
// interpolation error is largest; a second table puts them a quarter step from a node. The states:
// CONTACT's creepages and forces mapped as `railtab chart` maps them
// (speed_accuracy/speed_accuracy_states.hpp, docs/speed-vs-accuracy.md "Method"); the states with creepage
// (sets b..e; a_none has no creep force). Metric per state: |F - F_C| / (mu N_C), F the creep-force
// vector (fx, fy) on the wheel summed over the loaded slots, N_C CONTACT's normal force. Direct
// evaluation: the contact kernel at the state (accuracy_util.hpp, evaluate_direct).
//
// Skipped (with a message) when ../shared/reference is absent. Run:
// build/<dir>/tests/test_table_accuracy --gtest_filter='ContactEndToEnd*' (prints the numbers);
// RAILTAB_END_TO_END_SCENE=default.toml for the exact model's table.
#include <fmt/format.h>

#include <cstdio>
#include <cstdlib>

#include "accuracy_util.hpp"
#include "speed_accuracy/speed_accuracy_states.hpp"
#include "adaptive/jump_locator.hpp"

namespace railtab::accuracy {
namespace {

namespace fs = std::filesystem;

constexpr double kMedianMargin = 0.005;  // of mu N (lookup accuracy target)
constexpr double kP90Margin = 0.01;

// The y nodes: y_i + f (y_{i+1} - y_i) over the STRIPES scene's nodes y_i (f = 0.5: midpoints),
// covering [lo, hi] with one node beyond each end. A default node (an integer-mm state) then lies
// between two new nodes, a fraction 1 - f of the step above the lower one (where the steps agree).
std::vector<double> shifted_nodes(const std::vector<double>& y, double f, double lo, double hi) {
  std::vector<double> m;
  m.push_back(y.front() - (1.0 - f) * (y[1] - y[0]));
  for (std::size_t i = 0; i + 1 < y.size(); ++i) m.push_back(y[i] + f * (y[i + 1] - y[i]));
  m.push_back(y.back() + f * (y[y.size() - 1] - y[y.size() - 2]));
  std::vector<double> out;
  for (std::size_t i = 0; i < m.size(); ++i) {
    const bool reaches_lo = i + 1 < m.size() && m[i + 1] > lo;  // not below the last node <= lo
    const bool reaches_hi = i == 0 || m[i - 1] < hi;            // not above the first node >= hi
    if (reaches_lo && reaches_hi) out.push_back(std::round(m[i] * 1e9) * 1e-9);
  }
  return out;
}

double percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  const double pos = q * static_cast<double>(v.size() - 1);
  const std::size_t i = static_cast<std::size_t>(pos);
  const double f = pos - static_cast<double>(i);
  return i + 1 < v.size() ? v[i] * (1.0 - f) + v[i + 1] * f : v[i];
}

struct Forces {
  double fx = 0.0, fy = 0.0;
};

// `fraction`: where the y nodes sit between the STRIPES scene's (shifted_nodes).
void table_against_contact(double fraction) {
  const fs::path ref = fs::path(RAILTAB_SHARED_DIR) / "reference" / "blockC_sweep_integer_dy.csv";
  if (!fs::exists(ref)) GTEST_SKIP() << "CONTACT reference " << ref.string() << " absent (../shared/reference)";
  std::vector<SaState> states = read_contact_states(ref, SpeedAccuracyOptions{});
  std::erase_if(states, [](const SaState& s) { return !s.creep; });
  ASSERT_GE(states.size(), 60u);

  // RAILTAB_END_TO_END_SCENE=<name in tables/>: another scene set up the same way (the exact
  // model's, default.toml: docs/validation/exact-tables.md).
  const char* other = std::getenv("RAILTAB_END_TO_END_SCENE");
  Scene scene = load_scene(fs::path(RAILTAB_SOURCE_DIR) / "tables" / (other ? other : "default_stripes.toml"));
  ASSERT_TRUE(contact_reference_applies(scene));
  double ylo = states.front().y, yhi = ylo;
  for (const SaState& s : states) {
    ASSERT_EQ(s.load, 78.5e3);
    ASSERT_EQ(s.friction, scene.tangential.friction) << "CONTACT's mu must be the scene's (F / (mu N) tables)";
    ylo = std::min(ylo, s.y), yhi = std::max(yhi, s.y);
  }
  scene.material.poisson_ratio = 0.28;  // CONTACT's material (E = 210 GPa is the scene's)
  scene.equilibrium_roll = false;
  scene.grids.roll = {0.0};
  scene.grids.load = {78.5e3};
  scene.grids.y = shifted_nodes(scene.grids.y, fraction, ylo, yhi);
  scene.text += fmt::format("\n# contact_end_to_end_test overrides: poisson_ratio 0.28, roll 0, load 78.5e3, y nodes "
                            "shifted by {:g} of the step\n", fraction);

  // The states lie between nodes (at least an eighth of the step from both; the quarter
  // placement puts the state at y = -6 mm, where the step changes, 1/7 of its cell from a node).
  const std::vector<double>& yn = scene.grids.y;
  for (const SaState& s : states) {
    const auto it = std::upper_bound(yn.begin(), yn.end(), s.y);
    ASSERT_TRUE(it != yn.begin() && it != yn.end()) << "dy " << s.dy_mm << " mm outside the y nodes";
    const double lo = *(it - 1), hi = *it;
    ASSERT_GT(std::min(s.y - lo, hi - s.y), 0.125 * (hi - lo)) << "dy " << s.dy_mm << " mm near a node";
  }

  const lk::Table table = generated_lookup(scene, "contact_end_to_end");

  std::vector<Point> points(states.size());
  for (std::size_t i = 0; i < states.size(); ++i) {
    const SaState& s = states[i];
    points[i].v[kY] = s.y, points[i].v[kLoad] = s.load;
    points[i].v[kXi] = s.xi, points[i].v[kEta] = s.eta, points[i].v[kPhi] = s.phi;
  }
  const std::vector<Direct> direct = evaluate_direct(scene, points);
  constexpr std::size_t kRight = 1;

  // [0 table, 1 direct][0 tread, 1 flange, 2 all]
  std::vector<double> err[2][3];
  std::printf("y nodes at %g of the STRIPES scene's steps (%zu nodes, %.4f..%.4f m); block C creep states (right "
              "wheel), |F - F_CONTACT| / (mu N_CONTACT), F = (fx, fy) on the wheel:\n"
              "  dy[mm] set           table   direct   (fx, fy) CONTACT [N]   table [N]   direct [N]\n",
              fraction, yn.size(), yn.front(), yn.back());
  for (std::size_t i = 0; i < states.size(); ++i) {
    const SaState& s = states[i];
    const lk::Result r = table.query(lk::Wheel::kRight, to_state(table, points[i]));
    Forces f[2];
    for (std::size_t k = 0; k < kSlots; ++k) {
      if (r.contact[k].value[lk::kNormalForce] > 0.0) {
        f[0].fx += r.contact[k].value[lk::kFx];
        f[0].fy += r.contact[k].value[lk::kFy];
      }
      if (direct[i][kRight].value[lk::kNormalForce][k] > 0.0) {
        f[1].fx += direct[i][kRight].value[lk::kFx][k];
        f[1].fy += direct[i][kRight].value[lk::kFy][k];
      }
    }
    const double scale = s.friction * s.ref_fn;
    ASSERT_GT(scale, 0.0);
    double e[2];
    for (int v = 0; v < 2; ++v) {
      e[v] = std::hypot(f[v].fx - s.ref_fx, f[v].fy - s.ref_fy) / scale;
      err[v][s.flange ? 1 : 0].push_back(e[v]);
      err[v][2].push_back(e[v]);
    }
    std::printf("  %5.0f  %-12s %7.4f  %7.4f   (%7.0f, %7.0f)   (%7.0f, %7.0f)   (%7.0f, %7.0f)%s\n", s.dy_mm,
                s.creep_set.c_str(), e[0], e[1], s.ref_fx, s.ref_fy, f[0].fx, f[0].fy, f[1].fx, f[1].fy,
                e[0] > e[1] + kP90Margin ? "  <- table off by > 1 % more than direct" : "");
  }
  const char* names[3] = {"tread (dy <= 6 mm)", "flange (dy >= 7 mm)", "all"};
  for (int g = 0; g < 3; ++g)
    std::printf("%-20s %2zu states: table median %.4f p90 %.4f max %.4f | direct median %.4f p90 %.4f max %.4f (of mu N)\n",
                names[g], err[0][g].size(), percentile(err[0][g], 0.5), percentile(err[0][g], 0.9),
                percentile(err[0][g], 1.0), percentile(err[1][g], 0.5), percentile(err[1][g], 0.9),
                percentile(err[1][g], 1.0));
  EXPECT_LE(percentile(err[0][2], 0.5), percentile(err[1][2], 0.5) + kMedianMargin);
  EXPECT_LE(percentile(err[0][2], 0.9), percentile(err[1][2], 0.9) + kP90Margin);
}

// States mid-way between y nodes (the largest y interpolation error), and a quarter step from one.
TEST(ContactEndToEnd, StatesMidwayBetweenYNodes) { table_against_contact(0.5); }
TEST(ContactEndToEnd, StatesAQuarterStepFromAYNode) { table_against_contact(0.75); }

}  // namespace
}  // namespace railtab::accuracy
