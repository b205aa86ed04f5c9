// SPDX-License-Identifier: Apache-2.0
// Thin RAII and error checking over the HDF5 C API, shared by the table writer and reader.
// Every call result goes through check(), which throws railtab::Error naming the file, what was
// being done and HDF5's own innermost message. HDF5's automatic stack printing is switched off.
// HDF5 is touched by one thread only (the Debian build serialises the C API behind one lock).
#pragma once

#include <hdf5.h>

#include <cstddef>
#include <string>
#include <vector>

namespace railtab::h5 {

// Owns one HDF5 identifier and closes it with the matching H5?close.
class Id {
 public:
  using Closer = herr_t (*)(hid_t);
  Id() = default;
  Id(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Id(const Id&) = delete;
  Id& operator=(const Id&) = delete;
  Id(Id&& other) noexcept : id_(other.id_), closer_(other.closer_) { other.id_ = H5I_INVALID_HID; }
  Id& operator=(Id&& other) noexcept;
  ~Id() { reset(); }
  void reset();
  hid_t release() {  // give up ownership (to close explicitly and check the result)
    hid_t id = id_;
    id_ = H5I_INVALID_HID;
    return id;
  }
  hid_t get() const { return id_; }
  operator hid_t() const { return id_; }  // NOLINT: handles are passed straight to the C API

 private:
  hid_t id_ = H5I_INVALID_HID;
  Closer closer_ = nullptr;
};

// Turns off HDF5's error printing to stderr once per process (errors become exceptions).
void silence_errors();

// Innermost message of HDF5's current error stack, e.g. "truncated file: eof = 1024, ...".
std::string last_error();

// Throw railtab::Error("FILE: WHAT: hdf5 message") when status < 0 (herr_t or hid_t).
void check(long long status, const std::string& file, const std::string& what);
hid_t check_id(hid_t id, const std::string& file, const std::string& what);

// Variable-length UTF-8 string type (h5py reads these as str).
Id string_type(const std::string& file);

void write_string_attribute(hid_t object, const std::string& name, const std::string& value,
                            const std::string& file);
// Longest string attribute read [bytes] (the scene text is the longest a table holds).
inline constexpr std::size_t kMaxStringBytes = std::size_t{64} << 20;

// Reads a fixed- or variable-length string attribute.
std::string read_string_attribute(hid_t object, const std::string& name, const std::string& file);
bool has_attribute(hid_t object, const std::string& name);
// The `count` strings of a variable-length string attribute (scalar or 1-D), read with bounds
// checks instead of libhdf5's variable-length read; throws railtab::Error naming the problem.
std::vector<std::string> read_vlen_strings(hid_t attr, std::size_t count, const std::string& file,
                                           const std::string& what);

}  // namespace railtab::h5
