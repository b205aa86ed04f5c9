// SPDX-License-Identifier: Apache-2.0
// Typed HDF5 attributes for format 2 (docs/table-format.md): numbers as numbers, lists as arrays,
// JSON objects as groups of such attributes, so h5py, xarray and h5dump show values, not JSON
// text. The in-memory Table keeps its JSON text (table.hpp); only the file encoding changes.
#pragma once

#include <hdf5.h>

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace railtab::h5 {

void write_int64_attribute(hid_t object, const std::string& name, std::int64_t value, const std::string& file);
void write_int32_attribute(hid_t object, const std::string& name, std::int32_t value, const std::string& file);
void write_uint32_array_attribute(hid_t object, const std::string& name, const std::vector<std::uint32_t>& values,
                                  const std::string& file);
void write_int32_array_attribute(hid_t object, const std::string& name, const std::vector<std::int32_t>& values,
                                 const std::string& file);
void write_string_array_attribute(hid_t object, const std::string& name, const std::vector<std::string>& values,
                                  const std::string& file);

// Writes a JSON object as attributes of `group`: string -> string, integer -> int64, other
// number -> float64, non-empty array of numbers -> 1-D float64 (int64 if all integers), non-empty
// array of strings -> 1-D string array, object -> subgroup (created with `gcpl`). Anything else
// (bool, null, empty or mixed arrays, arrays of objects) is stored as its JSON text, and its
// name is listed in the group's string-array attribute `json_members` so it reads back as JSON.
void write_json_object(hid_t group, const nlohmann::json& object, const std::string& file, hid_t gcpl);

// The inverse of write_json_object (attributes in any order, subgroups as objects).
nlohmann::json read_json_object(hid_t group, const std::string& file);

// A root attribute of any type as text: strings as they are, integers and floats printed
// (shortest round-trip form). Throws naming the file for other types.
std::string read_attribute_as_text(hid_t object, const std::string& name, const std::string& file);

}  // namespace railtab::h5
