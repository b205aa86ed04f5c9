// SPDX-License-Identifier: Apache-2.0
// Shared machinery of the table accuracy tests (docs/lookup.md, "Accuracy"): generate a table
// with the generator API, load it with the lookup, evaluate off-grid states directly with the
// contact kernel, and classify each (state, wheel, slot, part) as a smooth cell (every corner
// node of the interpolation cell and the direct evaluation share one status word) or a jump cell.
//
// Direct evaluation: the contact kernel itself (make_contact_kernel) on a copy of the scene whose
// grids are the one state (y, load, xi, eta, phi; roll = the scene's equilibrium roll at y). That
// is exactly the code path of the sweep (geometry, slot rules, load-controlled normal contact,
// FASTSIM, Archard, statuses), with no kernel logic repeated here; building a kernel costs
// ~0.1 ms (profiles and solver), small next to the solve.
#pragma once

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "railtab/lookup.hpp"
#include "adaptive/jump_locator.hpp"
#include "scene/scene.hpp"
#include "kernel/contact_kernel.hpp"
#include "kernel/creep_map.hpp"
#include "engine/sweep.hpp"
#include "table/table_io.hpp"

namespace railtab::accuracy {

namespace lk = railtab::lookup;

// State variables a table of these tests may tabulate (roll follows the equilibrium).
enum Var : int { kY = 0, kLoad = 1, kXi = 2, kEta = 3, kPhi = 4, kNumVars = 5 };
inline const char* const kVarNames[kNumVars] = {"y", "load", "xi", "eta", "phi"};

struct Point {
  double v[kNumVars] = {};  // y [m], load [N], xi [1], eta [1], phi [rad/m]
};

inline lk::State to_state(const lk::Table& table, const Point& p) {
  lk::State s = table.default_state();
  s.y = p.v[kY];
  s.load = p.v[kLoad];
  s.xi = p.v[kXi];
  s.eta = p.v[kEta];
  s.phi = p.v[kPhi];
  return s;
}

// Status bits compared between corner nodes: all but full_slip, which marks saturation
// |F| = mu N of the creep force, a kink along the creepages (FASTSIM's forces are continuous
// through it), not a jump.
inline constexpr StatusBits kCompared = ~status::kFullSlip;

// Fixed-seed uniform numbers, the same on every platform (std::uniform_real_distribution is not).
class Random {
 public:
  explicit Random(std::uint64_t seed) : state_(seed) {}
  double uniform(double lo, double hi) { return lo + (hi - lo) * static_cast<double>(next() >> 11) * 0x1.0p-53; }

