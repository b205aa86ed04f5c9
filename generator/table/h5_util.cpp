// SPDX-License-Identifier: Apache-2.0
// HDF5 C API helpers: RAII handles and errors that name the file and the object.
#include "table/h5_util.hpp"

#include <fmt/format.h>

#include <mutex>
#include <vector>

#include "core/check.hpp"
#include "lookup_vlen/vlen_string.hpp"

namespace railtab::h5 {

Id& Id::operator=(Id&& other) noexcept {
  if (this != &other) {
    reset();
    id_ = other.id_;
    closer_ = other.closer_;
    other.id_ = H5I_INVALID_HID;
  }
  return *this;
}

void Id::reset() {
  if (id_ >= 0 && closer_) closer_(id_);
  id_ = H5I_INVALID_HID;
}

void silence_errors() {
  static std::once_flag once;
  std::call_once(once, [] { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); });
}

namespace {
herr_t innermost(unsigned n, const H5E_error2_t* err, void* data) {
  // Walking upward, the first entry is the most specific one.
  if (n == 0 && err->desc) *static_cast<std::string*>(data) = err->desc;
  return 0;
}
}  // namespace

std::string last_error() {
  std::string message;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, innermost, &message);
  H5Eclear2(H5E_DEFAULT);
  return message;
}

void check(long long status, const std::string& file, const std::string& what) {
  if (status >= 0) return;
  std::string detail = last_error();
  throw Error(detail.empty() ? fmt::format("{}: {}", file, what)
                             : fmt::format("{}: {} ({})", file, what, detail));
}

hid_t check_id(hid_t id, const std::string& file, const std::string& what) {
  check(id, file, what);
  return id;
}

Id string_type(const std::string& file) {
  Id type(check_id(H5Tcopy(H5T_C_S1), file, "copy string type"), H5Tclose);
  check(H5Tset_size(type, H5T_VARIABLE), file, "string type size");
  check(H5Tset_cset(type, H5T_CSET_UTF8), file, "string type charset");
  return type;
}

void write_string_attribute(hid_t object, const std::string& name, const std::string& value,
                            const std::string& file) {
  // Fixed length (format 1.1): the bytes live in the checksummed object header, not in the
  // global heap (which has no checksum) as a variable-length string's would.
  std::string what = fmt::format("write attribute '{}'", name);
  Id type(check_id(H5Tcopy(H5T_C_S1), file, what), H5Tclose);
  check(H5Tset_size(type, value.empty() ? 1 : value.size()), file, what);
  check(H5Tset_strpad(type, H5T_STR_NULLPAD), file, what);
  check(H5Tset_cset(type, H5T_CSET_UTF8), file, what);
  Id space(check_id(H5Screate(H5S_SCALAR), file, what), H5Sclose);
  Id attr(check_id(H5Acreate2(object, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), file, what),
          H5Aclose);
  const std::string padded = value.empty() ? std::string(1, '\0') : value;
  check(H5Awrite(attr, type, padded.data()), file, what);
}

bool has_attribute(hid_t object, const std::string& name) {
  return H5Aexists(object, name.c_str()) > 0;
}

std::vector<std::string> read_vlen_strings(hid_t attr, std::size_t count, const std::string& file,
                                           const std::string& what) {
  // Not libhdf5's variable-length read: a corrupt heap reference makes that read out of bounds
  // (`railtab inspect` once crashed on 2 in 1000 damaged format-1.0 tables). The lookup's
  // bounded reader copies each string out of the file after checking every offset and size.
  namespace vlen = railtab::lookup::detail;
  vlen::RawFileLayout layout;
  std::string problem = vlen::raw_file_layout(attr, layout);
  std::vector<std::string> out;
  if (problem.empty()) problem = vlen::read_vlen_string_attribute(attr, layout, kMaxStringBytes, count, out);
  RAILTAB_CHECK(problem.empty(), "{}: {}: {}", file, what, problem);
  return out;
}

std::string read_string_attribute(hid_t object, const std::string& name, const std::string& file) {
  std::string what = fmt::format("read attribute '{}'", name);
  Id attr(check_id(H5Aopen(object, name.c_str(), H5P_DEFAULT), file, what), H5Aclose);
  Id file_type(check_id(H5Aget_type(attr), file, what), H5Tclose);
  RAILTAB_CHECK(H5Tget_class(file_type) == H5T_STRING, "{}: attribute '{}' is not a string", file, name);
  Id space(check_id(H5Aget_space(attr), file, what), H5Sclose);
  RAILTAB_CHECK(H5Sget_simple_extent_npoints(space) == 1, "{}: attribute '{}' is not a scalar", file, name);
  if (H5Tis_variable_str(file_type) > 0) return read_vlen_strings(attr, 1, file, what).at(0);
  std::size_t size = H5Tget_size(file_type);
  RAILTAB_CHECK(size > 0 && size <= kMaxStringBytes, "{}: attribute '{}' declares {} bytes", file, name,
                size);
  Id mem(check_id(H5Tcopy(H5T_C_S1), file, what), H5Tclose);
  check(H5Tset_size(mem, size), file, what);
  check(H5Tset_cset(mem, H5Tget_cset(file_type)), file, what);  // no ASCII <-> UTF-8 conversion
  check(H5Tset_strpad(mem, H5T_STR_NULLPAD), file, what);  // NULLTERM would drop the last byte
  std::vector<char> buffer(size + 1, '\0');
  check(H5Aread(attr, mem, buffer.data()), file, what);
  return std::string(buffer.data());
}

}  // namespace railtab::h5
