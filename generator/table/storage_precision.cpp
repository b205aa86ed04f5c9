// SPDX-License-Identifier: Apache-2.0
// Which outputs a table stores as rounded float32, and the rounding (storage_precision.hpp).
//
// float32 only for the creep and wear parts (in the wheel groups and their one-sided values in
// /jumps): their values are forces, moments, slip fractions, wear rates and the contact at a
// creepage, each used as it is, never as the small difference of two large stored numbers, so a
// relative rounding of 1e-6 stays 1e-6 in what a user computes. float64 stays for:
// - axes and jump positions: the lookup's cell search and cell fractions;
// - the geometry part: a dynamics code takes the difference of the two wheels' rolling radii
//   (~0.46 m, ~1e-5 m apart near centre; float32 alone steps by 3e-8 m there, 20 bits by 5e-7 m)
//   and of wheel_y / rail_y positions;
// - the normal part, whose creep scales map every creepage to the creep part's coordinates;
// - statuses and jump kinds (integers).
// Those are 3 % of the default table's bytes.
#include "table/storage_precision.hpp"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace railtab {

bool table_stores_float32(const Table& table) {
  const std::string* version = table.attribute("format_version");
  if (!version) return true;
  const std::string& v = *version;
  const std::size_t dot = v.find('.');
  int major = 0, minor = 0;
  if (dot == std::string::npos) return true;
  std::from_chars(v.data(), v.data() + dot, major);
  std::from_chars(v.data() + dot + 1, v.data() + v.size(), minor);
  return major > 2 || (major == 2 && minor >= 2);
}

bool stored_as_float32(const std::string& group, const TableDataset& d) {
  if (d.is_status) return false;
  const std::size_t slash = group.rfind('/');
  const std::string part = slash == std::string::npos ? group : group.substr(slash + 1);
  return part == "creep" || part == "wear";
}

float quantize_for_storage(double value) {
  if (!std::isfinite(value)) return static_cast<float>(value);
  // Round the float64 significand (52 explicit bits) to kStoredSignificandBits, to nearest with
  // ties to even, on the bit pattern: adding half an output step minus one, plus the kept last
  // bit, then clearing the dropped bits. A carry out of the significand raises the exponent, as
  // it must. One rounding only: the float32 conversion below is then exact (for |value| above
  // float32's smallest normal, 1.2e-38; below it the absolute error is under 1.4e-45).
  constexpr int kDrop = 52 - kStoredSignificandBits;
  std::uint64_t bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  const std::uint64_t kept_lsb = (bits >> kDrop) & 1u;
  bits += (std::uint64_t{1} << (kDrop - 1)) - 1u + kept_lsb;
  bits &= ~((std::uint64_t{1} << kDrop) - 1u);
  double rounded = 0.0;
  std::memcpy(&rounded, &bits, sizeof rounded);
  return static_cast<float>(rounded);
}

}  // namespace railtab
