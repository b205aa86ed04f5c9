// SPDX-License-Identifier: Apache-2.0
// Convergence of the multilinear lookup under grid refinement (docs/lookup.md, "Accuracy"): the
// STRIPES scene's models on reduced grids over smooth sub-domains, three spacings h, h/2, h/4,
// the same random states on each (every one a smooth cell, checked). Second-order interpolation:
// the max error falls ~4x per halving, observed order p = log2(e_h / e_h/2) ~ 2.
//   - lateral shift: left-wheel tread, y in [1, 3.5] mm (one contact, no two-point, no flange),
//     h = 0.5, 0.25, 0.125 mm; load and creepages at their (fixed or node) values, so only y is
//     interpolated. Asserted p > 1.6 per halving on the geometry outputs. The normal and creep
//     outputs level off at the core's own fine-scale noise in y (strip layout of STRIPES and
//     FASTSIM shifting with the patch: ~0.5 N normal force, ~150 N creep force), reported only.
//   - creepages: xi, eta in [-1.5, 1.5] 1e-3 (below full slip), h = 0.75, 0.375, 0.19 1e-3, at one
//     y and load. Asserted on fx, fy, mz: p > 1.6 over h -> h/4 and > 1.3 for each halving (the
//     first halving of mz is pre-asymptotic, ~1.45). slip_fraction and wear_rate are sums over
//     FASTSIM's slipping elements, steps at the element scale, not smooth: reported only.
// Reduced grids keep the run small (~0.3 s); the full STRIPES grid is the other test's business.
#include <cmath>
#include <cstdio>
#include <optional>

#include "accuracy_util.hpp"

