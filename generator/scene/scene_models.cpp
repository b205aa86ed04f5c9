// SPDX-License-Identifier: Apache-2.0
// Model settings of a scene: the single mapping from scene keys to the tangential and wear layers.
#include "scene/scene.hpp"

namespace railtab {

FastsimOptions fastsim_options(const Scene& scene) {
  FastsimOptions options;
  options.elements_per_strip = scene.tangential.elements_per_strip;
  options.spin = scene.tangential.spin_per_strip ? SpinVariation::per_strip : SpinVariation::patch_constant;
  return options;
}

CreepConditions creep_conditions(const Scene& scene) {
  CreepConditions conditions;
  conditions.friction = scene.tangential.friction;
  conditions.speed = scene.tangential.speed;
  return conditions;
}

// Relative tolerance on the vertical balance of the scene's coupled load control [-] (below).
constexpr double kSceneCouplingTolerance = 1e-3;

CoupledLoadOptions coupled_load_options(const Scene& scene) {
  CoupledLoadOptions options;
  options.couple = scene.tangential.load_coupling;
  // Balance to 1e-3 of the load: N (cos g + (fy/N) sin g) = Q with fy/N nearly independent of N, so
  // the normal force is within about 0.1 % of the balanced one (a fifth of the load coupling's 0.5
  // % target on the tread, far below FASTSIM's error against CONTACT). The creepage-free start is
  // accepted under the same rule, i.e. no coupled re-solve where the creep forces' vertical
  // component |sum fy sin g| is below 1e-3 of the load (tread at small lateral creepage and spin),
  // and most other points need one normal re-solve fewer than at the library default 1e-4
  // (docs/scenes.md).
  options.tolerance = kSceneCouplingTolerance;
  return options;
}

WearOptions wear_options(const Scene& scene) {
  WearOptions options;
  options.map.hardness = scene.wear.hardness;
  // The scene gives the divisor of k_dry directly (1 dry, 5.5 natural contamination, 11
  // lubricated).
  options.map.factor_natural = scene.wear.lubrication_factor;
  options.lubrication = Lubrication::natural;
  validate(options.map);
  return options;
}

}  // namespace railtab
