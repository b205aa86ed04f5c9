// SPDX-License-Identifier: Apache-2.0
// In-memory table: dataset lookup by name, sizes and the creation time stamp.
#include "table/table.hpp"

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <cstring>
#include <ctime>

#include "core/check.hpp"

#include "core/check.hpp"

namespace railtab {

std::size_t TableDataset::size() const {
  std::size_t n = 1;
  for (std::size_t extent : shape) {
    // A wrapped product would allocate a small buffer and index far beyond it.
    RAILTAB_CHECK(!__builtin_mul_overflow(n, extent, &n), "dataset {}: shape overflows 64 bits", name);
  }
  return n;
}

const TableDataset* TableGroup::find(const std::string& name) const {
  auto it = std::find_if(datasets.begin(), datasets.end(), [&](const auto& d) { return d.name == name; });
  return it == datasets.end() ? nullptr : &*it;
}

TableDataset* TableGroup::find(const std::string& name) {
  return const_cast<TableDataset*>(std::as_const(*this).find(name));
}

const std::string* Table::attribute(const std::string& name) const {
  for (const auto& [key, value] : attributes) {
    if (key == name) return &value;
  }
  return nullptr;
}

void Table::set_attribute(const std::string& name, std::string value) {
  for (auto& [key, old] : attributes) {
    if (key == name) {
      old = std::move(value);
      return;
    }
  }
  attributes.emplace_back(name, std::move(value));
}

void Table::remove_attribute(const std::string& name) {
  std::erase_if(attributes, [&](const auto& kv) { return kv.first == name; });
}

const TableAxis* Table::axis(const std::string& name) const {
  auto it = std::find_if(axes.begin(), axes.end(), [&](const auto& a) { return a.name == name; });
  return it == axes.end() ? nullptr : &*it;
}

const TableGroup* Table::group(const std::string& path) const {
  auto it = std::find_if(groups.begin(), groups.end(), [&](const auto& g) { return g.path == path; });
  return it == groups.end() ? nullptr : &*it;
}

TableGroup* Table::group(const std::string& path) {
  return const_cast<TableGroup*>(std::as_const(*this).group(path));
}

const std::vector<std::string>& required_outputs(const std::string& part) {
  static const std::vector<std::string> kGeometry{"contact_angle", "rolling_radius", "wheel_y", "rail_y",
                                                  "separation",    "curvature_a",    "curvature_b", "status"};
  static const std::vector<std::string> kNormal{"normal_force", "approach", "area", "max_pressure",
                                                "a",            "b",        "status"};
  static const std::vector<std::string> kCreep{"fx", "fy", "mz", "slip_fraction", "status"};
  static const std::vector<std::string> kWear{"wear_rate", "status"};
  static const std::vector<std::string> kNone{};
  if (part == "geometry") return kGeometry;
  if (part == "normal") return kNormal;
  if (part == "creep") return kCreep;
  if (part == "wear") return kWear;
  return kNone;
}

std::string utc_timestamp() {
  std::time_t now = std::time(nullptr);
  // Reproducible builds (reproducible-builds.org/specs/source-date-epoch): a rebuilt table is
  // byte-identical when SOURCE_DATE_EPOCH is set.
  if (const char* epoch = std::getenv("SOURCE_DATE_EPOCH"); epoch != nullptr && *epoch != '\0') {
    long long seconds = -1;
    const char* end = epoch + std::strlen(epoch);
    const auto [ptr, ec] = std::from_chars(epoch, end, seconds);
    RAILTAB_CHECK(ec == std::errc() && ptr == end && seconds >= 0,
                  "SOURCE_DATE_EPOCH must be a non-negative integer (seconds since 1970), got '{}'", epoch);
    now = static_cast<std::time_t>(seconds);
  }
  std::tm tm{};
  gmtime_r(&now, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

}  // namespace railtab
