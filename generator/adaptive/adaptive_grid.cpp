// SPDX-License-Identifier: Apache-2.0
// Adaptive grids: the contact-chain sampler of each axis and build_adaptive_grids (adaptive_grid.hpp).
#include "adaptive/adaptive_grid.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

#include "core/check.hpp"
#include "engine/parallel_for.hpp"
#include "kernel/contact_kernel.hpp"
#include "adaptive/model_choice.hpp"

namespace railtab {

AxisRange axis_range_of(const Scene& scene, const std::string& axis) {
  for (const AdaptiveAxisSpec& a : scene.accuracy.axes) {
    if (a.axis == axis) return {a.start, a.stop};
  }
  const SceneGrids& g = scene.grids;
  const std::vector<double>& v = axis == "y" ? g.y : axis == "load" ? g.load : axis == "xi" ? g.xi : axis == "eta" ? g.eta : g.phi;
  return {v.front(), v.back()};
}

// ---------------------------------------------------------------------------------------------
// Samplers of the contact chain

namespace {

// Representative lateral positions: both ends (flange of one wheel each) and the centre (tread).
std::vector<double> y_representatives(const Scene& scene) {
  AxisRange r = axis_range_of(scene, "y");
  std::vector<double> y{r.lo, std::clamp(0.0, r.lo, r.hi), r.hi};
  y.erase(std::unique(y.begin(), y.end()), y.end());
  return y;
}

std::vector<double> load_representatives(const Scene& scene) {
  AxisRange r = axis_range_of(scene, "load");
  return r.hi > r.lo ? std::vector<double>{r.lo, r.hi} : std::vector<double>{r.lo};
}

// Creepage probe level of an axis: `fraction` of the way from 0 to the end of larger magnitude when
// the range holds 0, else from its start; the fixed value of an untabulated axis.
double creep_level(const Scene& scene, const std::string& axis, double fraction) {
  AxisRange r = axis_range_of(scene, axis);
  if (r.hi == r.lo) return r.lo;
  if (r.lo > 0.0 || r.hi < 0.0) return r.lo + fraction * (r.hi - r.lo);
  return fraction * (std::abs(r.lo) > std::abs(r.hi) ? r.lo : r.hi);
}

// The creepage "zero" of an axis: 0 clamped into its range.
double creep_zero(const Scene& scene, const std::string& axis) {
  AxisRange r = axis_range_of(scene, axis);
  return std::clamp(0.0, r.lo, r.hi);
}

// Creepages at which y and load are refined: each creepage alone and combined, at a quarter of range.
std::vector<std::array<double, 3>> creep_probes(const Scene& scene) {
  const double x = creep_level(scene, "xi", 0.25), e = creep_level(scene, "eta", 0.25),
               p = creep_level(scene, "phi", 0.25);
  const double x0 = creep_zero(scene, "xi"), e0 = creep_zero(scene, "eta"), p0 = creep_zero(scene, "phi");
  std::vector<std::array<double, 3>> c{{x, e0, p0}, {x0, e, p0}, {x0, e0, p}, {x, e, p}};
  std::sort(c.begin(), c.end());
  c.erase(std::unique(c.begin(), c.end()), c.end());
  return c;
}

// Parallel batch over positions, deterministic (each position into its own result slot).
template <class F>
std::vector<AxisSample> batch(const std::vector<double>& x, int threads, F f) {
  std::vector<AxisSample> out(x.size());
  parallel_for_index(threads, x.size(), [&](std::size_t i) { out[i] = f(x[i]); });
  return out;
}

struct Targets {
  double creep, angle, radius, normal, mu;
};

// Append the outputs of one wheel-slot result.
void add_geometry(AxisSample& s, const ContactProbe::Slot& slot, const Targets& t) {
  s.values.push_back(slot.contact_angle);
  s.tolerance.push_back(slot.geometry ? t.angle : 0.0);
  s.values.push_back(slot.rolling_radius);
  s.tolerance.push_back(slot.geometry ? t.radius : 0.0);
}
void add_normal(AxisSample& s, const ContactProbe::Slot& slot, const Targets& t) {
  s.values.push_back(slot.normal_force);
  s.tolerance.push_back(t.normal * slot.normal_force);
}
void add_creep(AxisSample& s, const ContactProbe::Slot& slot, const Targets& t) {
  for (double f : {slot.fx, slot.fy}) {
    s.values.push_back(f);
    s.tolerance.push_back(t.creep * t.mu * slot.normal_force);
  }
}

}  // namespace

AxisSampler contact_axis_sampler(const Scene& scene, const ContactProbe& probe, const std::string& axis, int threads) {
  const AccuracyTargets& a = scene.accuracy;
  const Targets t{a.creep_force, a.contact_angle, a.rolling_radius, a.normal_force, probe.friction()};
  const std::vector<double> ys = y_representatives(scene);
  const std::vector<double> loads = load_representatives(scene);
  const std::vector<std::array<double, 3>> probes = creep_probes(scene);
  const ContactProbe* p = &probe;

  if (axis == "y") {
    return [=](const std::vector<double>& x) {
      return batch(x, threads, [&](double y) {
        AxisSample s;
        auto r = p->evaluate(y, loads, probes);
        for (std::size_t w = 0; w < 2; ++w) {
          for (std::size_t sl = 0; sl < kSlots; ++sl) {
            add_geometry(s, r[0][0][w].slot[sl], t);
            s.regime.push_back(r[0][0][w].slot[sl].status & (probe_slot_bits::kGeometry | probe_slot_bits::kGeometryTwo));
          }
        }
        for (std::size_t il = 0; il < loads.size(); ++il) {
          for (std::size_t ic = 0; ic < probes.size(); ++ic) {
            for (std::size_t w = 0; w < 2; ++w) {
              for (std::size_t sl = 0; sl < kSlots; ++sl) {
                const ContactProbe::Slot& slot = r[il][ic][w].slot[sl];
                if (ic == 0) add_normal(s, slot, t);
                add_creep(s, slot, t);
                s.regime.push_back(slot.status);
              }
            }
          }
        }
        return s;
      });
    };
  }
  if (axis == "load") {
    return [=](const std::vector<double>& x) {
      return batch(x, threads, [&](double load) {
        AxisSample s;
        for (double y : ys) {
          auto r = p->evaluate(y, {load}, probes);
          for (std::size_t ic = 0; ic < probes.size(); ++ic) {
            for (std::size_t w = 0; w < 2; ++w) {
              for (std::size_t sl = 0; sl < kSlots; ++sl) {
                const ContactProbe::Slot& slot = r[0][ic][w].slot[sl];
                if (ic == 0) add_normal(s, slot, t);
                add_creep(s, slot, t);
                s.regime.push_back(slot.status);
              }
            }
          }
        }
        return s;
      });
    };
  }
  RAILTAB_CHECK(axis == "xi" || axis == "eta" || axis == "phi", "adaptive grid: axis '{}' cannot be adaptive", axis);
  // Creepage axes: the other two creepages at 0 and at half their range (each combination).
  const std::size_t k = axis == "xi" ? 0 : axis == "eta" ? 1 : 2;
  const char* names[3] = {"xi", "eta", "phi"};
  std::vector<std::array<double, 3>> others{{0, 0, 0}};
  for (std::size_t j = 0; j < 3; ++j) {
    if (j == k) continue;
    const double level = creep_level(scene, names[j], 0.5);
    std::vector<std::array<double, 3>> next;
    for (auto c : others) {
      c[j] = creep_zero(scene, names[j]);
      next.push_back(c);
      if (level != c[j]) {
        c[j] = level;
        next.push_back(c);
      }
    }
    others = next;
  }
  return [=](const std::vector<double>& x) {
    return batch(x, threads, [&](double value) {
      AxisSample s;
      std::vector<std::array<double, 3>> creeps = others;
      for (auto& c : creeps) c[k] = value;
      for (double y : ys) {
        auto r = p->evaluate(y, loads, creeps);
        for (std::size_t il = 0; il < loads.size(); ++il) {
          for (std::size_t ic = 0; ic < creeps.size(); ++ic) {
            for (std::size_t w = 0; w < 2; ++w) {
              for (std::size_t sl = 0; sl < kSlots; ++sl) {
                add_creep(s, r[il][ic][w].slot[sl], t);
                s.regime.push_back(r[il][ic][w].slot[sl].status);
              }
            }
          }
        }
      }
      return s;
    });
  };
}

std::vector<double>& axis_grid_of(SceneGrids& g, const std::string& axis) {
  if (axis == "y") return g.y;
  if (axis == "load") return g.load;
  if (axis == "xi") return g.xi;
  if (axis == "eta") return g.eta;
  RAILTAB_CHECK(axis == "phi", "adaptive grid: unknown axis '{}'", axis);
  return g.phi;
}

static nlohmann::json model_choice_text(const AccuracyTargets& a) {
  if (a.models.empty()) return "none (the scene's model everywhere)";
  nlohmann::json names = nlohmann::json::array();
  for (NormalModel m : a.models) names.push_back(to_string(m));
  return {{"models", names}, {"per", "y node"}, {"model_tolerance", a.model_tolerance}, {"dataset", "normal_model_index"}};
}

nlohmann::json AdaptiveGridSummary::targets_json(const Scene& scene) const {
  const AccuracyTargets& a = scene.accuracy;
  nlohmann::json specs = nlohmann::json::array();
  for (const AdaptiveAxisSpec& s : a.axes) {
    specs.push_back({{"axis", s.axis}, {"start", s.start}, {"stop", s.stop}, {"max_step", s.max_step},
                    {"min_step", s.min_step}});
  }
  return {{"creep_force", a.creep_force},         {"creep_force_units", "relative to mu N"},
          {"contact_angle", a.contact_angle},     {"rolling_radius", a.rolling_radius},
          {"normal_force", a.normal_force},       {"normal_force_units", "relative to N"},
          {"estimate", "midpoint between neighbouring nodes, linear interpolation"},
          {"model_choice", model_choice_text(a)},
          {"axes", specs}};
}

nlohmann::json AdaptiveGridSummary::achieved_json() const {
  nlohmann::json axes_json = nlohmann::json::array();
  double worst = 0.0;
  std::size_t unmet = 0;
  for (const AxisRefinement& r : axes) {
    axes_json.push_back(r.to_json());
    worst = std::max(worst, r.worst_error);
    unmet += r.unmet;
  }
  // worst_midpoint_error covers the smooth intervals only: the target is met when that is <= 1 AND
  // no interval is unmet (an unmet interval is above target at min_step, kept out of the worst).
  nlohmann::json out = {{"worst_midpoint_error", worst},
                        {"units", "fraction of the target, smooth intervals only (unmet intervals excluded)"},
                        {"unmet", unmet},
                        {"met", worst <= 1.0 && unmet == 0},
                        {"axes", axes_json},
                        {"seconds", seconds}};
  if (!model_choice.is_null()) out["model_choice"] = model_choice;
  return out;
}

AdaptiveGridSummary build_adaptive_grids(Scene& scene, int threads) {
  AdaptiveGridSummary summary;
  if (!scene.accuracy.enabled) return summary;
  const auto start = std::chrono::steady_clock::now();
  ContactProbe probe(scene);
  for (const AdaptiveAxisSpec& spec : scene.accuracy.axes) {
    AxisSampler sampler = contact_axis_sampler(scene, probe, spec.axis, threads);
    summary.axes.push_back(refine_axis(sampler, spec));
  }
  for (const AxisRefinement& r : summary.axes) axis_grid_of(scene.grids, r.axis) = r.nodes;
  // The model choice runs on the final grids: one model per y node of the table.
  if (!scene.accuracy.models.empty()) {
    ModelChoice choice = choose_models(scene, threads);
    scene.accuracy.model_by_y = choice.by_y;
    summary.model_choice = choice.to_json();
  }
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}


}  // namespace railtab
