// SPDX-License-Identifier: Apache-2.0
// Introspection that needs no query data: status bit names, units, slot names, versions, and the
// Table accessors added with them (the query-path accessors are in table.cpp).
#include <string>

#include "grid.hpp"
#include "railtab/lookup.hpp"
#include "table_data.hpp"

#ifndef RAILTAB_LOOKUP_VERSION
#error "RAILTAB_LOOKUP_VERSION must be defined by the build (lookup/CMakeLists.txt)"
#endif

namespace railtab::lookup {

namespace status {

const char* bit_name(StatusBits bit) noexcept {
  // Names as in src/core/status.hpp's describe() and the table files' flag_meanings.
  static const char* const names[kNumBits] = {
      "converged",    "not_converged",  "two_point",      "lift_off",      "curvature_clipped",
      "curvature_shifted", "fallback_model", "flange_contact", "non_hertzian", "full_slip",
      "out_of_range", "invalid_input",  "profile_edge",   "failed",         "area_too_small",
      "not_planar",   "near_equal_minima", "curvature_step", "low_confidence"};
  for (int b = 0; b < kNumBits; ++b)
    if (bit == (1u << b)) return names[b];
  return "unknown";
}

std::string describe(StatusBits bits) {
  if (bits == 0) return "none";
  std::string out;
  for (unsigned b = 0; b < 32; ++b) {
    if (!(bits & (1u << b))) continue;
    if (!out.empty()) out += ',';
    out += b < static_cast<unsigned>(kNumBits) ? bit_name(1u << b) : "bit" + std::to_string(b);
  }
  return out;
}

}  // namespace status

const char* output_units(Output output) {
  static const char* const units[kNumOutputs] = {"rad", "m",  "m",   "m", "m",   "1/m",
                                                 "1/m", "N",  "m",   "m2", "Pa", "m",
                                                 "m",   "N",  "N",   "N m", "1", "m2/m"};
  return (output >= 0 && output < kNumOutputs) ? units[output] : "";
}

const char* state_units(const std::string& variable) {
  static const char* const units[detail::kNumVars] = {"m", "rad", "N", "1", "1", "rad/m", "rad"};
  for (int var = 0; var < detail::kNumVars; ++var)
    if (variable == detail::var_name(var)) return units[var];
  return "";
}

std::string slot_name(int slot) {
  if (slot == 0) return "tread";
  if (slot == 1) return "flange";
  return "slot" + std::to_string(slot);
}

const char* library_version() noexcept { return RAILTAB_LOOKUP_VERSION; }
const char* supported_format_version() noexcept { return "2.4"; }

bool Table::checksums_verified() const { return data_->checksums_verified; }

bool Table::yaw_even() const { return data_->yaw_even; }

}  // namespace railtab::lookup
