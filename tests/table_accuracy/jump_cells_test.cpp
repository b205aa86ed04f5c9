// SPDX-License-Identifier: Apache-2.0
// Contact jumps (docs/validation/contact-jumps.md, docs/lookup.md "Contact jumps"): the generator
// locates every jump along y per wheel and load node (jump_locator.hpp) and the lookup interpolates
// a cell cut by one from the query's side only. Measured here on the STRIPES scene at the random
// states of stripes_scene_accuracy_test (same seed): the creep forces of every cell that is not
// smooth, with the metric of the smooth cells, |F_lookup - F_direct| / (mu N), for the table with
// its jumps (format 2.1) and the same table without them (the lookup of format 2.0), in two
// classes: jump cells (a located jump of the slot inside the cell) and status-change cells
// (classify_point says jump, e.g. two-point contact or a status bit changing, but no located jump
// cuts the cell). The states beyond 2 % of mu N are listed with their distance from the nearest
// located jump (RAILTAB_JUMP_MISSES_CSV=<file> writes all of them).
//
// Run: build/<dir>/tests/test_table_accuracy --gtest_filter='JumpCells*' (prints the numbers).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <optional>

#include "accuracy_util.hpp"
#include "adaptive/contact_probe.hpp"
#include "adaptive/jump_locator.hpp"

