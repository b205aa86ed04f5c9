// SPDX-License-Identifier: Apache-2.0
// The worn scenes' tables (tables/worn_rail.toml, tables/worn_miniprof.toml) end to end against
// the half-space reference: CONTACT has no worn pair in ../shared, so the reference is railtab's
// exact model (src/halfspace, 0.3 mm elements) on the scene's own profiles, as `railtab chart`
// measures them (docs/validation/worn-profiles.md). Each scene's table is made as `railtab
// generate` makes it (sweep, located jumps, the scene's model and creepage grids) with its y nodes
// moved half a step (0.25 mm), so that whole millimetres fall mid-cell, and queried through the
// public lookup. Two measurements, figures in % of mu N:
//  - block C's states (the chart's target creepages b..e at dy -6..10 mm, right wheel, y = -dy,
//    78.5 kN, inside the scene's y range): |F - F_exact| / (mu N_exact), F = (fx, fy) summed over
//    the loaded slots; the table, and the scene's model evaluated directly; tread or flange by the
//    exact model's more loaded slot. Normal force (% of N_exact) and the geometry's contact angle
//    beside them;
//  - random off-grid states (both wheels): per slot, |fx or fy error| / (mu N) of the slots the
//    lookup does not flag low_confidence: the table against its own model (the exact table's
//    second figure), that model against the exact model, and the table against the exact model.
// Asserted, the accuracy rule for these tables: within twice the exact table's targets (block C,
// table against the exact model: tread median / p90 / max 2 / 4 / 10, flange 6 / 12 / 20; random
// states, table against the exact model: tread slot RMS / p99 1 / 4, flange slot 2 / 8; queries
// flagged low_confidence at most 2 %); and every state is evaluated and the queries stay in range.
// The scenes tabulate the exact model (0.4 mm elements), so their table is generated as the scene
// says: five to ten minutes of CPU per scene (docs/validation/worn-profiles.md); it runs only with
// RAILTAB_WORN_ACCURACY=<random states per scene> (e.g. 150):
// RAILTAB_WORN_ACCURACY=150 build/<dir>/tests/test_table_accuracy --gtest_filter='WornTableAccuracy*'
// (RAILTAB_WORN_SCENE=<absolute path>: another scene of a worn pair, e.g. a proposed change).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "accuracy_util.hpp"
#include "adaptive/jump_locator.hpp"
#include "speed_accuracy/speed_accuracy_states.hpp"

