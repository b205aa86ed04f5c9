// SPDX-License-Identifier: Apache-2.0
// Names shared with the table format: output datasets and part groups.
#include "part_spec.hpp"

namespace railtab::lookup {
namespace detail {

//                                          y     roll  load  xi     eta    phi    yaw
const PartSpec kPartSpecs[kNumParts] = {
    {"geometry", kContactAngle, 7, {true, true, false, false, false, false, true}},
    {"normal", kNormalForce, 6, {true, true, true, false, false, false, true}},
    {"creep", kFx, 4, {true, true, true, true, true, true, true}},
    {"wear", kWearRate, 1, {true, true, true, true, true, true, true}},
};

}  // namespace detail

const char* output_name(Output output) {
  static const char* const names[kNumOutputs] = {
      "contact_angle", "rolling_radius", "wheel_y", "rail_y", "separation", "curvature_a",
      "curvature_b", "normal_force", "approach", "area", "max_pressure", "a", "b",
      "fx", "fy", "mz", "slip_fraction", "wear_rate"};
  return (output >= 0 && output < kNumOutputs) ? names[output] : "?";
}

Part output_part(Output output) {
  for (int p = kNumParts - 1; p >= 0; --p)
    if (output >= detail::kPartSpecs[p].first_output) return static_cast<Part>(p);
  return kGeometry;
}

const char* part_name(Part part) {
  return (part >= 0 && part < kNumParts) ? detail::kPartSpecs[part].name : "?";
}

}  // namespace railtab::lookup