namespace railtab::accuracy::jump_cells_test {  // own namespace: unity builds compile several test files as one
namespace {

constexpr std::uint64_t kSeed = kStripesStatesSeed;  // the states of StripesSceneRandomOffGrid
constexpr std::size_t kPoints = kStripesStates;
constexpr double kLimit = 0.02;            // of mu N (contact jumps target)
constexpr double kCrossingSumLimit = 0.02;  // of N: the sum over the slots between crossing jumps' positions

struct JumpFixture {
  Scene scene;
  Table table;
  ContactJumps jumps;
  Table with_table;                      // the generator's table with /jumps
  std::optional<lk::Table> with_jumps, without_jumps;
  double locate_seconds = 0.0;           // locate_jumps + add_jumps (one-sided values)
  std::uintmax_t bytes_without = 0, bytes_with = 0;  // table files [B]
};

const JumpFixture& fixture() {
  static const JumpFixture f = [] {
    JumpFixture x;
    const StripesSweep& d = stripes_sweep();
    x.scene = d.scene;
    x.table = d.table;
    const std::filesystem::path plain = temp_table_path("jumps_plain"), jumps = temp_table_path("jumps");
    write_for_lookup(x.table, plain);
    x.without_jumps.emplace(lk::Table::load(plain.string()));
    const auto t0 = std::chrono::steady_clock::now();
    x.jumps = d.jumps;
    Table with = x.table;
    add_jumps(with, x.scene, x.jumps);
    x.locate_seconds = d.locate_seconds + std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    write_for_lookup(with, jumps);
    x.with_table = with;
    x.with_jumps.emplace(lk::Table::load(jumps.string()));
    x.bytes_without = std::filesystem::file_size(plain);
    x.bytes_with = std::filesystem::file_size(jumps);
    std::filesystem::remove(plain);
    std::filesystem::remove(jumps);
    return x;
  }();
  return f;
}

// Nearest located jump of the wheel to y over the load nodes around `load` [m] (and the jump).
double distance_to_jump(const JumpFixture& f, std::size_t wheel, double y, double load,
                        const ContactJump** nearest = nullptr) {
  const std::vector<double>& loads = f.scene.grids.load;
  std::size_t l = static_cast<std::size_t>(std::upper_bound(loads.begin(), loads.end(), load) - loads.begin());
  l = std::clamp<std::size_t>(l, 1, loads.size() - 1) - 1;
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t k : {l, l + 1})
    for (const ContactJump& j : f.jumps.wheel[wheel][k])
      if (std::abs(y - j.y) < d) {
        d = std::abs(y - j.y);
        if (nearest) *nearest = &j;
      }
  return d;
}

// Every jump found is a real one: the contact chain differs between the ends of its interval (the
// located y -+ half the tolerance), and the flange onset is found for both wheels at every load.
TEST(JumpCells, LocatedJumpsSeparateTwoConfigurations) {
  const JumpFixture& f = fixture();
  const ContactProbe probe(f.scene);
  const JumpLocatorOptions options;
  std::size_t total = 0;
  for (std::size_t w = 0; w < 2; ++w) {
    ASSERT_EQ(f.jumps.wheel[w].size(), f.scene.grids.load.size());
    for (std::size_t l = 0; l < f.scene.grids.load.size(); ++l) {
      bool flange_onset = false;
      double last = -1.0;
      for (const ContactJump& j : f.jumps.wheel[w][l]) {
        ++total;
        EXPECT_GT(j.y, last);
        last = j.y;
        flange_onset |= (j.kind & jump_kind::kPatchSlot1) != 0;
        const double load = f.scene.grids.load[l];
        const auto a = probe.evaluate(j.y - 0.5 * options.tolerance, {load}, {{0.0, 0.0, 0.0}})[0][0][w];
        const auto b = probe.evaluate(j.y + 0.5 * options.tolerance, {load}, {{0.0, 0.0, 0.0}})[0][0][w];
        bool differ = false;
        for (int s = 0; s < 2; ++s) {
          differ |= a.slot[s].status != b.slot[s].status;
          differ |= std::abs(a.slot[s].rolling_radius - b.slot[s].rolling_radius) > options.radius_step;
          differ |= std::abs(a.slot[s].patch_radius - b.slot[s].patch_radius) > options.radius_step;
        }
        EXPECT_TRUE(differ) << "wheel " << w << " load " << load << " y " << j.y << " kind " << j.kind;
      }
      EXPECT_TRUE(flange_onset) << "wheel " << w << " load " << f.scene.grids.load[l];
    }
  }
  std::printf("STRIPES scene: %zu jumps located (both wheels, %zu loads), %zu evaluations; with the one-sided "
              "values %.2f s; table file %.0f KiB without jumps, %.0f KiB with\n",
              total, f.scene.grids.load.size(), f.jumps.evaluations, f.locate_seconds,
              static_cast<double>(f.bytes_without) / 1024.0, static_cast<double>(f.bytes_with) / 1024.0);
  for (std::size_t w = 0; w < 2; ++w)
    for (std::size_t l = 0; l < f.scene.grids.load.size(); ++l) {
      std::printf("  %s wheel, load %.0f N:", w == 0 ? "left" : "right", f.scene.grids.load[l]);
      for (const ContactJump& j : f.jumps.wheel[w][l]) std::printf(" %.6f m (kind %u)", j.y, j.kind);
      std::printf("\n");
    }
}

struct JumpStats {
  std::size_t cells = 0, within = 0;
  double max_error = 0.0;
};

// The kind bits of a jump that concern slot s (0 tread, 1 flange): jump_kind's even bits are
// slot 0's, the odd ones slot 1's.
constexpr std::uint32_t kSlotKinds[kSlots] = {0x155u, 0x2AAu};

// The located jump of the wheel that cuts the slot's (y, load) cell of `p` (a jump of that slot
// strictly between the cell's y nodes at either load node of the cell), nullptr if none.
const ContactJump* jump_in_cell(const JumpFixture& f, std::size_t wheel, std::size_t slot, const Point& p) {
  auto lower = [](const std::vector<double>& x, double v) {
    const std::size_t i = static_cast<std::size_t>(std::upper_bound(x.begin(), x.end(), v) - x.begin());
    return std::clamp<std::size_t>(i, 1, x.size() - 1) - 1;
  };
  const std::vector<double>& ys = f.scene.grids.y;
  const std::size_t iy = lower(ys, p.v[kY]), il = lower(f.scene.grids.load, p.v[kLoad]);
  const ContactJump* found = nullptr;
  for (std::size_t l : {il, il + 1})
    for (const ContactJump& j : f.jumps.wheel[wheel][l])
      if ((j.kind & kSlotKinds[slot]) && j.y > ys[iy] && j.y < ys[iy + 1] &&
          (!found || std::abs(j.y - p.v[kY]) < std::abs(found->y - p.v[kY])))
        found = &j;
  return found;
}

// Error of the slot's creep force: the larger over fx, fy of |lookup - direct| / (mu N), N the
// slot's larger normal force of lookup and direct; both 0 (a flange loaded only at this creepage,
// load coupling): the load. Returns (error, output).
std::pair<double, int> slot_error(const lk::Result& r, const WheelValues& direct, std::size_t s, double mu, double load) {
  double worst = 0.0;
  int worst_output = lk::kFx;
  for (int o : {lk::kFx, lk::kFy}) {
    const double err = std::abs(r.contact[s].value[o] - direct.value[o][s]);
    double n = std::max(direct.value[lk::kNormalForce][s], r.contact[s].value[lk::kNormalForce]);
    if (!(n > 0.0)) n = load;
    const double rel = err / (mu * n);
    if (rel > worst) worst = rel, worst_output = o;
  }
  return {worst, worst_output};
}

// Cells of the creep part measured here (smooth cells are StripesSceneRandomOffGrid's):
//   jump: a located jump of the slot lies inside the cell (jump_in_cell): the one-sided lookup's
//     own case (contact jumps target: >= 99 % within 2 % of mu N);
//   status change: classify_point calls the cell a jump (statuses differ between corners, two-point
//     contact, Hertz/strip switch, ...) but no located jump cuts it: the lookup interpolates as in a
//     smooth cell, so its error is the creepage and y interpolation error, not a jump's.
enum Category { kJumpInside = 0, kStatusChange = 1, kCategories = 2 };
constexpr const char* kCategoryNames[kCategories] = {"jump cells (a located jump inside)",
                                                     "status-change cells (no located jump inside)"};

// `creepage_nodes`: xi, eta, phi on random values of the scene's creepage lists; else uniform like
// y and load (the states of StripesSceneRandomOffGrid). With normalised creep coordinates (format
// 2.1, the STRIPES scene) the list values are NOT the table's creep nodes (those sit at each slot's
// own scale), so both variants carry the creepage interpolation error
// (docs/validation/creep-interpolation.md); each miss is therefore re-measured at its cell's y node
// on its side of the jump, which separates that error from the jump's and y's. Env
// RAILTAB_JUMP_MISSES_CSV=<file>: every state beyond the limit written there (the print is capped).
void creep_forces_on_jump_cells(bool creepage_nodes) {
  const JumpFixture& f = fixture();
  const TableView view(f.table);
  const std::vector<double>* grids[kNumVars] = {&f.scene.grids.y, &f.scene.grids.load, &f.scene.grids.xi,
                                                &f.scene.grids.eta, &f.scene.grids.phi};
  Random rng(kSeed);
  std::vector<Point> points(kPoints);
  for (Point& p : points)
    for (int k = 0; k < kNumVars; ++k) {
      p.v[k] = rng.uniform(grids[k]->front(), grids[k]->back());
      if (creepage_nodes && k >= kXi) {
        const std::vector<double>& g = *grids[k];
        const double u = rng.uniform(0.0, static_cast<double>(g.size()));
        p.v[k] = g[std::min(g.size() - 1, static_cast<std::size_t>(u))];
      }
    }
  // All uniform: the states of stripes_direct() (the same draws), whose direct evaluation is made
  // once per process; checked to be the same states bit for bit.
  if (!creepage_nodes) {
    const std::vector<Point>& shared = stripes_direct().points;
    ASSERT_EQ(shared.size(), points.size());
    for (std::size_t i = 0; i < points.size(); ++i)
      ASSERT_EQ(std::memcmp(shared[i].v, points[i].v, sizeof points[i].v), 0) << "state " << i;
  }
  const std::vector<Direct> direct = creepage_nodes ? evaluate_direct(f.scene, points) : stripes_direct().direct;
  const double mu = f.scene.tangential.friction;

  JumpStats stats[2][kCategories][kSlots];  // [0 without jumps, 1 with][category][slot]
  // The wheel's total creep force (both slots summed) at wheel-states with a jump cell: a jump that
  // only moves one contact from one slot to the other (e.g. kind 192 at y = +-5.59 mm: the tread
  // patch becomes the flange slot's, same N and forces, at a y that moves with load and creepage)
  // is a full miss per slot but none in total. Reported only (the acceptance counts slots).
  JumpStats wheel_stats[2];  // [0 without jumps, 1 with]
  struct Miss {
    double error, distance, y, load, xi, eta, phi;
    std::size_t wheel, slot;
    int output, category;
    std::uint32_t kind;  // the nearest located jump's kind
    double node_y = 0.0;      // the y node of the cell on the state's side of the jump (else the nearest)
    double node_error = 0.0;  // the same error there (same load and creepages): the creepage part
  };
  std::vector<Miss> misses;
  std::size_t states_in[kCategories] = {}, unchanged_differ = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (std::size_t w = 0; w < 2; ++w) {
      const PointKinds kinds = classify_point(view, w, points[i], direct[i][w]);
      const lk::Result r[2] = {f.without_jumps->query(static_cast<lk::Wheel>(w), to_state(*f.without_jumps, points[i])),
                               f.with_jumps->query(static_cast<lk::Wheel>(w), to_state(*f.with_jumps, points[i]))};
      bool any[kCategories] = {};
      for (std::size_t s = 0; s < kSlots; ++s) {
        const CellKind kind = kinds.kind[lk::kCreep][s];
        if (kind == CellKind::kEmpty) continue;
        const ContactJump* inside = jump_in_cell(f, w, s, points[i]);
        if (!inside && kind != CellKind::kJump) continue;  // smooth: StripesSceneRandomOffGrid
        const int cat = inside ? kJumpInside : kStatusChange;
        any[cat] = true;
        for (int v = 0; v < 2; ++v) {
          const auto [worst, worst_output] = slot_error(r[v], direct[i][w], s, mu, points[i].v[kLoad]);
          JumpStats& st = stats[v][cat][s];
          ++st.cells;
          st.within += worst <= kLimit;
          st.max_error = std::max(st.max_error, worst);
          if (v == 1 && worst > kLimit) {
            const ContactJump* near = inside;
            const double d = near ? std::abs(points[i].v[kY] - near->y)
                                  : distance_to_jump(f, w, points[i].v[kY], points[i].v[kLoad], &near);
            const std::vector<double>& ys = f.scene.grids.y;
            const auto up = std::clamp(std::upper_bound(ys.begin(), ys.end(), points[i].v[kY]), ys.begin() + 1, ys.end() - 1);
            const double lo = *(up - 1), hi = *up, y = points[i].v[kY];
            const double node = inside ? (y < inside->y ? lo : hi) : (y - lo < hi - y ? lo : hi);
            misses.push_back({worst, d, y, points[i].v[kLoad], points[i].v[kXi], points[i].v[kEta], points[i].v[kPhi], w,
                              s, worst_output, cat, near ? near->kind : 0u, node});
          }
        }
        // No jump cuts the cell: the lookup with jumps must interpolate it exactly as without.
        if (cat == kStatusChange)
          for (int o : {lk::kFx, lk::kFy, lk::kNormalForce})
            unchanged_differ += r[0].contact[s].value[o] != r[1].contact[s].value[o];
      }
      for (int c = 0; c < kCategories; ++c) states_in[c] += any[c];
      if (any[kJumpInside])
        for (int v = 0; v < 2; ++v) {
          double sum[2][3] = {};  // [lookup, direct][fx, fy, N]
          for (std::size_t s = 0; s < kSlots; ++s)
            for (int k = 0; k < 3; ++k) {
              const int o = k == 0 ? lk::kFx : k == 1 ? lk::kFy : lk::kNormalForce;
              sum[0][k] += r[v].contact[s].value[o];
              sum[1][k] += direct[i][w].value[o][s];
            }
          double n = std::max(sum[0][2], sum[1][2]);
          if (!(n > 0.0)) n = points[i].v[kLoad];
          const double err = std::max(std::abs(sum[0][0] - sum[1][0]), std::abs(sum[0][1] - sum[1][1])) / (mu * n);
          ++wheel_stats[v].cells;
          wheel_stats[v].within += err <= kLimit;
          wheel_stats[v].max_error = std::max(wheel_stats[v].max_error, err);
        }
    }
  }
  // Each miss again at its cell's y node on its side of the jump (same load and creepages): what
  // is left there is the creepage (and load) interpolation error, not the jump's nor y's.
  std::vector<Point> at_node(misses.size());
  for (std::size_t k = 0; k < misses.size(); ++k) {
    const Miss& m = misses[k];
    at_node[k].v[kY] = m.node_y, at_node[k].v[kLoad] = m.load;
    at_node[k].v[kXi] = m.xi, at_node[k].v[kEta] = m.eta, at_node[k].v[kPhi] = m.phi;
  }
  const std::vector<Direct> node_direct = evaluate_direct(f.scene, at_node);
  std::size_t node_misses[kCategories][kSlots] = {}, slot_misses[kCategories][kSlots] = {};
  for (std::size_t k = 0; k < misses.size(); ++k) {
    Miss& m = misses[k];
    const lk::Result r = f.with_jumps->query(static_cast<lk::Wheel>(m.wheel), to_state(*f.with_jumps, at_node[k]));
    m.node_error = slot_error(r, node_direct[k][m.wheel], m.slot, mu, m.load).first;
    ++slot_misses[m.category][m.slot];
    node_misses[m.category][m.slot] += m.node_error > kLimit;
  }
  std::printf("%s\n", creepage_nodes ? "CREEPAGES AT THE SCENE'S LIST VALUES (y, load uniform; not the creep nodes of a "
                                                       "normalised table)"
                                      : "ALL UNIFORM (y, load, xi, eta, phi: with the creepage interpolation error)");
  std::printf("STRIPES scene, creep forces: %zu random states x 2 wheels (seed %llu); wheel-states with a jump cell "
              "in a slot: %zu (%.1f %%), with a status-change cell: %zu (%.1f %%); error = max over fx, fy of "
              "|lookup - direct| / (mu N), N the slot's larger normal force of lookup and direct (the load where "
              "both are 0)\n",
              points.size(), static_cast<unsigned long long>(kSeed), states_in[kJumpInside],
              100.0 * static_cast<double>(states_in[kJumpInside]) / (2.0 * static_cast<double>(points.size())),
              states_in[kStatusChange],
              100.0 * static_cast<double>(states_in[kStatusChange]) / (2.0 * static_cast<double>(points.size())));
  for (int c = 0; c < kCategories; ++c)
    for (int v = 0; v < 2; ++v)
      for (std::size_t s = 0; s < kSlots; ++s) {
        const JumpStats& st = stats[v][c][s];
        std::printf("  %-44s %-26s slot %zu: %5zu cells, %5.1f %% within %.0f %% of mu N, max %.3g mu N\n",
                    kCategoryNames[c], v == 0 ? "without jumps (format 2.0)" : "with jumps (format 2.1)", s, st.cells,
                    st.cells ? 100.0 * static_cast<double>(st.within) / static_cast<double>(st.cells) : 100.0,
                    100.0 * kLimit, st.max_error);
      }
  for (int v = 0; v < 2; ++v)
    std::printf("  wheel totals (both slots summed) at wheel-states with a jump cell, %-26s: %5zu, %5.1f %% within %.0f %% "
                "of mu N, max %.3g mu N\n",
                v == 0 ? "without jumps (format 2.0)" : "with jumps (format 2.1)", wheel_stats[v].cells,
                wheel_stats[v].cells ? 100.0 * static_cast<double>(wheel_stats[v].within) /
                                           static_cast<double>(wheel_stats[v].cells)
                                     : 100.0,
                100.0 * kLimit, wheel_stats[v].max_error);
  std::sort(misses.begin(), misses.end(), [](const Miss& a, const Miss& b) {
    return a.category != b.category ? a.category < b.category : a.error > b.error;
  });
  if (const char* csv = std::getenv("RAILTAB_JUMP_MISSES_CSV")) {
    if (FILE* out = std::fopen(csv, "w")) {
      std::fprintf(out, "category,wheel,slot,y_m,load_N,xi,eta,phi_rad_per_m,output,error_mu_n,distance_mm,jump_kind,"
                        "node_y_m,node_error_mu_n\n");
      for (const Miss& m : misses)
        std::fprintf(out, "%s,%s,%zu,%.9g,%.9g,%.9g,%.9g,%.9g,%s,%.6g,%.6g,%u,%.9g,%.6g\n",
                     m.category == kJumpInside ? "jump" : "status_change", m.wheel == 0 ? "left" : "right", m.slot,
                     m.y, m.load, m.xi, m.eta, m.phi, lk::output_name(static_cast<lk::Output>(m.output)), m.error,
                     m.distance * 1e3, m.kind, m.node_y, m.node_error);
      std::fclose(out);
      std::printf("  all %zu states beyond %.0f %% of mu N written to %s\n", misses.size(), 100.0 * kLimit, csv);
    }
  }
  for (int c = 0; c < kCategories; ++c) {
    std::vector<const Miss*> list;
    for (const Miss& m : misses)
      if (m.category == c) list.push_back(&m);
    std::printf("  %s, with jumps, beyond %.0f %% of mu N: %zu (largest first; distance = the jump inside the cell, "
                "else the nearest located jump of the wheel at the two load nodes around the state):\n",
                kCategoryNames[c], 100.0 * kLimit, list.size());
    for (std::size_t sl = 0; sl < kSlots; ++sl)
      std::printf("    slot %zu: %zu, of which %zu are beyond %.0f %% at the cell's y node on their side too (the creepage "
                  "interpolation error), %zu only between the nodes\n",
                  sl, slot_misses[c][sl], node_misses[c][sl], 100.0 * kLimit, slot_misses[c][sl] - node_misses[c][sl]);
    for (std::size_t k = 0; k < list.size(); ++k) {
      const Miss& m = *list[k];
      if (k >= 25) {
        std::printf("    ... %zu more (RAILTAB_JUMP_MISSES_CSV=<file> writes them all)\n", list.size() - k);
        break;
      }
      std::printf("    %s wheel slot %zu y %.6f m load %.0f N (xi %.3g eta %.3g phi %.3g): %s error %.3f mu N (%.3f at "
                  "y node %.6f m), %.3f mm from a jump (kind %u)\n",
                  m.wheel == 0 ? "left" : "right", m.slot, m.y, m.load, m.xi, m.eta, m.phi,
                  lk::output_name(static_cast<lk::Output>(m.output)), m.error, m.node_error, m.node_y, m.distance * 1e3,
                  m.kind);
    }
  }
  // The one-sided lookup must not be worse than blending across the jump on the same states, and
  // must not touch a cell no located jump cuts.
  for (std::size_t s = 0; s < kSlots; ++s) {
    EXPECT_GT(stats[1][kJumpInside][s].cells, 0u);
    EXPECT_GE(stats[1][kJumpInside][s].within, stats[0][kJumpInside][s].within) << "slot " << s;
  }
  EXPECT_EQ(unchanged_differ, 0u) << "lookup values of status-change cells changed by the jumps";
}