 private:
  std::uint64_t next() {  // splitmix64
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  std::uint64_t state_;
};

// The scene's grid of one state variable (kY, kLoad, kXi, kEta, kPhi).
inline const std::vector<double>& scene_grid(const Scene& scene, int var) {
  const std::vector<double>* grids[kNumVars] = {&scene.grids.y, &scene.grids.load, &scene.grids.xi, &scene.grids.eta,
                                                &scene.grids.phi};
  return *grids[var];
}

// n states drawn uniformly over the ranges of the scene's grids (off the nodes with probability 1),
// the same on every platform for one seed.
inline std::vector<Point> random_states(const Scene& scene, std::size_t n, std::uint64_t seed) {
  Random rng(seed);
  std::vector<Point> points(n);
  for (Point& p : points)
    for (int k = 0; k < kNumVars; ++k) p.v[k] = rng.uniform(scene_grid(scene, k).front(), scene_grid(scene, k).back());
  return points;
}

// Every output and status of both slots of one wheel, indexed like the lookup (lk::Output, lk::Part).
struct WheelValues {
  double value[lk::kNumOutputs][kSlots] = {};
  StatusBits status[lk::kNumParts][kSlots] = {};
};
using Direct = std::array<WheelValues, 2>;  // [wheel] 0 left, 1 right

// The creep part's per-creepage normal force (load coupling), which the lookup serves in place of
// the normal part's creepage-free one (docs/lookup.md).
inline bool is_creep_normal(int o) { return o == lk::kNormalForce; }

// The lookup output of every kernel output, in kernel order (-1: an output the lookup does not
// serve, e.g. the normal part's creep scales of format 2.1). The creep part's normal_force maps
// to kNormalForce and, coming later, overrides the normal part's.
inline std::vector<int> lookup_outputs(const SweepKernel& kernel) {
  std::vector<int> index;
  for (std::size_t p = 0; p < kernel.parts.size(); ++p)
    for (const OutputInfo& info : kernel.parts[p].outputs) {
      int found = -1;
      for (int o = 0; o < lk::kNumOutputs; ++o)
        if ((lk::output_part(static_cast<lk::Output>(o)) == static_cast<int>(p) ||
             (static_cast<int>(p) == lk::kCreep && is_creep_normal(o))) &&
            (info.name == lk::output_name(static_cast<lk::Output>(o)) ||
             info.name == std::string(lk::output_name(static_cast<lk::Output>(o))) + "_normalised"))
          found = o;
      index.push_back(found);
    }
  return index;
}

// The kernel's parts and the lookup's outputs must be the kernel's, in the same order
// (docs/table-format.md); the kernel may have more (the creep part's normal contact, the normal
// part's creep scales), which are skipped here.
inline void check_kernel_layout(const SweepKernel& kernel) {
  ASSERT_EQ(kernel.parts.size(), static_cast<std::size_t>(lk::kNumParts));
  for (int p = 0; p < lk::kNumParts; ++p)
    ASSERT_EQ(kernel.parts[static_cast<std::size_t>(p)].name, lk::part_name(static_cast<lk::Part>(p)));
  const std::vector<int> index = lookup_outputs(kernel);
  int o = 0;
  std::size_t i = 0;
  for (std::size_t p = 0; p < kernel.parts.size(); ++p)
    for (std::size_t k = 0; k < kernel.parts[p].outputs.size(); ++k, ++i) {
      if (index[i] < 0 || lk::output_part(static_cast<lk::Output>(index[i])) != static_cast<int>(p)) continue;
      ASSERT_EQ(index[i], o++);
    }
  ASSERT_EQ(o, lk::kNumOutputs);
}

// The contact kernel at one state (both wheels), as the sweep computes a grid point; `yaw` [rad]
// for a scene with yaw (its grid is then that one value).
inline Direct evaluate_direct(const Scene& scene, const Point& p, double yaw = 0.0) {
  Scene one = scene;
  if (!scene.grids.yaw.empty()) one.grids.yaw = {yaw};
  one.creep_normalised = false;  // the physical creep forces at the state itself
  one.grids.y = {p.v[kY]};
  one.grids.load = {p.v[kLoad]};
  one.grids.xi = {p.v[kXi]};
  one.grids.eta = {p.v[kEta]};
  one.grids.phi = {p.v[kPhi]};
  const SweepKernel kernel = make_contact_kernel(one);
  std::vector<std::size_t> first_output{0};
  for (const PartSpec& part : kernel.parts) first_output.push_back(first_output.back() + part.outputs.size());
  const std::size_t total = first_output.back(), parts = kernel.parts.size();
  std::vector<double> values(2 * total * kSlots, 0.0);
  std::vector<StatusBits> statuses(2 * parts * kSlots, 0u);  // empty slots keep 0, as in the sweep
  std::vector<double*> value_ptr;
  std::vector<StatusBits*> status_ptr;
  for (std::size_t i = 0; i < 2 * total; ++i) value_ptr.push_back(values.data() + i * kSlots);
  for (std::size_t i = 0; i < 2 * parts; ++i) status_ptr.push_back(statuses.data() + i * kSlots);
  ColumnOutput out(value_ptr, status_ptr, first_output, parts);
  ColumnState state;
  state.y = p.v[kY];
  state.roll = scene.equilibrium_roll ? kernel.equilibrium_roll(p.v[kY]) : scene.grids.roll.front();
  state.yaw = yaw;
  kernel.compute(state, out);
  const std::vector<int> index = lookup_outputs(kernel);
  Direct d;
  for (std::size_t w = 0; w < 2; ++w) {
    for (std::size_t o = 0; o < total; ++o) {
      if (index[o] < 0) continue;  // not served by the lookup
      for (std::size_t s = 0; s < kSlots; ++s)
        d[w].value[static_cast<std::size_t>(index[o])][s] = values[(w * total + o) * kSlots + s];
    }
    for (std::size_t q = 0; q < parts; ++q)
      for (std::size_t s = 0; s < kSlots; ++s) d[w].status[q][s] = statuses[(w * parts + q) * kSlots + s];
  }
  return d;
}

// Many states in parallel (each state independent: the result does not depend on the threads).
inline std::vector<Direct> evaluate_direct(const Scene& scene, const std::vector<Point>& points) {
  std::vector<Direct> out(points.size());
  tbb::parallel_for(std::size_t{0}, points.size(), [&](std::size_t i) { out[i] = evaluate_direct(scene, points[i]); });
  return out;
}

// The generated table written for the lookup exactly as `railtab generate` writes it (fixed_axes
// {"roll":"equilibrium"} included: the lookup ignores roll then, and every value at y was computed
// at the equilibrium roll of that y, which is what the direct evaluation uses too).
inline void write_for_lookup(const Table& table, const std::filesystem::path& path) { write_table(table, path); }

inline std::filesystem::path temp_table_path(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         ("railtab_table_accuracy_" + std::to_string(::getpid()) + "_" + name + ".h5");
}

// The table written to a temporary file (`name`) as `railtab generate` writes it and loaded
// through the public lookup API; the file is removed.
inline lk::Table load_through_file(const Table& table, const std::string& name, const lk::LoadOptions& options = {}) {
  const std::filesystem::path file = temp_table_path(name);
  write_for_lookup(table, file);
  lk::Table loaded = lk::Table::load(file.string(), options);
  std::filesystem::remove(file);
  return loaded;
}

// The scene's table as `railtab generate` makes it (sweep, located jumps with their one-sided
// values), loaded through the public lookup API.
inline lk::Table generated_lookup(const Scene& scene, const std::string& name) {
  SweepResult sweep = run_sweep(scene, make_contact_kernel(scene), SweepOptions{});
  if (sweep.summary.failures) throw std::runtime_error(scene.name + ": " + sweep.summary.first_failure);
  add_jumps(sweep.table, scene, locate_jumps(scene));
  return load_through_file(sweep.table, name);
}

// The STRIPES scene (tables/default_stripes.toml), its swept table (without jumps) and its located jumps,
// computed once per process. The test files that measure the STRIPES table start from it (each
// adds the jumps to its own copy, as `railtab generate` does), and CTest runs their suites in one
// process (tests/table_accuracy/CMakeLists.txt): the sweep and the jump search are deterministic,
// so every test sees the table it would compute itself, generated once instead of once per test.
struct StripesSweep {
  Scene scene;
  Table table;                  // the sweep's table, no /jumps (format 2.0 layout of the jumps)
  ContactJumps jumps;           // locate_jumps(scene)
  double sweep_seconds = 0.0;   // run_sweep
  double locate_seconds = 0.0;  // locate_jumps
};

inline const StripesSweep& stripes_sweep() {
  static const StripesSweep d = [] {
    StripesSweep x;
    x.scene = load_scene(std::filesystem::path(RAILTAB_SOURCE_DIR) / "tables" / "default_stripes.toml");
    auto t0 = std::chrono::steady_clock::now();
    SweepResult r = run_sweep(x.scene, make_contact_kernel(x.scene), SweepOptions{});
    x.sweep_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (r.summary.failures) throw std::runtime_error("STRIPES table: " + r.summary.first_failure);
    x.table = std::move(r.table);
    t0 = std::chrono::steady_clock::now();
    x.jumps = locate_jumps(x.scene);
    x.locate_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return x;
  }();
  return d;
}

// The random off-grid states of the STRIPES scene's accuracy measurements (StripesSceneRandomOffGrid
// and the jump cells' CreepForcesOnJumpCells measure the same states) and their direct evaluation,
// computed once per process like stripes_sweep().
inline constexpr std::uint64_t kStripesStatesSeed = 20240611;
inline constexpr std::size_t kStripesStates = 4000;  // random states, both wheels each

struct StripesDirect {
  std::vector<Point> points;   // random_states(STRIPES scene, kStripesStates, kStripesStatesSeed)
  std::vector<Direct> direct;  // evaluate_direct at each
  double seconds = 0.0;        // evaluate_direct
};

inline const StripesDirect& stripes_direct() {
  static const StripesDirect d = [] {
    StripesDirect x;
    const Scene& scene = stripes_sweep().scene;
    x.points = random_states(scene, kStripesStates, kStripesStatesSeed);
    const auto t0 = std::chrono::steady_clock::now();
    x.direct = evaluate_direct(scene, x.points);
    x.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return x;
  }();
  return d;
}

// The generator's in-memory table seen per (wheel, part): node values and statuses, cell lookup,
// and second differences along each axis (the curvature estimate of the tolerances).
class TableView {
 public:
  explicit TableView(const Table& table) {
    for (std::size_t w = 0; w < 2; ++w) {
      for (int p = 0; p < lk::kNumParts; ++p) {
        const std::string path = std::string(w == 0 ? "left/" : "right/") + lk::part_name(static_cast<lk::Part>(p));
        const TableGroup* g = table.group(path);
        if (!g) throw std::runtime_error("table has no " + path);
        PartGrid& pg = grid_[w][static_cast<std::size_t>(p)];
        const TableDataset* st = g->find("status");
        pg.status = &st->status;
        for (std::size_t a = 0; a + 1 < st->axes.size(); ++a) {  // the last axis is slot
          int var = -1;
          for (int k = 0; k < kNumVars; ++k)
            if (st->axes[a] == kVarNames[k]) var = k;
          if (var < 0) throw std::runtime_error("unexpected axis " + st->axes[a]);
          pg.vars.push_back(var);
          pg.nodes.push_back(&table.axis(st->axes[a])->values);
        }
        pg.stride.assign(pg.vars.size(), 0);
        std::size_t stride = kSlots;
        for (std::size_t a = pg.vars.size(); a-- > 0;) {
          pg.stride[a] = stride;
          stride *= pg.nodes[a]->size();
        }
        for (int o = 0; o < lk::kNumOutputs; ++o)
          if (lk::output_part(static_cast<lk::Output>(o)) == p) {
            const std::string name = lk::output_name(static_cast<lk::Output>(o));
            const TableDataset* ds = g->find(name) ? g->find(name) : g->find(name + "_normalised");
            pg.values[o] = &ds->values;
          }
        if (p == lk::kCreep && g->find("normal_force")) {  // load coupling: served by the lookup
          coupled_ = true;
          pg.values[lk::kNormalForce] = &g->find("normal_force")->values;
        }
        if (p == lk::kNormal && g->find("creep_scale_xi"))
          for (int k = 0; k < 3; ++k) scale_values_[w][k] = &g->find(kScaleNames[k])->values;
      }
    }
    if (const std::string* text = table.attribute("creep_map")) {
      const nlohmann::json j = nlohmann::json::parse(*text);
      normalised_ = true;
      friction_ = j.at("friction").get<double>();
      law_spin_ = j.value("law_spin", 0.0);
      for (int k = 0; k < 3; ++k) {
        const std::string name = kVarNames[kXi + k];
        if (!j.contains(name + "_min")) continue;
        swept_[k] = true;
        lo_[k] = j.at(name + "_min").get<double>();
        hi_[k] = j.at(name + "_max").get<double>();
        knee_[k] = j.value(name + "_knee", 1.0);
      }
      if (coupled_ && j.value("normal_force", std::string()) == "vertical_share")
        for (std::size_t w = 0; w < 2; ++w) normal_from_share(w);
    }
  }

