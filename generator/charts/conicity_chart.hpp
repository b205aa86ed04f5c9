// SPDX-License-Identifier: Apache-2.0
// Outputs of railtab conicity: JSON (amplitude_m, equivalent_conicity, ...), CSVs of the conicity
// and of the lateral functions, and the PNG chart (gnuplot) with an optional second pair beside.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "charts/conicity.hpp"

namespace railtab {

// One pair as JSON: "pair", "source", "roll", "e0_m", "r0_m", "centre_m", the arrays "amplitude_m",
// "equivalent_conicity" (reference principle), "equivalent_conicity_regression", "wavelength_m",
// "y_min_m", "y_max_m", "roll_angle_parameter", "contact_angle_parameter" (NaN as null), and
// "functions" {"y_m", "roll_rad", "rolling_radius_difference_m", "contact_angle_difference"}.
nlohmann::json conicity_json(const ConicityCurve& curve);

struct ConicityFiles {
  std::vector<std::filesystem::path> written;  // every file, in the order written
};

// Writes DIR/conicity.csv, conicity_functions.csv, conicity.json, conicity.gp and conicity.png for
// `curve`; with `compare`, also conicity_compare.csv and conicity_compare_functions.csv, its curves
// drawn beside in the PNG and its JSON under "compare". Every file through table/output_file.hpp.
ConicityFiles write_conicity_outputs(const std::filesystem::path& dir, const ConicityCurve& curve,
                                     const std::optional<ConicityCurve>& compare);

}  // namespace railtab