// Normalised creep coordinates with jumps (s4-15c + s4-15j): a query just left of (right of) a
// jump in a cut cell takes the one-sided values of that side, the creep part's scales included.
// At a physical xi that is an interior v node at the side's own scale (eta, phi 0: their middle
// nodes, symmetric ranges), the lookup must give the kernel's value at the sample's own y, up to
// the 1e-12 m between the query and the stored jump y. A scale from the other side (or the grid)
// would put xi between v nodes and differ by the creep interpolation error (~1e-3 of mu N or more).
TEST(JumpCells, NormalisedCreepTakesTheQuerysSideScales) {
  const JumpFixture& f = fixture();
  if (!f.scene.creep_normalised) GTEST_SKIP() << "the STRIPES scene does not use normalised creep coordinates";
  const double mu = f.scene.tangential.friction;
  const std::vector<double>& xi = f.scene.grids.xi;
  ASSERT_EQ(f.scene.grids.eta.front(), -f.scene.grids.eta.back());
  ASSERT_EQ(f.scene.grids.phi.front(), -f.scene.grids.phi.back());
  ASSERT_EQ(f.scene.grids.eta.size() % 2, 1u);
  ASSERT_EQ(f.scene.grids.phi.size() % 2, 1u);
  const std::vector<double> v_nodes = creep_map::nodes(xi.size());
  const double v = v_nodes[v_nodes.size() / 2 + 1];  // first node above 0: below saturation
  const char* names[2] = {"left", "right"};
  std::size_t checked = 0;
  double worst = 0.0;
  for (std::size_t w = 0; w < 2; ++w) {
    const TableGroup* normal = f.with_table.group(std::string("jumps/") + names[w] + "/normal");
    ASSERT_NE(normal, nullptr);
    const TableDataset* scale = normal->find("creep_scale_xi");
    ASSERT_NE(scale, nullptr) << "one-sided creep scales missing";
    const std::size_t count = scale->shape[1];
    for (std::size_t l = 0; l < f.scene.grids.load.size(); ++l)
      for (std::size_t j = 0; j < f.jumps.wheel[w][l].size(); ++j) {
        const ContactJump& jump = f.jumps.wheel[w][l][j];
        for (std::size_t side = 0; side < 2; ++side) {
          Point at;
          at.v[kLoad] = f.scene.grids.load[l];
          at.v[kY] = side == 0 ? jump.left : jump.right;
          Point query = at;
          query.v[kY] = jump.y + (side == 0 ? -1e-12 : 1e-12);
          for (std::size_t s = 0; s < kSlots; ++s) {
            const double sxi = scale->values[((l * count + j) * 2 + side) * kSlots + s];
            at.v[kXi] = query.v[kXi] = creep_map::physical(v, xi.front(), xi.back(), sxi);
            const Direct direct = evaluate_direct(f.scene, at);
            const double n = direct[w].value[lk::kNormalForce][s];
            if (!(n > 0.0)) continue;  // no loaded patch in this slot at this side
            const lk::Result r = f.with_jumps->query(static_cast<lk::Wheel>(w), to_state(*f.with_jumps, query));
            for (int o : {lk::kFx, lk::kFy}) {
              const double err = std::abs(r.contact[s].value[o] - direct[w].value[o][s]) / (mu * n);
              worst = std::max(worst, err);
              EXPECT_LT(err, 1e-4) << names[w] << " wheel, load " << at.v[kLoad] << " N, jump at " << jump.y
                                   << " m, side " << side << ", slot " << s << ", output " << o;
            }
            ++checked;
          }
        }
      }
  }
  std::printf("one-sided normalised creep at %zu (jump, side, slot) states: max |lookup - kernel| = %.2e mu N\n",
              checked, worst);
  EXPECT_GT(checked, 0u);
}