namespace railtab::accuracy {
namespace {

// The STRIPES scene (tables/default_stripes.toml) with reduced grids.
Scene reduced_scene(const std::vector<double>& y, const std::vector<double>& load, const std::vector<double>& xi,
                    const std::vector<double>& eta, const std::vector<double>& phi) {
  Scene s = load_scene(std::filesystem::path(RAILTAB_SOURCE_DIR) / "tables" / "default_stripes.toml");
  s.grids.y = y;
  s.grids.load = load;
  s.grids.xi = xi;
  s.grids.eta = eta;
  s.grids.phi = phi;
  s.creep_normalised = false;  // a study of physical creepage spacings (normalised: the STRIPES scene's test)
  return s;
}

std::vector<double> range(double start, double stop, std::size_t intervals) {
  std::vector<double> v;
  for (std::size_t i = 0; i <= intervals; ++i)
    v.push_back(start + (stop - start) * static_cast<double>(i) / static_cast<double>(intervals));
  return v;
}

struct Level {
  Table table;
  std::optional<lk::Table> lookup;
};

Level make_level(const Scene& scene, const std::string& name) {
  Level l;
  SweepResult r = run_sweep(scene, make_contact_kernel(scene), SweepOptions{});
  if (r.summary.failures) throw std::runtime_error(name + ": " + r.summary.first_failure);
  l.table = std::move(r.table);
  l.lookup.emplace(load_through_file(l.table, name));
  return l;
}

// Max error of every output (slot 0, left wheel) at `points` on each level; asserts every
// point is a smooth cell on every level.
std::vector<std::array<double, lk::kNumOutputs>> max_errors(const Scene& scene, const std::vector<Level>& levels,
                                                            const std::vector<Point>& points) {
  const std::vector<Direct> direct = evaluate_direct(scene, points);
  std::vector<std::array<double, lk::kNumOutputs>> out(levels.size());
  for (std::size_t l = 0; l < levels.size(); ++l) {
    out[l].fill(0.0);
    const TableView view(levels[l].table);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const PointKinds kinds = classify_point(view, 0, points[i], direct[i][0]);
      for (int part = 0; part < lk::kNumParts; ++part)
        EXPECT_EQ(kinds.kind[part][0], CellKind::kSmooth) << lk::part_name(static_cast<lk::Part>(part)) << " level " << l
                                                          << " y " << points[i].v[kY];
      const lk::Result r = levels[l].lookup->query(lk::Wheel::kLeft, to_state(*levels[l].lookup, points[i]));
      EXPECT_EQ(r.status & lk::status::kOutOfRange, 0u);
      for (int o = 0; o < lk::kNumOutputs; ++o)
        out[l][o] = std::max(out[l][o], std::abs(r.contact[0].value[o] - direct[i][0].value[o][0]));
    }
  }
  return out;
}

void report(const char* title, const std::vector<std::array<double, lk::kNumOutputs>>& err) {
  std::printf("convergence, %s: max error (left wheel, tread slot) and observed order\n", title);
  for (int o = 0; o < lk::kNumOutputs; ++o) {
    if (err[0][o] == 0.0) continue;  // outputs that are 0 throughout (separation, a, b of strips)
    std::printf("  %-15s %10.3e %10.3e %10.3e  order %5.2f %5.2f\n", lk::output_name(static_cast<lk::Output>(o)),
                err[0][o], err[1][o], err[2][o], std::log2(err[0][o] / err[1][o]), std::log2(err[1][o] / err[2][o]));
  }
}

TEST(TableConvergence, TreadLateralShiftHalvings) {
  const double y0 = 1.0e-3, y1 = 3.5e-3;  // left-wheel tread, one contact, no two-point (STRIPES table)
  const std::vector<double> load{78.5e3}, xi{-1e-3, 1.5e-3}, eta{0.0, 1e-3}, phi{0.1};
  std::vector<Level> levels;
  for (std::size_t n : {5u, 10u, 20u})  // h = 0.5, 0.25, 0.125 mm
    levels.push_back(make_level(reduced_scene(range(y0, y1, n), load, xi, eta, phi), "conv_y" + std::to_string(n)));
  Random rng(7);
  std::vector<Point> points;
  for (int i = 0; i < 40; ++i)
    for (double x : xi)
      for (double e : eta) {
        Point p;
        p.v[kY] = rng.uniform(y0, y1);
        p.v[kLoad] = load[0];
        p.v[kXi] = x;  // creepages at nodes: interpolation error along y only
        p.v[kEta] = e;
        p.v[kPhi] = phi[0];
        points.push_back(p);
      }
  const Scene scene = reduced_scene(range(y0, y1, 5), load, xi, eta, phi);
  const auto err = max_errors(scene, levels, points);
  report("lateral shift y, h = 0.5, 0.25, 0.125 mm", err);
  for (int o : {lk::kContactAngle, lk::kRollingRadius, lk::kWheelY, lk::kRailY, lk::kCurvatureA, lk::kCurvatureB}) {
    EXPECT_GT(std::log2(err[0][o] / err[1][o]), 1.6) << lk::output_name(static_cast<lk::Output>(o));
    EXPECT_GT(std::log2(err[1][o] / err[2][o]), 1.6) << lk::output_name(static_cast<lk::Output>(o));
  }
}

TEST(TableConvergence, CreepagesHalvings) {
  const double y = 2.0e-3, c = 1.5e-3;
  const std::vector<double> load{78.5e3}, phi{0.1};
  std::vector<Level> levels;
  for (std::size_t n : {4u, 8u, 16u})  // h = 0.75, 0.375, 0.19 1e-3
    levels.push_back(make_level(reduced_scene({y}, load, range(-c, c, n), range(-c, c, n), phi), "conv_c" + std::to_string(n)));
  Random rng(11);
  std::vector<Point> points;
  for (int i = 0; i < 1500; ++i) {
    Point p;
    p.v[kY] = y;
    p.v[kLoad] = load[0];
    p.v[kXi] = rng.uniform(-c, c);
    p.v[kEta] = rng.uniform(-c, c);
    p.v[kPhi] = phi[0];
    points.push_back(p);
  }
  const Scene scene = reduced_scene({y}, load, range(-c, c, 4), range(-c, c, 4), phi);
  const auto err = max_errors(scene, levels, points);
  report("creepages xi, eta, h = 0.75, 0.375, 0.19 1e-3", err);
  for (int o : {lk::kFx, lk::kFy, lk::kMz}) {
    EXPECT_GT(0.5 * std::log2(err[0][o] / err[2][o]), 1.6) << lk::output_name(static_cast<lk::Output>(o));
    EXPECT_GT(std::log2(err[0][o] / err[1][o]), 1.3) << lk::output_name(static_cast<lk::Output>(o));
    EXPECT_GT(std::log2(err[1][o] / err[2][o]), 1.3) << lk::output_name(static_cast<lk::Output>(o));
  }
}
}  // namespace
}  // namespace railtab::accuracy
