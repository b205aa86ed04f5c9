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

CoupledLoadOptions coupled_load_options(const Scene& scene) {
  CoupledLoadOptions options;
  options.couple = scene.tangential.load_coupling;
  return options;
}

WearOptions wear_options(const Scene& scene) {
  WearOptions options;
  options.map.hardness = scene.wear.hardness;
  // The scene gives the divisor of k_dry directly (1 dry, 5.5 natural contamination, 11 lubricated).
  options.map.factor_natural = scene.wear.lubrication_factor;
  options.lubrication = Lubrication::natural;
  validate(options.map);
  return options;
}

}  // namespace railtab