// A state at y with load and creepages uniform over the table's axes.
lk::State state_at(const lk::Table& table, double y, std::mt19937& rng) {
  lk::State s = table.default_state();
  s.y = y;
  for (const lk::AxisInfo& a : table.axes()) {
    const double x = std::uniform_real_distribution<double>(a.nodes.front(), a.nodes.back())(rng);
    if (a.name == "load") s.load = x;
    else if (a.name == "xi") s.xi = x;
    else if (a.name == "eta") s.eta = x;
    else if (a.name == "phi") s.phi = x;
  }
  return s;
}

// The one-sided path's sum kernels (weighted_sum.hpp, jump_sum) exist for SSE2 and AVX2 with the
// same arithmetic: both give the same bytes at states within 0.1 mm of every located jump (cut
// cells, both sides) and at the jumps themselves. On a CPU without AVX2 both loads run SSE2.
TEST(JumpCells, Avx2AndSse2GiveTheSameBytesInCutCells) {
  const JumpFixture& f = fixture();
  const std::filesystem::path path = temp_table_path("jumps_simd");
  write_for_lookup(f.with_table, path);
  ::setenv("RAILTAB_LOOKUP_NO_AVX2", "1", 1);
  const lk::Table sse2 = lk::Table::load(path.string());
  ::unsetenv("RAILTAB_LOOKUP_NO_AVX2");
  const lk::Table best = lk::Table::load(path.string());
  std::filesystem::remove(path);
  std::mt19937 rng(15);
  std::size_t compared = 0;
  for (std::size_t w = 0; w < 2; ++w)
    for (const auto& list : f.jumps.wheel[w])
      for (const ContactJump& j : list)
        for (int k = 0; k < 8; ++k) {
          const lk::State s =
              state_at(best, j.y + (k == 0 ? 0.0 : std::uniform_real_distribution<double>(-1e-4, 1e-4)(rng)), rng);
          const lk::Result a = sse2.query(static_cast<lk::Wheel>(w), s);
          const lk::Result b = best.query(static_cast<lk::Wheel>(w), s);
          ASSERT_EQ(std::memcmp(&a, &b, sizeof a), 0) << "wheel " << w << " y " << s.y;
          ++compared;
        }
  EXPECT_GT(compared, 100u);
}