  bool normalised() const { return normalised_; }
  // The creep part's normal_force holds the vertical share N cos(angle) + fy sin(angle) (creep_map
  // "normal_force": "vertical_share"): N at every creep node, as the lookup recovers it there, so
  // that the tolerances see N's own curvature. Needs the creep part over (y, load, xi, eta, phi).
  void normal_from_share(std::size_t w) {
    PartGrid& pc = grid_[w][lk::kCreep];
    const PartGrid& pg = grid_[w][lk::kGeometry];
    // The load axis may be fixed (a table of one load): then it is not among the creep part's axes.
    const bool load_axis = pc.vars == std::vector<int>{kY, kLoad, kXi, kEta, kPhi};
    if ((!load_axis && pc.vars != std::vector<int>{kY, kXi, kEta, kPhi}) || pg.vars != std::vector<int>{kY})
      throw std::runtime_error("vertical share: unexpected creep or geometry axes");
    const std::size_t first_creep = load_axis ? 2 : 1, axes = first_creep + 3;
    const std::vector<double>& share = *pc.values[lk::kNormalForce];
    const std::vector<double>& fy = *pc.values[lk::kFy];
    const std::vector<double>& angle = *pg.values[lk::kContactAngle];
    std::vector<double>& n = n_creep_[w];
    n.resize(share.size());
    const std::size_t nl = load_axis ? pc.nodes[1]->size() : 1;
    for (std::size_t i = 0; i < share.size(); ++i) {
      std::size_t idx[5] = {};
      for (std::size_t a = 0; a < axes; ++a) idx[a] = (i / pc.stride[a]) % pc.nodes[a]->size();
      const std::size_t s = i % kSlots;
      const std::size_t normal_node = (idx[0] * nl + (load_axis ? idx[1] : 0)) * kSlots + s;
      double x[3];
      for (int k = 0; k < 3; ++k) {
        const double scale = (*scale_values_[w][k])[normal_node];
        const std::size_t a = first_creep + static_cast<std::size_t>(k);
        const double v = (*pc.nodes[a])[idx[a]];
        x[k] = creep_map::physical(v, lo_[k], hi_[k], scale * knee_[k]) / scale;
      }
      const double ry = fy[i] + creep_map::law(x[0], x[1], x[2], law_spin_)[1];
      const double a = angle[idx[0] * kSlots + s];
      n[i] = share[i] / (std::cos(a) + friction_ * ry * std::sin(a));
    }
    pc.values[lk::kNormalForce] = &n;
  }

