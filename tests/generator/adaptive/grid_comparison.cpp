// SPDX-License-Identifier: Apache-2.0
// Adaptive grids against uniform grids of the same worst midpoint error, both against direct
// evaluation at random off-grid states (grid_comparison.hpp, docs/adaptive-grids.md).
#include "generator/adaptive/grid_comparison.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <random>

#include "core/check.hpp"
#include "kernel/contact_kernel.hpp"
#include "adaptive/model_choice.hpp"
#include "engine/parallel_for.hpp"

namespace railtab {

namespace {

std::size_t tabulated_points(const Scene& scene, const SceneGrids& g) {
  std::size_t n = g.y.size() * g.load.size() * g.xi.size() * g.eta.size() * g.phi.size();
  if (!scene.equilibrium_roll) n *= g.roll.size();
  return n;
}

std::size_t table_bytes(const Scene& scene, const SceneGrids& g) {
  const std::size_t column = scene.equilibrium_roll ? 1 : g.roll.size();
  const std::size_t creep = g.load.size() * g.xi.size() * g.eta.size() * g.phi.size();
  // Outputs per part of the contact kernel (contact_kernel.cpp): geometry 7, normal 6, creep 4, wear 1;
  // each part also has a uint32 status; two wheels and two slots.
  const std::size_t per_column = 2 * kSlots * ((7 * 8 + 4) + g.load.size() * (6 * 8 + 4) + creep * (4 * 8 + 4 + 8 + 4));
  return g.y.size() * column * per_column + (scene.equilibrium_roll ? 8 * g.y.size() : 0);
}

// Bracket of v on a grid: lower index and weight of the upper node (clamped).
std::pair<std::size_t, double> bracket(const std::vector<double>& g, double v) {
  if (g.size() == 1) return {0, 0.0};
  auto it = std::upper_bound(g.begin(), g.end(), v);
  std::size_t i = it == g.begin() ? 0 : static_cast<std::size_t>(it - g.begin()) - 1;
  i = std::min(i, g.size() - 2);
  return {i, std::clamp((v - g[i]) / (g[i + 1] - g[i]), 0.0, 1.0)};
}

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(std::round(q * static_cast<double>(v.size() - 1)))];
}

struct StateErrors {
  double creep[2] = {-1, -1}, normal[2] = {-1, -1}, angle[2] = {-1, -1};  // per wheel; -1 = not measured
  bool smooth[2] = {true, true};  // every corner of the cell in the direct state's regime (no jump inside)
};

// Multilinear interpolation of the contact chain on grid g at the state, against direct evaluation.
// node_probe: per y node of g, the probe that gives its values (empty: `probe` everywhere).
StateErrors state_errors(const ContactProbe& probe, const SceneGrids& g, const std::vector<const ContactProbe*>& node_probe,
                         double y, double load, const std::array<double, 3>& c,
                         const std::array<ContactProbe::Wheel, 2>& direct) {
  auto [iy, wy] = bracket(g.y, y);
  auto [il, wl] = bracket(g.load, load);
  auto [ix, wx] = bracket(g.xi, c[0]);
  auto [ie, we] = bracket(g.eta, c[1]);
  auto [ip, wp] = bracket(g.phi, c[2]);
  auto node = [](const std::vector<double>& v, std::size_t i, int k) { return v[std::min(i + static_cast<std::size_t>(k), v.size() - 1)]; };
  std::vector<double> loads{node(g.load, il, 0), node(g.load, il, 1)};
  std::vector<std::array<double, 3>> creeps;
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
      for (int d = 0; d < 2; ++d) creeps.push_back({node(g.xi, ix, a), node(g.eta, ie, b), node(g.phi, ip, d)});
  ContactProbe::Wheel interp[2]{};
  bool tread_everywhere[2] = {true, true};
  bool smooth_cell[2] = {true, true};
  for (int ky = 0; ky < 2; ++ky) {
    const std::size_t jy = std::min(iy + static_cast<std::size_t>(ky), g.y.size() - 1);
    const ContactProbe& values = node_probe.empty() ? probe : *node_probe[jy];
    auto r = values.evaluate(g.y[jy], loads, creeps);
    for (int kl = 0; kl < 2; ++kl) {
      for (std::size_t kc = 0; kc < creeps.size(); ++kc) {
        const int a = static_cast<int>(kc >> 2), b = static_cast<int>((kc >> 1) & 1), d = static_cast<int>(kc & 1);
        const double w = (ky ? wy : 1 - wy) * (kl ? wl : 1 - wl) * (a ? wx : 1 - wx) * (b ? we : 1 - we) * (d ? wp : 1 - wp);
        for (std::size_t wh = 0; wh < 2; ++wh) {
          for (std::size_t s = 0; s < kSlots; ++s) {
            const ContactProbe::Slot& n = r[static_cast<std::size_t>(kl)][kc][wh].slot[s];
            interp[wh].slot[s].fx += w * n.fx;
            interp[wh].slot[s].fy += w * n.fy;
            interp[wh].slot[s].normal_force += w * n.normal_force;
            interp[wh].slot[s].contact_angle += w * n.contact_angle;
            if (s == 0 && !n.geometry && w > 0) tread_everywhere[wh] = false;
            if (n.status != direct[wh].slot[s].status) smooth_cell[wh] = false;
          }
        }
      }
    }
  }
  StateErrors e;
  for (std::size_t wh = 0; wh < 2; ++wh) {
    e.smooth[wh] = smooth_cell[wh];
    double n_total = 0.0, df2 = 0.0, dn2 = 0.0;
    for (std::size_t s = 0; s < kSlots; ++s) {
      const ContactProbe::Slot& d = direct[wh].slot[s];
      const ContactProbe::Slot& i = interp[wh].slot[s];
      n_total += d.normal_force;
      df2 += std::pow(i.fx - d.fx, 2) + std::pow(i.fy - d.fy, 2);
      dn2 += std::pow(i.normal_force - d.normal_force, 2);
    }
    if (n_total > 0.0) {
      e.creep[wh] = std::sqrt(df2) / (probe.friction() * n_total);
      e.normal[wh] = std::sqrt(dn2) / n_total;
    }
    if (tread_everywhere[wh] && direct[wh].slot[0].geometry) {
      e.angle[wh] = std::abs(interp[wh].slot[0].contact_angle - direct[wh].slot[0].contact_angle);
    }
  }
  return e;
}

}  // namespace