// A jump whose place in its node's list differs at the other load node of its cell (it crosses
// another jump between the two loads): its wheel, load cell and the y span between its positions.
// Paired as the lookup pairs them: the k-th jump of a kind with the other node's k-th of that kind
// (the STRIPES scene's jumps carry either geometric or patch bits, never both, so the kind is the
// lookup's pairing key there).
struct CrossingJump {
  std::size_t wheel, load_cell;
  double lo, hi;
};

// The fixture's table with jumps loaded for the generic query path (no fused query), to check both.
lk::Table generic_path_table(const JumpFixture& f, const char* name) {
  const std::filesystem::path path = temp_table_path(name);
  write_for_lookup(f.with_table, path);
  ::setenv("RAILTAB_LOOKUP_NO_FAST_PATH", "1", 1);
  lk::Table generic = lk::Table::load(path.string());
  ::unsetenv("RAILTAB_LOOKUP_NO_FAST_PATH");
  std::filesystem::remove(path);
  return generic;
}

std::vector<CrossingJump> crossing_jumps(const JumpFixture& f) {
  std::vector<CrossingJump> crossings;
  for (std::size_t w = 0; w < 2; ++w)
    for (std::size_t l = 0; l + 1 < f.jumps.wheel[w].size(); ++l) {
      const std::vector<ContactJump>& a = f.jumps.wheel[w][l];
      const std::vector<ContactJump>& b = f.jumps.wheel[w][l + 1];
      for (std::size_t k = 0; k < a.size(); ++k) {
        const auto rank = std::count_if(a.begin(), a.begin() + static_cast<std::ptrdiff_t>(k),
                                        [&](const ContactJump& j) { return j.kind == a[k].kind; });
        std::ptrdiff_t seen = 0;
        const auto other = std::find_if(b.begin(), b.end(), [&](const ContactJump& j) {
          return j.kind == a[k].kind && seen++ == rank;
        });
        if (other == b.end() || static_cast<std::size_t>(other - b.begin()) == k) continue;
        crossings.push_back({w, l, std::min(a[k].y, other->y), std::max(a[k].y, other->y)});
      }
    }
  return crossings;
}

