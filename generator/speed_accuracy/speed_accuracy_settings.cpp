// SPDX-License-Identifier: Apache-2.0
// The model and table settings `railtab chart` measures (speed_accuracy.hpp) and their labels.
#include <fmt/format.h>

#include "speed_accuracy/speed_accuracy.hpp"

namespace railtab {

std::string SaModelSetting::label() const {
  if (model == NormalModel::halfspace) return "halfspace exact";
  if (model == NormalModel::hertz) return fmt::format("hertz e{}", elements);
  return fmt::format("{} {}x{}", to_string(model), strips, elements);
}

std::string SaTableSetting::label() const {
  return fmt::format("table y{:g}mm{}{}", y_step * 1e3, fine_creep ? " fine-creep" : "", exact ? " exact" : "");
}

std::vector<SaModelSetting> default_model_settings() {
  std::vector<SaModelSetting> v;
  for (int e : {10, 20, 40}) v.push_back({NormalModel::hertz, 0, e});
  for (NormalModel m : {NormalModel::linder, NormalModel::kik_piotrowski}) {
    v.push_back({m, 10, 20});
    v.push_back({m, 25, 20});
    v.push_back({m, 50, 10});
    v.push_back({m, 50, 20});
    v.push_back({m, 50, 40});
    v.push_back({m, 100, 20});
  }
  for (NormalModel m : {NormalModel::stripes_a, NormalModel::stripes_ab})
    for (int s : {10, 25, 50, 100})
      for (int e : {10, 20, 40}) v.push_back({m, s, e});
  v.push_back({NormalModel::halfspace, 0, 0});  // where the exact model itself stands
  return v;
}

std::vector<SaTableSetting> default_table_settings(bool exact_scene) {
  // A scene of the exact model makes every table an exact one (about 15-30 ms CPU per point): the
  // fine creepage grids (891 creepages per y node) and the finer y steps would take hours, so such
  // a scene gets its own y 0.5 mm table only (the product's kind, as for the fast scenes' last row).
  if (exact_scene) return {{0.5e-3, false}};
  return {{2e-3, false},  {1e-3, false},  {0.5e-3, false},       {0.25e-3, false},
          {0.5e-3, true}, {0.25e-3, true}, {0.5e-3, false, true}};  // the last: a table of the exact model
}

std::vector<SaModelSetting> quick_model_settings() {
  return {{NormalModel::hertz, 0, 20}, {NormalModel::linder, 50, 20}, {NormalModel::kik_piotrowski, 50, 20},
          {NormalModel::stripes_a, 25, 20}, {NormalModel::stripes_ab, 25, 20}, {NormalModel::stripes_ab, 50, 20},
          {NormalModel::halfspace, 0, 0}};
}

std::vector<SaTableSetting> quick_table_settings() { return {{1e-3, false}, {0.5e-3, false}, {1e-3, false, true}}; }

}  // namespace railtab