GridComparison compare_adaptive_with_uniform(const Scene& base, std::size_t states, unsigned seed, int threads,
                                             const std::vector<std::pair<std::string, SceneGrids>>& others) {
  RAILTAB_CHECK(base.accuracy.enabled, "compare: the scene {} has no [accuracy] section", base.name);
  GridComparison cmp;
  Scene adaptive = base;
  AdaptiveGridSummary summary = build_adaptive_grids(adaptive, threads);
  ContactProbe probe(base);

  cmp.adaptive.name = "adaptive";
  cmp.adaptive.grids = adaptive.grids;
  cmp.uniform.name = "uniform";
  cmp.uniform.grids = adaptive.grids;
  for (std::size_t i = 0; i < summary.axes.size(); ++i) {
    const AdaptiveAxisSpec& spec = base.accuracy.axes[i];
    const AxisRefinement& r = summary.axes[i];
    cmp.adaptive.worst_midpoint.push_back(r.worst_error);
    // The fewest uniform intervals whose worst midpoint error is at most the adaptive grid's.
    AxisSampler sampler = contact_axis_sampler(base, probe, spec.axis, threads);
    auto ok = [&](std::size_t n) {
      return check_axis(sampler, spec.axis, uniform_nodes(spec.start, spec.stop, n), r.discontinuities).worst_error <=
             r.worst_error;
    };
    // Like the adaptive grid, the uniform one keeps step <= max_step: n >= n0.
    const std::size_t cap = static_cast<std::size_t>(std::ceil((spec.stop - spec.start) / spec.min_step)) * 2;
    const auto n0 = static_cast<std::size_t>(std::ceil((spec.stop - spec.start) / spec.max_step - 1e-9));
    std::size_t hi = n0;
    while (hi < cap && !ok(hi)) hi *= 2;
    std::size_t lo = hi == n0 ? n0 - 1 : hi / 2;  // fails (or below n0)
    while (hi - lo > 1) {
      std::size_t m = (lo + hi) / 2;
      (ok(m) ? hi : lo) = m;
    }
    std::vector<double> nodes = uniform_nodes(spec.start, spec.stop, hi);
    cmp.uniform.worst_midpoint.push_back(check_axis(sampler, spec.axis, nodes, r.discontinuities).worst_error);
    axis_grid_of(cmp.uniform.grids, spec.axis) = nodes;
  }
  for (const auto& [name, grids] : others) {
    GridComparison::Grid g;
    g.name = name;
    g.grids = grids;
    for (std::size_t i = 0; i < summary.axes.size(); ++i) {
      const std::string& axis = base.accuracy.axes[i].axis;
      AxisSampler sampler = contact_axis_sampler(base, probe, axis, threads);
      g.worst_midpoint.push_back(check_axis(sampler, axis, axis_grid_of(g.grids, axis), summary.axes[i].discontinuities).worst_error);
    }
    cmp.others.push_back(std::move(g));
  }
  // The per-y model choice on the adaptive grids: node values from each node's model.
  std::vector<std::unique_ptr<ContactProbe>> model_probes;
  if (!adaptive.accuracy.model_by_y.empty()) {
    GridComparison::Grid g;
    g.name = "adaptive, models";
    g.grids = adaptive.grids;
    for (std::size_t i : adaptive.accuracy.model_by_y) g.model_by_y.push_back(adaptive.accuracy.models[i]);
    g.worst_midpoint = cmp.adaptive.worst_midpoint;  // same grids; the midpoint check uses the reference
    cmp.others.push_back(std::move(g));
    for (NormalModel m : adaptive.accuracy.models) {
      Scene variant = base;
      variant.normal.model = m;
      model_probes.push_back(std::make_unique<ContactProbe>(variant));
    }
  }
  std::vector<GridComparison::Grid*> all{&cmp.adaptive, &cmp.uniform};
  for (GridComparison::Grid& g : cmp.others) all.push_back(&g);
  std::vector<std::vector<const ContactProbe*>> node_probes(all.size());
  for (std::size_t k = 0; k < all.size(); ++k) {
    GridComparison::Grid* g = all[k];
    g->points = tabulated_points(base, g->grids);
    g->bytes = table_bytes(base, g->grids);
    for (NormalModel m : g->model_by_y) {
      const auto at = std::find(adaptive.accuracy.models.begin(), adaptive.accuracy.models.end(), m);
      node_probes[k].push_back(model_probes[static_cast<std::size_t>(at - adaptive.accuracy.models.begin())].get());
    }
  }

  // Random off-grid states over the box of the axes, fixed seed.
  std::mt19937 rng(seed);
  auto draw = [&](const std::string& axis) {
    AxisRange r = axis_range_of(base, axis);
    return std::uniform_real_distribution<double>(r.lo, r.hi)(rng);
  };
  struct State {
    double y, load;
    std::array<double, 3> c;
  };
  std::vector<State> drawn(states);
  for (State& s : drawn) s = {draw("y"), draw("load"), {draw("xi"), draw("eta"), draw("phi")}};
  std::vector<std::vector<StateErrors>> errors(states, std::vector<StateErrors>(all.size()));
  parallel_for_index(threads, states, [&](std::size_t i) {
    const State& s = drawn[i];
    auto direct = probe.evaluate(s.y, {s.load}, {s.c})[0][0];
    for (std::size_t k = 0; k < all.size(); ++k) {
      errors[i][k] = state_errors(probe, all[k]->grids, node_probes[k], s.y, s.load, s.c, direct);
    }
  });
  cmp.states = states;
  for (std::size_t k = 0; k < all.size(); ++k) {
    GridComparison::Grid& g = *all[k];
    std::vector<double> creep, normal, angle, creep_smooth;
    for (const auto& e : errors) {
      for (int w = 0; w < 2; ++w) {
        if (e[k].creep[w] >= 0 && e[k].smooth[w]) creep_smooth.push_back(e[k].creep[w]);
        if (e[k].creep[w] >= 0) creep.push_back(e[k].creep[w]);
        if (e[k].normal[w] >= 0) normal.push_back(e[k].normal[w]);
        if (e[k].angle[w] >= 0) angle.push_back(e[k].angle[w]);
      }
    }
    g.creep_median = quantile(creep, 0.5);
    g.creep_p90 = quantile(creep, 0.9);
    g.creep_max = quantile(creep, 1.0);
    g.smooth_share = creep.empty() ? 0.0 : static_cast<double>(creep_smooth.size()) / static_cast<double>(creep.size());
    g.smooth_creep_p90 = quantile(creep_smooth, 0.9);
    g.smooth_creep_max = quantile(creep_smooth, 1.0);
    g.normal_median = quantile(normal, 0.5);
    g.normal_p90 = quantile(normal, 0.9);
    g.normal_max = quantile(normal, 1.0);
    g.angle_median = quantile(angle, 0.5);
    g.angle_max = quantile(angle, 1.0);
  }
  return cmp;
}