// Two jumps of different kinds that cross between two load nodes (on the STRIPES scene the
// tread-flange hand-over of the normal patch passes the flange root's rigid-point jump between
// 78.5 and 100 kN): between the positions that one jump takes at the two nodes, one node holds
// the patch in one slot and the other in the other, so a query blends the two (the patch's force
// split over both slots, though its sum is right: the test below).
// Such queries are low confidence in every slot (docs/lookup.md "Low confidence"), by the fused
// and the generic path.
TEST(JumpCells, QueriesBetweenTheLoadNodesPositionsOfACrossingJumpAreLowConfidence) {
  const JumpFixture& f = fixture();
  const std::vector<double>& loads = f.scene.grids.load;
  const lk::Table generic = generic_path_table(f, "jumps_crossing");
  const std::vector<CrossingJump> crossings = crossing_jumps(f);
  std::size_t checked = 0;
  for (const CrossingJump& c : crossings)
    for (int i = 1; i <= 4; ++i) {
      lk::State s = f.with_jumps->default_state();
      s.y = c.lo + (c.hi - c.lo) * i / 5.0;
      s.load = 0.5 * (loads[c.load_cell] + loads[c.load_cell + 1]);
      for (const lk::Table* t : {&*f.with_jumps, &generic}) {
        const lk::Result r = t->query(static_cast<lk::Wheel>(c.wheel), s);
        for (int slot = 0; slot < r.n_slots; ++slot)
          EXPECT_TRUE(r.contact[slot].status & lk::status::kLowConfidence)
              << "wheel " << c.wheel << " y " << s.y << " load " << s.load << " slot " << slot
              << (t == &generic ? " (generic path)" : " (fused path)");
        ++checked;
      }
    }
  EXPECT_GT(crossings.size(), 0u) << "the STRIPES scene's jumps no longer cross between load nodes: choose another case";
  std::printf("crossing jumps: %zu, states checked: %zu\n", crossings.size(), checked);
}

