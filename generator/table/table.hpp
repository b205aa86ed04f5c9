// SPDX-License-Identifier: Apache-2.0
// In-memory image of a contact-table file (docs/table-format.md): root attributes, axes and the
// datasets of each wheel and part. The sweep fills it, the writer stores it, the reader returns it,
// merge concatenates shards of it. Everything is held in C order, last index fastest.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "core/status.hpp"

namespace railtab {

// Format 2 (docs/table-format.md): typed attributes, fixed variables as scalar datasets in /axes,
// CF flag attributes, coordinates in every part group, with the integrity of format 1.1
// (Fletcher32 on every chunked dataset, checksummed metadata, fixed-length strings). The reader
// also reads format 1.0 and 1.1.
inline constexpr int kTableFormatMajor = 2;
// 2.1: normalised creep coordinates, located contact jumps (/jumps); 2.2: creep and wear outputs
// stored as float32 rounded to 20 significant bits (table/storage_precision.hpp); 2.3: additive
// groups and datasets only (the error map, /error_map; the normal part's linear creep
// coefficients, creep_coefficient_*), a 2.2 reader reads a 2.3 table; 2.4: the yaw axis or fixed
// yaw (/axes/yaw), written only by scenes with a yaw key: a scene without one keeps writing 2.3,
// so its table is unchanged byte for byte.
inline constexpr int kTableFormatMinor = 4;
inline constexpr const char* kTableFormatVersion = "2.3";
inline constexpr const char* kTableFormatVersionYaw = "2.4";

// The group of the contact jumps along y (format 2.1, docs/table-format.md) and the one a shard
// carries instead: the jumps of its y cells, which `railtab merge` joins into kJumpGroup.
inline constexpr const char* kJumpGroup = "jumps";
inline constexpr const char* kShardJumpGroup = "shard_jumps";
// The group of the error map (format 2.3, generator/generate/error_map.hpp).
inline constexpr const char* kErrorMapGroup = "error_map";

struct TableAxis {
  std::string name;          // "y", "roll", "load", "xi", "eta", "phi", "slot"
  std::string units;         // "m", "rad", "N", "1", "rad/m"
  std::string description;   // one line
  std::vector<double> values;  // strictly increasing grid [units]
  bool integer = false;      // stored as int32 (the slot axis)
};

struct TableDataset {
  std::string name;                  // e.g. "contact_angle", "status"
  std::string units;                 // SI units, "1" for dimensionless and status
  std::string description;           // one line
  std::vector<std::string> axes;     // dimension names, first = slowest (e.g. y, roll, slot)
  std::vector<std::size_t> shape;    // extent per dimension, same length as axes
  std::vector<double> values;        // float64 data (empty for status datasets), size = prod(shape)
  std::vector<StatusBits> status;    // uint32 data of a status dataset (empty otherwise)
  bool is_status = false;            // stored as uint32
  std::uint64_t storage_bytes = 0;   // bytes on disk (set by the reader) [B]

  std::size_t size() const;          // number of elements, prod(shape); throws on overflow
};

// A group of datasets: a wheel part ("left/geometry") or the root ("").
struct TableGroup {
  std::string path;                    // "left/geometry", "right/normal", ... ; "" = root
  std::vector<TableDataset> datasets;  // in file order
  const TableDataset* find(const std::string& name) const;
  TableDataset* find(const std::string& name);
};

struct Table {
  std::vector<std::pair<std::string, std::string>> attributes;  // root string attributes, in order
  std::vector<TableAxis> axes;         // /axes, in order
  std::vector<TableGroup> groups;      // wheel parts; a group with path "" holds root datasets

  const std::string* attribute(const std::string& name) const;  // nullptr when absent
  void set_attribute(const std::string& name, std::string value);
  void remove_attribute(const std::string& name);
  const TableAxis* axis(const std::string& name) const;
  const TableGroup* group(const std::string& path) const;
  TableGroup* group(const std::string& path);
};

// Datasets every reader may rely on, per part (format 1.0). Parts "creep" and "wear" are optional.
const std::vector<std::string>& required_outputs(const std::string& part);

// The current UTC time as ISO 8601 ("2026-11-21T22:37:00Z"), the root attribute `created`; the
// time SOURCE_DATE_EPOCH gives when it is set (throws railtab::Error when it is not an integer).
std::string utc_timestamp();

}  // namespace railtab