  // The part whose grid and status an output's lookup value comes from: the creep part for the
  // per-creepage normal contact when the table has it.
  int part_of(int o) const {
    return coupled_ && is_creep_normal(o) ? static_cast<int>(lk::kCreep) : lk::output_part(static_cast<lk::Output>(o));
  }
  // Format 2.1: `p` with its creepages replaced by the creep part's coordinates v for this wheel
  // and slot (the slot's scales interpolated at (y, load) as the lookup does); `p` unchanged for a
  // physical table.
  Point creep_point(std::size_t wheel, std::size_t slot, const Point& p) const {
    if (!normalised_) return p;
    Point q = p;
    for (int k = 0; k < 3; ++k) {
      if (!swept_[k]) continue;
      const double s = slot_scale(wheel, slot, k, p) * knee_[k];  // m(x / k): the map at scale s k
      q.v[kXi + k] = creep_map::coordinate(std::clamp(p.v[kXi + k], lo_[k], hi_[k]), lo_[k], hi_[k], s);
    }
    return q;
  }
  // Format 2.1: the physical creepage of coordinate v along creepage axis k (0 xi, 1 eta, 2 phi)
  // at the (y, load) of `p`, wheel and slot.
  double physical_creepage(std::size_t wheel, std::size_t slot, int k, const Point& p, double v) const {
    return creep_map::physical(v, lo_[k], hi_[k], slot_scale(wheel, slot, k, p) * knee_[k]);
  }
  // The slot's scale of creepage axis k at the (y, load) of `p`, as the lookup interpolates it.
  double slot_scale(std::size_t wheel, std::size_t slot, int k, const Point& p) const {
    const Cell c = cell(wheel, lk::kNormal, p);
    const PartGrid& pg = grid_[wheel][lk::kNormal];
    double s = 0.0;
    for (std::size_t corner = 0; corner < (std::size_t{1} << pg.vars.size()); ++corner) {
      double w = 1.0;
      for (std::size_t a = 0; a < pg.vars.size(); ++a)
        w *= ((corner >> (pg.vars.size() - 1 - a)) & 1u) ? c.t[a] : 1.0 - c.t[a];
      if (w != 0.0) s += w / (*scale_values_[wheel][k])[corner_index(pg, c, corner) + slot];
    }
    return 1.0 / s;  // the lookup interpolates the reciprocals (lookup/src/creep_map.hpp)
  }