// The sum over the slots between the load nodes' positions of a crossing jump: the lookup pairs
// the two nodes' jumps by kind there and each node reads its values on the query's side of the
// geometric jumps (crossing_pieces, jump_piece.hpp), so the wheel's normal force summed over the
// slots is the model's though the slots' split is blended (and flagged, above). Paired by order,
// one node read the other side of the flange root's rigid-point jump and the sum missed the
// model's. States: 4 y between the two positions of each crossing jump, at 3 loads inside the
// load cell, zero creepage; against the model (railtab eval) at the same state, by the fused and the
// generic path. Measured: worst 0.005 % of N (paired by order: 5.1 %, 22 of 48 states over 2 %).
TEST(JumpCells, SumOverTheSlotsBetweenTheLoadNodesPositionsOfACrossingJumpIsTheModels) {
  const JumpFixture& f = fixture();
  const std::vector<double>& loads = f.scene.grids.load;
  std::vector<Point> points;
  std::vector<std::size_t> wheel;
  for (const CrossingJump& c : crossing_jumps(f))
    for (int i = 1; i <= 4; ++i)
      for (double s : {0.25, 0.5, 0.75}) {
        Point p;
        p.v[kY] = c.lo + (c.hi - c.lo) * i / 5.0;
        p.v[kLoad] = (1.0 - s) * loads[c.load_cell] + s * loads[c.load_cell + 1];
        points.push_back(p);
        wheel.push_back(c.wheel);
      }
  ASSERT_FALSE(points.empty()) << "the STRIPES scene's jumps no longer cross between load nodes: choose another case";
  const std::vector<Direct> direct = evaluate_direct(f.scene, points);
  const lk::Table generic = generic_path_table(f, "jumps_crossing_sum");
  double worst = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::size_t w = wheel[i];
    for (const lk::Table* t : {&*f.with_jumps, &generic}) {
      const lk::Result r = t->query(static_cast<lk::Wheel>(w), to_state(*t, points[i]));
      double lookup = 0.0, model = 0.0;
      for (int s = 0; s < r.n_slots; ++s) lookup += r.contact[s].value[lk::kNormalForce];
      for (std::size_t s = 0; s < kSlots; ++s) model += direct[i][w].value[lk::kNormalForce][s];
      ASSERT_GT(model, 0.0);
      const double error = std::abs(lookup - model) / model;
      worst = std::max(worst, error);
      EXPECT_LE(error, kCrossingSumLimit) << "wheel " << w << " y " << points[i].v[kY] << " load " << points[i].v[kLoad]
                                          << ": N summed over the slots, lookup " << lookup << ", model " << model
                                          << (t == &generic ? " (generic path)" : " (fused path)");
    }
  }
  std::printf("crossing jumps: %zu states, N summed over the slots, worst %.3f %% of the model's\n", points.size(),
              100.0 * worst);
}

// Cubic methods next to a jump (docs/lookup.md "Contact jumps"): a cell no located jump cuts, with
// a cut cell beside it, interpolates from its own side only: the cubic y stencil drops the node
// across the cut cell (as at a table edge). Checked by changing that node's values (every part,
// every load, one wheel) and asserting that the cubic and monotone cubic results in the cell keep
// their bytes. Cells chosen so that no jump of the wheel lies in them at any load node, nor sweeps
// across them between two load nodes (so the lookup does not treat them as cut).
TEST(JumpCells, CubicStencilsStayOnTheCellsSideOfAJump) {
  const JumpFixture& f = fixture();
  const std::vector<double>& ys = f.scene.grids.y;
  const char* names[2] = {"left", "right"};
  std::mt19937 rng(1515);
  std::size_t cases = 0, compared = 0;
  const std::filesystem::path original_path = temp_table_path("jumps_stencil_original");
  write_for_lookup(f.with_table, original_path);
  const lk::Table original[2] = {lk::Table::load(original_path.string(), {lk::Method::kCubic}),
                                 lk::Table::load(original_path.string(), {lk::Method::kMonotoneCubic})};
  std::filesystem::remove(original_path);
  for (std::size_t w = 0; w < 2; ++w) {
    const auto& loads = f.jumps.wheel[w];
    // No jump of the wheel in [ys[q], ys[q + 1]] at any load node, none crossing it between two.
    auto clear = [&](std::size_t q) {
      for (std::size_t l = 0; l < loads.size(); ++l)
        for (std::size_t j = 0; j < loads[l].size(); ++j) {
          const double y = loads[l][j].y;
          if (y >= ys[q] && y <= ys[q + 1]) return false;
          if (l + 1 < loads.size() && loads[l + 1].size() == loads[l].size() &&
              (y < ys[q]) != (loads[l + 1][j].y < ys[q]))
            return false;
        }
      return true;
    };
    // (query cell q, node p across the cut cell beside it), one per jump side, every third jump.
    std::vector<std::pair<std::size_t, std::size_t>> picks;
    const auto& middle = loads[loads.size() / 2];
    for (std::size_t j = 0; j < middle.size(); j += 3) {
      const std::size_t c = static_cast<std::size_t>(std::upper_bound(ys.begin(), ys.end(), middle[j].y) - ys.begin()) - 1;
      if (c >= 1 && c + 2 < ys.size() && clear(c - 1)) picks.push_back({c - 1, c + 1});
      if (c + 3 < ys.size() && clear(c + 1)) picks.push_back({c + 1, c});
    }
    for (const auto& [q, p] : picks) {
      Table changed = f.with_table;
      for (TableGroup& g : changed.groups) {
        if (g.path.rfind(std::string(names[w]) + "/", 0) != 0) continue;
        for (TableDataset& d : g.datasets) {
          if (d.is_status || d.axes.empty() || d.axes[0] != "y") continue;
          const std::size_t slice = d.values.size() / d.shape[0];
          for (std::size_t k = p * slice; k < (p + 1) * slice; ++k) d.values[k] = 1.5 * d.values[k] + 1e-3;
        }
      }
      const std::filesystem::path path = temp_table_path("jumps_stencil");
      write_for_lookup(changed, path);
      for (const lk::Table& before : original) {
        const lk::Table after = lk::Table::load(path.string(), {before.method()});
        for (int k = 0; k < 16; ++k) {
          const lk::State s = state_at(before, std::uniform_real_distribution<double>(ys[q], ys[q + 1])(rng), rng);
          const lk::Result a = before.query(static_cast<lk::Wheel>(w), s);
          const lk::Result b = after.query(static_cast<lk::Wheel>(w), s);
          ASSERT_EQ(std::memcmp(&a, &b, sizeof a), 0)
              << names[w] << " wheel, method " << static_cast<int>(before.method()) << ", y " << s.y << " m in cell ["
              << ys[q] << ", " << ys[q + 1] << "], node " << ys[p] << " m changed";
          ++compared;
        }
      }
      std::filesystem::remove(path);
      ++cases;
    }
  }
  std::printf("cubic stencils next to jumps: %zu cells, %zu queries unchanged by the node across the jump\n", cases,
              compared);
  EXPECT_GE(cases, 4u);
}

