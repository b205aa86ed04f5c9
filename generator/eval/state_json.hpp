// SPDX-License-Identifier: Apache-2.0
// The JSON form of one evaluated state (state_eval.hpp): the document `railtab eval --json` prints
// and `railtab.evaluate` returns as a dict, stable keys in SI units (docs/scenes.md).
#pragma once

#include <nlohmann/json.hpp>

#include "eval/state_eval.hpp"

namespace railtab {

// Per wheel: "contacts" (loaded patches: normal contact and, with creepage, creep forces and wear)
// and "rigid_points" (the geometry's contact points).
nlohmann::json state_json(const StateEvaluation& evaluation);

}  // namespace railtab