std::string GridComparison::text() const {
  std::string out = fmt::format("{} random states (both wheels each), errors against direct evaluation\n", states);
  out += fmt::format("{:<17} {:>5} {:>5} {:>5} {:>5} {:>5} {:>10} {:>10} | {:>24} | {:>8} {:>8} {:>8} | {:>6} {:>8} {:>8} | {:>8} {:>8} {:>8} | {:>9} {:>9}\n",
                     "grid", "ny", "nload", "nxi", "neta", "nphi", "points", "MiB", "worst midpoint/target",
                     "F med%", "F p90%", "F max%", "smooth", "sF p90%", "sF max%", "N med%", "N p90%", "N max%", "ang med", "ang max");
  std::vector<const Grid*> all{&adaptive, &uniform};
  for (const Grid& g : others) all.push_back(&g);
  for (const Grid* g : all) {
    std::string mids;
    for (double m : g->worst_midpoint) mids += fmt::format("{}{:.2f}", mids.empty() ? "" : " ", m);
    out += fmt::format("{:<17} {:>5} {:>5} {:>5} {:>5} {:>5} {:>10} {:>10.2f} | {:>24} | {:>8.3f} {:>8.3f} {:>8.2f} | {:>5.0f}% {:>8.3f} {:>8.2f} | {:>8.3f} {:>8.3f} {:>8.2f} | {:>9.2e} {:>9.2e}\n",
                       g->name, g->grids.y.size(), g->grids.load.size(), g->grids.xi.size(), g->grids.eta.size(),
                       g->grids.phi.size(), g->points, static_cast<double>(g->bytes) / 1048576.0, mids,
                       100 * g->creep_median, 100 * g->creep_p90, 100 * g->creep_max, 100 * g->smooth_share,
                       100 * g->smooth_creep_p90, 100 * g->smooth_creep_max, 100 * g->normal_median,
                       100 * g->normal_p90, 100 * g->normal_max, g->angle_median, g->angle_max);
  }
  return out;
}

}  // namespace railtab