namespace railtab::accuracy::worn_scene_accuracy_test {  // own namespace: unity builds compile several test files as one
namespace {

namespace fs = std::filesystem;

constexpr std::uint64_t kSeed = 20261130;

// The accuracy rule (fractions of mu N): twice the exact default table's targets.
struct BlockCRule {
  double median, p90, max;
};
constexpr BlockCRule kBlockCRule[2] = {{0.02, 0.04, 0.10}, {0.06, 0.12, 0.20}};  // tread, flange
struct RandomRule {
  double rms, p99;
};
constexpr RandomRule kRandomRule[kSlots] = {{0.01, 0.04}, {0.02, 0.08}};  // tread, flange slot
constexpr double kFlaggedShare = 0.02;  // queries flagged low_confidence, of the random queries

std::size_t random_state_count() {
  const char* n = std::getenv("RAILTAB_WORN_ACCURACY");
  if (n == nullptr) return 0;
  char* end = nullptr;
  const long v = std::strtol(n, &end, 10);
  if (end == n || *end != '\0' || v < 1)
    throw std::runtime_error(std::string("RAILTAB_WORN_ACCURACY: a whole number >= 1, got '") + n + "'");
  return static_cast<std::size_t>(v);
}

// The scene's y nodes moved half a step up, one more below: whole millimetres mid-cell.
std::vector<double> midway_nodes(const std::vector<double>& y) {
  std::vector<double> out{y.front() - 0.5 * (y[1] - y[0])};
  for (std::size_t i = 0; i + 1 < y.size(); ++i) out.push_back(std::round((y[i] + 0.5 * (y[i + 1] - y[i])) * 1e9) * 1e-9);
  return out;
}

struct Sum {
  double fx = 0.0, fy = 0.0, n = 0.0;
  int dominant = 0;  // the slot with the larger normal force
};
Sum wheel_sum(const double fx[kSlots], const double fy[kSlots], const double n[kSlots]) {
  Sum s;
  for (std::size_t k = 0; k < kSlots; ++k) {
    if (!(n[k] > 0.0)) continue;
    s.fx += fx[k], s.fy += fy[k], s.n += n[k];
  }
  s.dominant = n[1] > n[0] ? 1 : 0;
  return s;
}
Sum direct_sum(const WheelValues& d) {
  return wheel_sum(d.value[lk::kFx], d.value[lk::kFy], d.value[lk::kNormalForce]);
}

// "L 6.31/72" : the left wheel at y = 6.31 mm, 72 kN.
std::string fmt_flagged(std::size_t wheel, const Point& p) {
  return fmt::format("{} {:.2f}/{:.0f}", wheel == 0 ? 'L' : 'R', 1e3 * p.v[kY], 1e-3 * p.v[kLoad]);
}

void measure(const char* file) {
  const std::size_t n_random = random_state_count();
  if (n_random == 0) GTEST_SKIP() << "set RAILTAB_WORN_ACCURACY=<random states per scene> to run (minutes of CPU)";
  Scene scene = load_scene(fs::path(file).is_absolute() ? fs::path(file) : fs::path(RAILTAB_SOURCE_DIR) / "tables" / file);
  scene.grids.y = midway_nodes(scene.grids.y);
  Scene exact = scene;
  exact.normal.model = NormalModel::halfspace;
  exact.halfspace.element_size = 0.3e-3;
  const double mu = scene.tangential.friction;

  const lk::Table table = generated_lookup(scene, "worn_scene_accuracy");
  const std::vector<double>& yn = scene.grids.y;
  std::printf("%s (%s), y nodes moved half a step (%zu, %.2f..%.2f mm), loads %zu, creepages %zu x %zu x %zu; "
              "reference: the exact model, %.1f mm elements\n",
              file, to_string(scene.normal.model), yn.size(), 1e3 * yn.front(), 1e3 * yn.back(), scene.grids.load.size(),
              scene.grids.xi.size(), scene.grids.eta.size(), scene.grids.phi.size(), 1e3 * exact.halfspace.element_size);

  // Block C's states.
  std::vector<SaState> states = target_states(SpeedAccuracyOptions{}, scene);
  std::erase_if(states, [&](const SaState& s) { return !s.creep || s.y <= yn.front() || s.y >= yn.back(); });
  ASSERT_GE(states.size(), 40u);
  std::vector<Point> points(states.size());
  for (std::size_t i = 0; i < states.size(); ++i) {
    points[i].v[kY] = states[i].y, points[i].v[kLoad] = 78.5e3;
    points[i].v[kXi] = states[i].xi, points[i].v[kEta] = states[i].eta, points[i].v[kPhi] = states[i].phi;
  }
  const std::vector<Direct> model = evaluate_direct(scene, points), reference = evaluate_direct(exact, points);
  constexpr std::size_t kRight = 1;
  std::vector<double> err[3][2], n_err[2], angle_err[2];  // [table, model, table vs model][tread, flange]
  std::printf("  dy[mm] set          region  table  model  (%% of mu N_exact)   N table / model / exact [kN]\n");
  for (std::size_t i = 0; i < states.size(); ++i) {
    const lk::Result r = table.query(lk::Wheel::kRight, to_state(table, points[i]));
    ASSERT_EQ(r.status & (lk::status::kOutOfRange | lk::status::kInvalidInput), 0u) << "dy " << states[i].dy_mm;
    double fx[kSlots], fy[kSlots], n[kSlots];
    for (std::size_t k = 0; k < kSlots; ++k)
      fx[k] = r.contact[k].value[lk::kFx], fy[k] = r.contact[k].value[lk::kFy], n[k] = r.contact[k].value[lk::kNormalForce];
    const Sum t = wheel_sum(fx, fy, n), m = direct_sum(model[i][kRight]), e = direct_sum(reference[i][kRight]);
    ASSERT_GT(e.n, 0.0) << "dy " << states[i].dy_mm << ": the exact model finds no contact";
    const int region = e.dominant;
    const double scale = mu * e.n;
    err[0][region].push_back(std::hypot(t.fx - e.fx, t.fy - e.fy) / scale);
    err[1][region].push_back(std::hypot(m.fx - e.fx, m.fy - e.fy) / scale);
    err[2][region].push_back(std::hypot(t.fx - m.fx, t.fy - m.fy) / (mu * std::max(m.n, 1.0)));
    n_err[region].push_back(std::abs(t.n - e.n) / e.n);
    angle_err[region].push_back(std::abs(r.contact[region].value[lk::kContactAngle] -
                                         reference[i][kRight].value[lk::kContactAngle][region]));
    std::printf("  %5.0f  %-12s %-6s %6.2f %6.2f   %7.1f %7.1f %7.1f\n", states[i].dy_mm, states[i].creep_set.c_str(),
                region ? "flange" : "tread", 100 * err[0][region].back(), 100 * err[1][region].back(), 1e-3 * t.n,
                1e-3 * m.n, 1e-3 * e.n);
  }
  for (int g = 0; g < 2; ++g) {
    const char* name = g ? "flange" : "tread";
    std::printf("%s block C states, %s (%zu): |F - F_exact| / (mu N_exact)\n", file, name, err[0][g].size());
    const ErrorFigures table_vs_exact(err[0][g]);
    table_vs_exact.print("  table against the exact model");
    const BlockCRule& rule = kBlockCRule[g];
    EXPECT_LE(table_vs_exact.median, rule.median) << file << " block C " << name << " median";
    EXPECT_LE(table_vs_exact.p90, rule.p90) << file << " block C " << name << " p90";
    EXPECT_LE(table_vs_exact.max, rule.max) << file << " block C " << name << " max";
    ErrorFigures(err[1][g]).print("  model against the exact model");
    ErrorFigures(err[2][g]).print("  table against its model      ");
    ErrorFigures(n_err[g]).print("  normal force, table against exact (of N)");
    ErrorFigures(angle_err[g]).print("  contact angle, table against exact [rad]", false);
  }

  // Random off-grid states, per slot and component.
  const std::vector<Point> random = random_states(scene, n_random, kSeed);
  const std::vector<Direct> own = evaluate_direct(scene, random), ref = evaluate_direct(exact, random);
  std::vector<double> vs_own[kSlots], own_vs_exact[kSlots], vs_exact[kSlots];
  std::size_t flagged = 0;
  std::vector<std::string> flagged_at;  // where the flagged queries are: wheel, y, load
  for (std::size_t i = 0; i < random.size(); ++i)
    for (std::size_t w = 0; w < 2; ++w) {
      const lk::Result r = table.query(static_cast<lk::Wheel>(w), to_state(table, random[i]));
      ASSERT_EQ(r.status & (lk::status::kOutOfRange | lk::status::kInvalidInput), 0u);
      bool any = false;
      for (std::size_t s = 0; s < kSlots; ++s) any = any || (r.contact[s].status & lk::status::kLowConfidence);
      flagged += any;
      if (any) flagged_at.push_back(fmt_flagged(w, random[i]));
      for (std::size_t s = 0; s < kSlots; ++s) {
        if (r.contact[s].status & lk::status::kLowConfidence) continue;
        const double n_own = own[i][w].value[lk::kNormalForce][s], n_ref = ref[i][w].value[lk::kNormalForce][s];
        for (int o : {lk::kFx, lk::kFy}) {
          const double t = r.contact[s].value[o], m = own[i][w].value[o][s], e = ref[i][w].value[o][s];
          if (n_own > 0.0) vs_own[s].push_back(std::abs(t - m) / (mu * n_own));
          if (n_ref > 0.0) {
            own_vs_exact[s].push_back(std::abs(m - e) / (mu * n_ref));
            vs_exact[s].push_back(std::abs(t - e) / (mu * n_ref));
          }
        }
      }
    }
  std::printf("%s, %zu random off-grid states x 2 wheels (seed %llu), %zu queries flagged low_confidence (%.2f %%); "
              "unflagged slots, |fx or fy error| / (mu N):\n",
              file, random.size(), static_cast<unsigned long long>(kSeed), flagged,
              100.0 * static_cast<double>(flagged) / (2.0 * static_cast<double>(random.size())));
  std::printf("  flagged at:");
  for (const std::string& at : flagged_at) std::printf(" %s", at.c_str());
  std::printf("\n");
  for (std::size_t s = 0; s < kSlots; ++s) {
    std::printf("  slot %zu (%s)\n", s, s ? "flange" : "tread");
    ErrorFigures(vs_own[s]).print("    table against its model      ");
    ErrorFigures(own_vs_exact[s]).print("    model against the exact model");
    const ErrorFigures table_vs_exact(vs_exact[s]);
    table_vs_exact.print("    table against the exact model");
    ASSERT_FALSE(vs_exact[s].empty()) << file << " slot " << s << ": no random state loads it";
    EXPECT_LE(table_vs_exact.rms, kRandomRule[s].rms) << file << " random states, slot " << s << " RMS";
    EXPECT_LE(table_vs_exact.p99, kRandomRule[s].p99) << file << " random states, slot " << s << " p99";
  }
  EXPECT_LE(static_cast<double>(flagged), kFlaggedShare * 2.0 * static_cast<double>(random.size())) << file;
}

TEST(WornTableAccuracy, WornRailAgainstTheExactModel) { measure("worn_rail.toml"); }
TEST(WornTableAccuracy, WornMiniProfAgainstTheExactModel) { measure("worn_miniprof.toml"); }
// A scene proposed for a worn pair, measured the same way: RAILTAB_WORN_SCENE=<absolute path>.
TEST(WornTableAccuracy, SceneFromTheEnvironment) {
  const char* file = std::getenv("RAILTAB_WORN_SCENE");
  if (file == nullptr) GTEST_SKIP() << "set RAILTAB_WORN_SCENE=<absolute path of a scene> to measure it";
  measure(file);
}

}  // namespace
}  // namespace railtab::accuracy::worn_scene_accuracy_test
