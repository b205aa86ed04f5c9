// SPDX-License-Identifier: Apache-2.0
// What format 1.0 puts in each part: group name, outputs and the state variables its datasets
// may be tabulated over (docs/table-format.md, "Wheels and parts").
#pragma once

#include "grid.hpp"
#include "railtab/lookup.hpp"

namespace railtab::lookup::detail {

struct PartSpec {
  const char* name;       // group name under /left and /right
  int first_output;       // Output index of its first dataset
  int n_out;              // number of float64 datasets (status excluded)
  bool uses[kNumVars];    // state variables its datasets are tabulated over (if swept)
};

extern const PartSpec kPartSpecs[kNumParts];

}  // namespace railtab::lookup::detail
