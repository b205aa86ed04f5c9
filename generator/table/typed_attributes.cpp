// SPDX-License-Identifier: Apache-2.0
// Typed HDF5 attributes of format 2 (typed_attributes.hpp): writing and reading numbers, lists and strings.
#include "table/typed_attributes.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "core/check.hpp"
#include "table/h5_util.hpp"

namespace railtab::h5 {
namespace {

template <class T>
void write_array(hid_t object, const std::string& name, hid_t file_type, hid_t mem_type, const std::vector<T>& values,
                 const std::string& file) {
  const std::string what = fmt::format("write attribute '{}'", name);
  const hsize_t n = values.size();
  Id space(check_id(n == 0 ? H5Screate(H5S_NULL) : H5Screate_simple(1, &n, nullptr), file, what), H5Sclose);
  Id attr(check_id(H5Acreate2(object, name.c_str(), file_type, space, H5P_DEFAULT, H5P_DEFAULT), file, what),
          H5Aclose);
  if (n > 0) check(H5Awrite(attr, mem_type, values.data()), file, what);
}

void write_scalar(hid_t object, const std::string& name, hid_t file_type, hid_t mem_type, const void* value,
                  const std::string& file) {
  const std::string what = fmt::format("write attribute '{}'", name);
  Id space(check_id(H5Screate(H5S_SCALAR), file, what), H5Sclose);
  Id attr(check_id(H5Acreate2(object, name.c_str(), file_type, space, H5P_DEFAULT, H5P_DEFAULT), file, what),
          H5Aclose);
  check(H5Awrite(attr, mem_type, value), file, what);
}

herr_t collect_name(hid_t, const char* name, const H5A_info_t*, void* data) {
  static_cast<std::vector<std::string>*>(data)->emplace_back(name);
  return 0;
}
herr_t collect_link(hid_t, const char* name, const H5L_info_t*, void* data) {
  static_cast<std::vector<std::string>*>(data)->emplace_back(name);
  return 0;
}

// Values of a string attribute (scalar or 1-D, variable or fixed length).
std::vector<std::string> read_strings(hid_t attr, hid_t file_type, hssize_t n, const std::string& file,
                                      const std::string& what) {
  std::vector<std::string> out;
  if (H5Tis_variable_str(file_type) > 0) {
    if (n <= 0) return out;
    return read_vlen_strings(attr, static_cast<std::size_t>(n), file, what);
  }
  const std::size_t size = H5Tget_size(file_type);
  RAILTAB_CHECK(size > 0 && size * static_cast<std::size_t>(n) <= (std::size_t{64} << 20),
                "{}: attribute declares {} strings of {} bytes", file, n, size);
  Id mem(check_id(H5Tcopy(H5T_C_S1), file, what), H5Tclose);
  check(H5Tset_size(mem, size), file, what);
  check(H5Tset_cset(mem, H5Tget_cset(file_type)), file, what);  // no ASCII <-> UTF-8 conversion
  check(H5Tset_strpad(mem, H5T_STR_NULLPAD), file, what);       // NULLTERM would drop the last byte
  std::vector<char> buffer(size * static_cast<std::size_t>(n), '\0');
  check(H5Aread(attr, mem, buffer.data()), file, what);
  for (hssize_t i = 0; i < n; ++i) {
    const char* p = buffer.data() + static_cast<std::size_t>(i) * size;
    out.emplace_back(p, strnlen(p, size));
  }
  return out;
}

// One attribute as JSON: scalars as values, 1-D attributes as arrays.
nlohmann::json read_attribute_json(hid_t object, const std::string& name, const std::string& file) {
  const std::string what = fmt::format("read attribute '{}'", name);
  Id attr(check_id(H5Aopen(object, name.c_str(), H5P_DEFAULT), file, what), H5Aclose);
  Id type(check_id(H5Aget_type(attr), file, what), H5Tclose);
  Id space(check_id(H5Aget_space(attr), file, what), H5Sclose);
  const bool scalar = H5Sget_simple_extent_type(space) == H5S_SCALAR;
  const hssize_t n = H5Sget_simple_extent_npoints(space);
  nlohmann::json out = nlohmann::json::array();
  switch (H5Tget_class(type)) {
    case H5T_STRING:
      for (auto& s : read_strings(attr, type, n, file, what)) out.push_back(std::move(s));
      break;
    case H5T_INTEGER: {
      std::vector<long long> v(static_cast<std::size_t>(n));
      if (n > 0) check(H5Aread(attr, H5T_NATIVE_LLONG, v.data()), file, what);
      for (long long x : v) out.push_back(x);
      break;
    }
    case H5T_FLOAT: {
      std::vector<double> v(static_cast<std::size_t>(n));
      if (n > 0) check(H5Aread(attr, H5T_NATIVE_DOUBLE, v.data()), file, what);
      for (double x : v) out.push_back(x);
      break;
    }
    default:
      RAILTAB_CHECK(false, "{}: attribute '{}' has a type railtab does not write", file, name);
  }
  if (scalar) return out.at(0);
  return out;
}

}  // namespace

void write_int64_attribute(hid_t object, const std::string& name, std::int64_t value, const std::string& file) {
  write_scalar(object, name, H5T_STD_I64LE, H5T_NATIVE_INT64, &value, file);
}

void write_int32_attribute(hid_t object, const std::string& name, std::int32_t value, const std::string& file) {
  write_scalar(object, name, H5T_STD_I32LE, H5T_NATIVE_INT32, &value, file);
}

void write_uint32_array_attribute(hid_t object, const std::string& name, const std::vector<std::uint32_t>& values,
                                  const std::string& file) {
  write_array(object, name, H5T_STD_U32LE, H5T_NATIVE_UINT32, values, file);
}

void write_int32_array_attribute(hid_t object, const std::string& name, const std::vector<std::int32_t>& values,
                                 const std::string& file) {
  write_array(object, name, H5T_STD_I32LE, H5T_NATIVE_INT32, values, file);
}

void write_string_array_attribute(hid_t object, const std::string& name, const std::vector<std::string>& values,
                                  const std::string& file) {
  // Fixed length, the longest value's size, shorter ones null-padded: like every string
  // attribute (h5_util.hpp), the bytes stay in the checksummed object header.
  const std::string what = fmt::format("write attribute '{}'", name);
  std::size_t size = 1;
  for (const std::string& s : values) size = std::max(size, s.size());
  Id type(check_id(H5Tcopy(H5T_C_S1), file, what), H5Tclose);
  check(H5Tset_size(type, size), file, what);
  check(H5Tset_strpad(type, H5T_STR_NULLPAD), file, what);
  check(H5Tset_cset(type, H5T_CSET_UTF8), file, what);
  std::vector<char> data(size * values.size(), '\0');
  for (std::size_t i = 0; i < values.size(); ++i) std::copy(values[i].begin(), values[i].end(), data.begin() + i * size);
  const hsize_t n = values.size();
  Id space(check_id(n == 0 ? H5Screate(H5S_NULL) : H5Screate_simple(1, &n, nullptr), file, what), H5Sclose);
  Id attr(check_id(H5Acreate2(object, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), file, what), H5Aclose);
  if (n > 0) check(H5Awrite(attr, type, data.data()), file, what);
}

void write_json_object(hid_t group, const nlohmann::json& object, const std::string& file, hid_t gcpl) {
  RAILTAB_CHECK(object.is_object(), "{}: internal: a JSON object expected, got {}", file, object.dump());
  std::vector<std::string> as_text;
  for (const auto& [key, value] : object.items()) {
    if (value.is_string()) {
      write_string_attribute(group, key, value.get<std::string>(), file);
    } else if (value.is_number_integer()) {
      write_int64_attribute(group, key, value.get<std::int64_t>(), file);
    } else if (value.is_number()) {
      const double x = value.get<double>();
      write_scalar(group, key, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &x, file);
    } else if (value.is_object()) {
      Id sub(check_id(H5Gcreate2(group, key.c_str(), H5P_DEFAULT, gcpl, H5P_DEFAULT), file, "create group " + key),
             H5Gclose);
      write_json_object(sub, value, file, gcpl);
    } else if (value.is_array() && !value.empty() &&
               std::all_of(value.begin(), value.end(), [](const auto& v) { return v.is_string(); })) {
      write_string_array_attribute(group, key, value.get<std::vector<std::string>>(), file);
    } else if (value.is_array() && !value.empty() &&
               std::all_of(value.begin(), value.end(), [](const auto& v) { return v.is_number_integer(); })) {
      const auto v = value.get<std::vector<std::int64_t>>();
      write_array(group, key, H5T_STD_I64LE, H5T_NATIVE_INT64, v, file);
    } else if (value.is_array() && !value.empty() &&
               std::all_of(value.begin(), value.end(), [](const auto& v) { return v.is_number(); })) {
      write_array(group, key, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, value.get<std::vector<double>>(), file);
    } else {
      write_string_attribute(group, key, value.dump(), file);
      as_text.push_back(key);
    }
  }
  if (!as_text.empty()) write_string_array_attribute(group, "json_members", as_text, file);
}

nlohmann::json read_json_object(hid_t group, const std::string& file) {
  nlohmann::json out = nlohmann::json::object();
  std::vector<std::string> names;
  check(H5Aiterate2(group, H5_INDEX_NAME, H5_ITER_INC, nullptr, collect_name, &names), file, "list attributes");
  std::vector<std::string> as_text;
  if (has_attribute(group, "json_members")) as_text = read_attribute_json(group, "json_members", file);
  for (const std::string& name : names) {
    if (name == "json_members") continue;
    nlohmann::json value = read_attribute_json(group, name, file);
    if (std::find(as_text.begin(), as_text.end(), name) != as_text.end()) value = nlohmann::json::parse(value.get<std::string>());
    out[name] = std::move(value);
  }
  std::vector<std::string> links;
  check(H5Literate(group, H5_INDEX_NAME, H5_ITER_INC, nullptr, collect_link, &links), file, "list groups");
  for (const std::string& name : links) {
    Id sub(check_id(H5Gopen2(group, name.c_str(), H5P_DEFAULT), file, "open group " + name), H5Gclose);
    out[name] = read_json_object(sub, file);
  }
  return out;
}

std::string read_attribute_as_text(hid_t object, const std::string& name, const std::string& file) {
  const nlohmann::json value = read_attribute_json(object, name, file);
  RAILTAB_CHECK(!value.is_array(), "{}: attribute '{}' is an array, a single value expected", file, name);
  return value.is_string() ? value.get<std::string>() : value.dump();
}

}  // namespace railtab::h5
