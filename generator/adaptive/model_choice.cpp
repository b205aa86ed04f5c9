// SPDX-License-Identifier: Apache-2.0
// Model choice per y node for [accuracy] scenes: the cheapest model within the targets.
#include "adaptive/model_choice.hpp"


#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>

#include "core/check.hpp"
#include "core/status.hpp"
#include "engine/parallel_for.hpp"
#include "engine/sweep.hpp"

namespace railtab {
namespace {

constexpr double kRejected = std::numeric_limits<double>::infinity();

// A candidate that needed a fallback or did not converge is not the model it claims to be.
constexpr std::uint32_t kUntrusted = status::kFallbackModel | status::kNotConverged | status::kFailed;

// Creepage values of one axis at the probe states: `fraction` of the way from 0 (clamped into the
// range) towards one end of the range.
double towards(const std::vector<double>& grid, double fraction, bool upper) {
  const double zero = std::clamp(0.0, grid.front(), grid.back());
  return zero + fraction * ((upper ? grid.back() : grid.front()) - zero);
}

}  // namespace

ModelProbeStates model_probe_states(const Scene& scene) {
  const SceneGrids& g = scene.grids;
  ModelProbeStates p;
  p.loads = {g.load.front(), g.load.back()};
  p.loads.erase(std::unique(p.loads.begin(), p.loads.end()), p.loads.end());
  const std::vector<double>* axes[3] = {&g.xi, &g.eta, &g.phi};
  std::array<double, 3> zero{};
  for (std::size_t k = 0; k < 3; ++k) zero[k] = towards(*axes[k], 0.0, true);
  // Each creepage alone: the start of the creep curve and full range (saturation).
  for (std::size_t k = 0; k < 3; ++k) {
    for (double f : {0.25, 1.0}) {
      for (bool upper : {false, true}) {
        std::array<double, 3> c = zero;
        c[k] = towards(*axes[k], f, upper);
        p.creepages.push_back(c);
      }
    }
  }
  // Combined: lateral creepage with spin of either sign (they add or cancel in fy).
  for (double f : {0.25, 0.5}) {
    for (bool upper : {false, true}) {
      p.creepages.push_back({towards(g.xi, f, true), towards(g.eta, f, true), towards(g.phi, f, upper)});
    }
  }
  std::sort(p.creepages.begin(), p.creepages.end());
  p.creepages.erase(std::unique(p.creepages.begin(), p.creepages.end()), p.creepages.end());
  return p;
}

double model_error(const ProbeResults& candidate, const ProbeResults& reference, const AccuracyTargets& t,
                   double friction) {
  RAILTAB_CHECK(candidate.size() == reference.size(), "model choice: {} against {} probe loads", candidate.size(),
                reference.size());
  double worst = 0.0;
  auto add = [&](double difference, double tolerance) {
    if (tolerance > 0.0) worst = std::max(worst, std::abs(difference) / tolerance);
  };
  for (std::size_t il = 0; il < reference.size(); ++il) {
    for (std::size_t ic = 0; ic < reference[il].size(); ++ic) {
      for (std::size_t w = 0; w < 2; ++w) {
        for (std::size_t s = 0; s < kSlots; ++s) {
          const ContactProbe::Slot& c = candidate[il][ic][w].slot[s];
          const ContactProbe::Slot& r = reference[il][ic][w].slot[s];
          if (c.status != r.status || (c.patch_status & kUntrusted)) return kRejected;
          if (!r.loaded) continue;
          const double n = r.normal_force;
          add(c.fx - r.fx, t.creep_force * friction * n);
          add(c.fy - r.fy, t.creep_force * friction * n);
          add(c.normal_force - n, t.normal_force * n);
          add(c.patch_angle - r.patch_angle, t.contact_angle);
          add(c.patch_radius - r.patch_radius, t.rolling_radius);
          if (!std::isfinite(c.fx + c.fy + c.normal_force + c.patch_angle + c.patch_radius)) return kRejected;
        }
      }
    }
  }
  return worst;
}

nlohmann::json ModelChoice::to_json() const {
  nlohmann::json names = nlohmann::json::array(), nodes = nlohmann::json::object();
  for (NormalModel m : models) {
    names.push_back(to_string(m));
    nodes[to_string(m)] = 0;
  }
  for (std::size_t i : by_y) nodes[to_string(models[i])] = nodes[to_string(models[i])].get<std::size_t>() + 1;
  return {{"models", names},
          {"reference", models.empty() ? "" : to_string(models.back())},
          {"y_nodes_per_model", nodes},
          {"probes_per_node", probes_per_node},
          {"model_tolerance", model_tolerance},
          {"rule", "per y node, the first (cheapest) model whose fx, fy, N and patch position stay within the "
                   "targets of the reference at every probe state, with the same slot regime; the reference "
                   "otherwise"},
          {"seconds", seconds}};
}

ModelChoice choose_models(const Scene& scene, int threads) {
  RAILTAB_CHECK(!scene.accuracy.models.empty(), "model choice: the scene {} has no [accuracy] models", scene.name);
  const auto start = std::chrono::steady_clock::now();
  ModelChoice choice;
  choice.models = scene.accuracy.models;
  choice.model_tolerance = scene.accuracy.model_tolerance;
  const ModelProbeStates states = model_probe_states(scene);
  choice.probes_per_node = states.loads.size() * states.creepages.size();
  std::vector<std::unique_ptr<ContactProbe>> probes;
  for (NormalModel m : choice.models) {
    Scene variant = scene;
    variant.normal.model = m;
    probes.push_back(std::make_unique<ContactProbe>(variant));
  }
  const std::vector<double>& ys = scene.grids.y;
  choice.by_y.assign(ys.size(), choice.models.size() - 1);
  choice.error.assign(ys.size(), std::vector<double>(choice.models.size(), 0.0));
  const double mu = probes.back()->friction();
  // The deviation a user accepts from the reference model may exceed the interpolation targets
  // (the models differ from each other by more than the grid's 2 %): model_tolerance scales them.
  AccuracyTargets targets = scene.accuracy;
  for (double* t : {&targets.creep_force, &targets.contact_angle, &targets.rolling_radius, &targets.normal_force}) {
    *t *= scene.accuracy.model_tolerance;
  }
  // Each y node writes only its own entries: the same choice for any thread count.
  parallel_for_index(threads, ys.size(), [&](std::size_t iy) {
    const ProbeResults reference = probes.back()->evaluate(ys[iy], states.loads, states.creepages);
    for (std::size_t m = 0; m + 1 < choice.models.size(); ++m) {
      const ProbeResults candidate = probes[m]->evaluate(ys[iy], states.loads, states.creepages);
      choice.error[iy][m] = model_error(candidate, reference, targets, mu);
    }
    for (std::size_t m = 0; m < choice.models.size(); ++m) {
      if (choice.error[iy][m] <= 1.0) {
        choice.by_y[iy] = m;
        break;
      }
    }
  });
  choice.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return choice;
}

}  // namespace railtab