  // The interpolation cell of `p` for a part: lower node index and fraction per axis.
  struct Cell {
    std::vector<std::size_t> lower;
    std::vector<double> t, h;
  };
  Cell cell(std::size_t wheel, int part, const Point& p) const {
    const PartGrid& pg = grid_[wheel][static_cast<std::size_t>(part)];
    Cell c;
    for (std::size_t a = 0; a < pg.vars.size(); ++a) {
      const std::vector<double>& x = *pg.nodes[a];
      const double v = std::clamp(p.v[pg.vars[a]], x.front(), x.back());
      std::size_t i = static_cast<std::size_t>(std::upper_bound(x.begin(), x.end(), v) - x.begin());
      i = std::clamp<std::size_t>(i, 1, x.size() - 1) - 1;
      c.lower.push_back(i);
      c.h.push_back(x[i + 1] - x[i]);
      c.t.push_back((v - x[i]) / c.h.back());
    }
    return c;
  }

  // Statuses of the 2^D corner nodes of the cell (slot `slot`).
  std::vector<StatusBits> corner_status(std::size_t wheel, int part, const Cell& c, std::size_t slot) const {
    const PartGrid& pg = grid_[wheel][static_cast<std::size_t>(part)];
    std::vector<StatusBits> out;
    for (std::size_t k = 0; k < (std::size_t{1} << pg.vars.size()); ++k)
      out.push_back((*pg.status)[corner_index(pg, c, k) + slot]);
    return out;
  }

  // Values of an output at the 2^D corner nodes of its part's cell (slot `slot`).
  std::vector<double> corner_values(std::size_t wheel, int output, const Cell& c, std::size_t slot) const {
    const PartGrid& pg = grid_[wheel][static_cast<std::size_t>(part_of(output))];
    std::vector<double> out;
    for (std::size_t k = 0; k < (std::size_t{1} << pg.vars.size()); ++k)
      out.push_back((*pg.values[output])[corner_index(pg, c, k) + slot]);
    return out;
  }