// The one-sided values reuse what they can (jump_samples.cpp): an end at a y node is the sweep's
// column there, and an end two jumps share (one bisection step apart) is computed once. Both must
// be the bytes of computing each end on its own: three jumps a step apart around a y node, per
// wheel and load, with the sweep's parts in the table (copied) and without them (computed), and
// the last jump alone (its shared end computed for it).
TEST(JumpCells, SharedAndNodeEndsAreTheComputedColumns) {
  const StripesSweep& d = stripes_sweep();
  const std::vector<double>& y = d.scene.grids.y;
  const double node = y[y.size() / 2 + 3], h = 1e-6;
  ContactJumps jumps, last;
  for (std::size_t w = 0; w < 2; ++w)
    for (std::size_t l = 0; l < d.scene.grids.load.size(); ++l) {
      jumps.wheel[w].push_back({{node - 0.5 * h, jump_kind::kPatchSlot1, node - h, node},
                                {node + 0.5 * h, jump_kind::kPatchSlot1, node, node + h},
                                {node + 1.5 * h, jump_kind::kPatchSlot1, node + h, node + 2 * h}});
      last.wheel[w].push_back({jumps.wheel[w].back()[2]});
    }
  Table copied = d.table, computed = d.table, alone = d.table;
  for (Table* t : {&computed, &alone})  // no sweep parts: every end is computed
    t->groups.erase(std::remove_if(t->groups.begin(), t->groups.end(),
                                   [](const TableGroup& g) { return g.path.rfind("left/", 0) == 0 || g.path.rfind("right/", 0) == 0; }),
                    t->groups.end());
  add_jumps(copied, d.scene, jumps);
  add_jumps(computed, d.scene, jumps);
  add_jumps(alone, d.scene, last);
  std::size_t datasets = 0, compared = 0;
  for (const TableGroup& g : copied.groups) {
    if (g.path.rfind(std::string(kJumpGroup) + "/", 0) != 0) continue;
    const TableGroup* c = computed.group(g.path);
    const TableGroup* a = alone.group(g.path);
    ASSERT_NE(c, nullptr) << g.path;
    ASSERT_NE(a, nullptr) << g.path;
    for (const TableDataset& ds : g.datasets) {
      const TableDataset* cs = c->find(ds.name);
      const TableDataset* as = a->find(ds.name);
      ASSERT_NE(cs, nullptr) << g.path << "/" << ds.name;
      ASSERT_NE(as, nullptr) << g.path << "/" << ds.name;
      EXPECT_EQ(ds.values, cs->values) << g.path << "/" << ds.name;
      EXPECT_EQ(ds.status, cs->status) << g.path << "/" << ds.name;
      // [load,] jump, side, rest: jump 2 of `copied` is jump 0 of `alone`.
      const bool status = ds.is_status;
      const std::size_t n = status ? ds.status.size() : ds.values.size();
      const std::size_t jump_axis = static_cast<std::size_t>(
          std::find(ds.axes.begin(), ds.axes.end(), kJumpDimension) - ds.axes.begin());
      ASSERT_LT(jump_axis, ds.axes.size());
      std::size_t inner = 1, outer = 1;
      for (std::size_t k = jump_axis + 1; k < ds.shape.size(); ++k) inner *= ds.shape[k];
      for (std::size_t k = 0; k < jump_axis; ++k) outer *= ds.shape[k];
      ASSERT_EQ(n, outer * 3 * inner);
      for (std::size_t o = 0; o < outer; ++o)
        for (std::size_t k = 0; k < inner; ++k) {
          const std::size_t at = (o * 3 + 2) * inner + k, there = o * inner + k;
          if (status)
            EXPECT_EQ(ds.status[at], as->status[there]) << g.path << "/" << ds.name;
          else
            EXPECT_EQ(ds.values[at], as->values[there]) << g.path << "/" << ds.name;
          ++compared;
        }
      ++datasets;
    }
  }
  EXPECT_GT(datasets, 10u);
  EXPECT_GT(compared, 1000u);
}

TEST(JumpCells, CreepForcesOnJumpCellsAtCreepageNodes) { creep_forces_on_jump_cells(true); }
TEST(JumpCells, CreepForcesOnJumpCells) { creep_forces_on_jump_cells(false); }

}  // namespace
}  // namespace railtab::accuracy::jump_cells_test