  // Multilinear error bound of the cell: sum over axes of h^2/8 |f''| (the cell-wide bound, not
  // t(1-t)/2 h^2 |f''| at the point: a kink of the core's output next to a node, e.g. where the
  // contact crosses a joint of the S1002 profile's arcs, makes the error near the node larger
  // than the t-weighted estimate), |f''| the
  // largest second divided difference along that axis at the cell's corner nodes (and, at the
  // table edge, the nearest interior node), using only nodes whose status equals the corner's
  // (a difference across a jump measures the jump, not the curvature).
  double error_estimate(std::size_t wheel, int output, const Cell& c, std::size_t slot) const {
    const int part = part_of(output);
    const PartGrid& pg = grid_[wheel][static_cast<std::size_t>(part)];
    const std::vector<double>& f = *pg.values[output];
    double sum = 0.0;
    for (std::size_t a = 0; a < pg.vars.size(); ++a) {
      const std::vector<double>& x = *pg.nodes[a];
      if (x.size() < 3) continue;  // two nodes: no curvature estimate along this axis
      double d2max = 0.0;
      for (std::size_t k = 0; k < (std::size_t{1} << pg.vars.size()); ++k) {
        const std::size_t base = corner_index(pg, c, k) + slot;
        const std::size_t i = c.lower[a] + ((k >> (pg.vars.size() - 1 - a)) & 1u);
        const std::size_t j = std::clamp<std::size_t>(i, 1, x.size() - 2);  // stencil centre
        const std::ptrdiff_t shift = static_cast<std::ptrdiff_t>(j) - static_cast<std::ptrdiff_t>(i);
        const std::size_t centre = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(base) +
                                                            shift * static_cast<std::ptrdiff_t>(pg.stride[a]));
        const std::size_t lo = centre - pg.stride[a], hi = centre + pg.stride[a];
        const StatusBits s = (*pg.status)[base] & kCompared;
        const std::vector<StatusBits>& st = *pg.status;
        if ((st[lo] & kCompared) != s || (st[centre] & kCompared) != s || (st[hi] & kCompared) != s) continue;
        const double h0 = x[j] - x[j - 1], h1 = x[j + 1] - x[j];
        const double d2 = 2.0 * ((f[hi] - f[centre]) / h1 - (f[centre] - f[lo]) / h0) / (h0 + h1);
        d2max = std::max(d2max, std::abs(d2));
      }
      sum += 0.125 * c.h[a] * c.h[a] * d2max;
    }
    return sum;
  }

  // Largest |value| of an output over the table (both wheels, the slot): its scale.
  double scale(int output, std::size_t slot) const {
    double m = 0.0;
    const int part = part_of(output);
    for (std::size_t w = 0; w < 2; ++w) {
      const std::vector<double>& f = *grid_[w][static_cast<std::size_t>(part)].values[output];
      for (std::size_t i = slot; i < f.size(); i += kSlots) m = std::max(m, std::abs(f[i]));
    }
    return m;
  }

 private:
  struct PartGrid {
    std::vector<int> vars;                         // tabulated axes of the part (file order)
    std::vector<const std::vector<double>*> nodes;  // their nodes
    std::vector<std::size_t> stride;               // C-order strides (slot fastest)
    const std::vector<StatusBits>* status = nullptr;
    const std::vector<double>* values[lk::kNumOutputs] = {};  // the part's outputs only
  };
  // Flat index (slot 0) of corner k of the cell: bit (D-1-a) of k = upper node along axis a.
  static std::size_t corner_index(const PartGrid& pg, const Cell& c, std::size_t k) {
    std::size_t index = 0;
    for (std::size_t a = 0; a < pg.vars.size(); ++a)
      index += (c.lower[a] + ((k >> (pg.vars.size() - 1 - a)) & 1u)) * pg.stride[a];
    return index;
  }
  PartGrid grid_[2][lk::kNumParts];
  static constexpr const char* kScaleNames[3] = {"creep_scale_xi", "creep_scale_eta", "creep_scale_phi"};
  bool coupled_ = false;     // the creep part holds the per-creepage normal contact
  bool normalised_ = false;  // format 2.1 normalised creep coordinates
  bool swept_[3] = {};
  double lo_[3] = {}, hi_[3] = {};
  double knee_[3] = {1.0, 1.0, 1.0};  // creep_map <axis>_knee
  double friction_ = 0.0;             // creep_map friction
  double law_spin_ = 0.0;             // creep_map law_spin
  std::vector<double> n_creep_[2];    // creep part's N recovered from the vertical share
  const std::vector<double>* scale_values_[2][3] = {};
};

// How a (state, wheel, slot, part) compares:
//   smooth: every corner node of the interpolation cell and the direct evaluation carry the same
//     status word (but full_slip, see kCompared), a converged loaded contact, and nothing below it jumps (see classify_point);
//   jump: anything else with a contact somewhere: the status differs between corners (flange
//     onset, lift-off, slot occupancy), the slot holds two contacts (two_point: the kept one, the
//     lower-separation point or the larger patch, can switch inside the cell), or the part it
//     sits on jumps;
//   empty: no contact at any corner nor at the state, or lift-off throughout (all zeros).
enum class CellKind { kSmooth, kJump, kEmpty };

inline CellKind classify(const std::vector<StatusBits>& corners, StatusBits direct) {
  const bool same = std::all_of(corners.begin(), corners.end(),
                                [&](StatusBits s) { return (s & kCompared) == (direct & kCompared); });
  if (same && (direct == 0u || (direct & status::kLiftOff))) return CellKind::kEmpty;
  if (same && (direct & status::kConverged) && !(direct & (status::kFailed | status::kTwoPoint)))
    return CellKind::kSmooth;
  return CellKind::kJump;
}

// The kinds of every part and slot of one wheel at one state. Parts sit on each other: normal on
// the geometry, creep and wear on the normal patch; a part whose base jumps jumps too. One model
// switch carries no status bit: the normal model returns a Hertz (elliptic) patch, semi-axes a, b
// > 0, where the strip model applies, else a strip patch with a = b = 0 (normal_model.hpp); creep
// and wear on it switch with it (fastsim_contact dispatches Hertz patches to elliptic FASTSIM). A
// cell whose corners and state do not all agree on a > 0 is therefore a jump for normal, creep
// and wear.
struct PointKinds {
  CellKind kind[lk::kNumParts][kSlots];
  TableView::Cell cell[lk::kNumParts][kSlots];  // per slot: normalised creep cells depend on it
};

inline PointKinds classify_point(const TableView& view, std::size_t wheel, const Point& p, const WheelValues& direct) {
  PointKinds k;
  for (std::size_t s = 0; s < kSlots; ++s) {
    const Point creep = view.creep_point(wheel, s, p);
    for (int part = 0; part < lk::kNumParts; ++part)
      k.cell[part][s] = view.cell(wheel, part, part >= lk::kCreep ? creep : p);
  }
  for (std::size_t s = 0; s < kSlots; ++s) {
    for (int part = 0; part < lk::kNumParts; ++part)
      k.kind[part][s] = classify(view.corner_status(wheel, part, k.cell[part][s], s), direct.status[part][s]);
    const std::vector<double> a = view.corner_values(wheel, lk::kSemiAxisA, k.cell[lk::kNormal][s], s);
    const bool elliptic = direct.value[lk::kSemiAxisA][s] > 0.0;
    const bool model_switch = std::any_of(a.begin(), a.end(), [&](double v) { return (v > 0.0) != elliptic; });
    auto inherit = [&](int part, bool base_jumps) {
      if (base_jumps && k.kind[part][s] == CellKind::kSmooth) k.kind[part][s] = CellKind::kJump;
    };
    inherit(lk::kNormal, k.kind[lk::kGeometry][s] == CellKind::kJump || model_switch);
    inherit(lk::kCreep, k.kind[lk::kNormal][s] == CellKind::kJump);
    inherit(lk::kWear, k.kind[lk::kNormal][s] == CellKind::kJump);
  }
  return k;
}

// One (state, wheel, output, slot) of a lookup-against-direct comparison (for_each_slot_error).
struct SlotError {
  std::size_t state, wheel, slot;
  int output;
  CellKind kind;
  const TableView::Cell* cell;  // the slot's cell of the output's part
  double lookup, direct, error;  // error = |lookup - direct|
  double normal_force;           // the direct evaluation's N of the slot
  StatusBits lookup_status;      // the lookup's status of the slot (low_confidence: counted apart)
};

// Queries the lookup at every state for both wheels and calls f(const SlotError&) for every
// output and loaded slot (empty cells skipped): the loop of the random off-grid accuracy tests.
// A query that leaves the grid or is refused fails the test.
template <class F>
void for_each_slot_error(const TableView& view, const lk::Table& lookup, const std::vector<Point>& points,
                         const std::vector<Direct>& direct, F&& f) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (std::size_t w = 0; w < 2; ++w) {
      const lk::Result r = lookup.query(static_cast<lk::Wheel>(w), to_state(lookup, points[i]));
      ASSERT_EQ(r.status & (lk::status::kOutOfRange | lk::status::kInvalidInput), 0u);
      const PointKinds kinds = classify_point(view, w, points[i], direct[i][w]);
      for (int o = 0; o < lk::kNumOutputs; ++o) {
        const int part = view.part_of(o);
        for (std::size_t s = 0; s < kSlots; ++s) {
          const CellKind kind = kinds.kind[part][s];
          if (kind == CellKind::kEmpty) continue;
          const double value = r.contact[s].value[o], reference = direct[i][w].value[o][s];
          f(SlotError{i, w, s, o, kind, &kinds.cell[part][s], value, reference, std::abs(value - reference),
                      direct[i][w].value[lk::kNormalForce][s], r.contact[s].status});
        }
      }
    }
  }
}

// Whether the lookup flags the slot low_confidence (docs/lookup.md, "Low confidence"): the issue's
// accuracy targets count such slots apart, and they may be at most 2 % of the random states.
inline bool flagged(const SlotError& e) { return (e.lookup_status & lk::status::kLowConfidence) != 0; }

// Queries (state, wheel) of `points` whose answer has low_confidence in any slot: the flagged
// states of the accuracy targets (python/tests/test_table.py counts them the same way).
inline std::size_t flagged_queries(const lk::Table& lookup, const std::vector<Point>& points) {
  std::size_t n = 0;
  for (const Point& p : points)
    for (std::size_t w = 0; w < 2; ++w) {
      const lk::Result r = lookup.query(static_cast<lk::Wheel>(w), to_state(lookup, p));
      bool any = false;
      for (int s = 0; s < r.n_slots; ++s) any = any || (r.contact[s].status & lk::status::kLowConfidence) != 0;
      n += any;
    }
  return n;
}

// RMS, median, 90th and 99th percentiles and maximum of a set of errors (nearest rank; all 0 for
// none): the figures the accuracy targets are stated in.
struct ErrorFigures {
  std::size_t n = 0;
  double rms = 0.0, median = 0.0, p90 = 0.0, p99 = 0.0, max = 0.0;
  explicit ErrorFigures(std::vector<double> v) : n(v.size()) {
    if (v.empty()) return;
    std::sort(v.begin(), v.end());
    double sq = 0.0;
    for (double e : v) sq += e * e;
    rms = std::sqrt(sq / static_cast<double>(n));
    auto at = [&](double q) { return v[static_cast<std::size_t>(q * static_cast<double>(n - 1) + 0.5)]; };
    median = at(0.5), p90 = at(0.9), p99 = at(0.99), max = v.back();
  }
  // One line: "rms .. median .. p90 .. p99 .. max .. (n values)", in % when `percent`.
  void print(const char* label, bool percent = true) const {
    const double k = percent ? 100.0 : 1.0;
    std::printf("%s: rms %.3f median %.3f p90 %.3f p99 %.3f max %.3f%s (%zu values)\n", label, k * rms, k * median,
                k * p90, k * p99, k * max, percent ? " %" : "", n);
  }
};

// Error statistics of one output and slot over the states of an accuracy test.
struct SlotStats {
  std::size_t smooth = 0, jump = 0, over = 0;  // over: smooth cells beyond the tolerance
  Point worst{};                                // the smooth state of the largest |F error| / (mu N)
  double worst_lookup = 0.0, worst_direct = 0.0;
  double sum_sq = 0.0, sum_mu_sq = 0.0, max_abs = 0.0, max_ratio = 0.0, max_mu_n = 0.0, jump_max = 0.0;

  // Counts e at state p (mu: the scene's friction). Returns true for a smooth cell (whose
  // tolerance check is the caller's), false for a jump cell.
  bool add(const SlotError& e, const Point& p, double mu) {
    if (e.kind == CellKind::kJump) {
      ++jump;
      jump_max = std::max(jump_max, e.error);
      return false;
    }
    ++smooth;
    sum_sq += e.error * e.error;
    max_abs = std::max(max_abs, e.error);
    if (e.output == lk::kFx || e.output == lk::kFy) {
      const double rel = e.error / (mu * e.normal_force);
      if (rel > max_mu_n) worst = p, worst_lookup = e.lookup, worst_direct = e.direct;
      max_mu_n = std::max(max_mu_n, rel);
      sum_mu_sq += rel * rel;
    }
    return true;
  }

  // The smooth-cell check of the random off-grid tests: |lookup - direct| <= kSafety e + kFloor
  // scale, e the second-order error estimate of the cell read from the table
  // (TableView::error_estimate; stripes_scene_accuracy_test.cpp's header says why 5), the scale
  // the output's largest |value|. Records the ratio and counts an excess; returns the tolerance.
  static constexpr double kSafety = 5.0;
  static constexpr double kFloor = 1e-4;
  double check_tolerance(const TableView& view, const SlotError& e) {
    const double tolerance =
        kSafety * view.error_estimate(e.wheel, e.output, *e.cell, e.slot) + kFloor * view.scale(e.output, e.slot);
    max_ratio = std::max(max_ratio, e.error / tolerance);
    if (e.error > tolerance) ++over;
    return tolerance;
  }
};

}  // namespace railtab::accuracy
