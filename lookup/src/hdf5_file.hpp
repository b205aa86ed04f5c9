// SPDX-License-Identifier: Apache-2.0
// Read-only access to one HDF5 file for the loader. Every failure throws LoadError naming the
// file, the object and, when HDF5 has one, its own innermost error message. Used at load only;
// the query path never touches HDF5.
//
// Hardened against corrupt and crafted files (docs/table-format.md, "What readers check"):
// every extent, storage size and filter is checked BEFORE anything is allocated for it, string
// attributes are read with bounded copies, and variable-length strings (legacy tables only) only
// after the global heap that holds them has been checked (global_heap_check.hpp).
#pragma once

#include <hdf5.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace railtab::lookup::detail {

// Owns one hid_t and closes it with the matching H5?close.
class Hid {
 public:
  using Closer = herr_t (*)(hid_t);
  Hid() = default;
  Hid(hid_t id, Closer close) : id_(id), close_(close) {}
  Hid(Hid&& o) noexcept : id_(o.id_), close_(o.close_) { o.id_ = -1; }
  Hid& operator=(Hid&& o) noexcept;
  Hid(const Hid&) = delete;
  Hid& operator=(const Hid&) = delete;
  ~Hid();
  hid_t get() const { return id_; }

 private:
  hid_t id_ = -1;           // HDF5 identifier, < 0 when empty
  Closer close_ = nullptr;  // H5Fclose, H5Dclose, ...
};

// Limits checked before any allocation (docs/table-format.md, "Limits").
inline constexpr std::size_t kMaxAttributeBytes = 1 << 20;  // one string attribute
inline constexpr int kMaxRank = 8;                          // dimensions of a dataset
// Deflate cannot shrink data by more than about 1032:1, so a compressed dataset declaring more
// than this many times its stored bytes is corrupt.
inline constexpr double kMaxCompressionRatio = 1100.0;
inline constexpr std::size_t kMaxChunkBytes = std::size_t{64} << 20;  // one chunk, uncompressed

// A dataset read whole, converted to the requested memory type.
template <typename T>
struct DatasetValues {
  std::vector<hsize_t> dims;  // shape in the file, C order
  std::vector<T> values;      // prod(dims) values, C order
  bool checksummed = false;   // its filter pipeline holds HDF5's Fletcher32 checksum
  bool compact = false;       // compact layout: the values live in the object header
};

class Hdf5File {
 public:
  explicit Hdf5File(const std::string& path);  // opens read-only; throws LoadError

  [[noreturn]] void fail(const std::string& problem) const;  // throws LoadError for this file

  // Whether an object (group or dataset) exists at an absolute path like "/left/geometry".
  bool exists(const std::string& object) const;
  // Whether `object` ("/" = root) has an attribute `name` (nothing is read).
  bool has_attribute(const std::string& object, const std::string& name) const;
  // A string attribute of an object ("/" = root): absent -> nullopt; not a single string, too
  // long, inconsistent with its stored size, or variable-length when !allow_variable_strings()
  // -> error.
  std::optional<std::string> string_attribute(const std::string& object,
                                              const std::string& name) const;
  // Reads every string attribute of every object in the file through string_attribute (so each
  // is checked as above), for readers that read more attributes than the lookup (`railtab
  // inspect`). Only for files with checksummed metadata: listing the attributes makes libhdf5
  // decode every attribute message, which it cannot do safely when they may be corrupt.
  void check_all_string_attributes() const;
  // One string attribute as check_all_string_attributes checks it: a single string through
  // string_attribute, an array of fixed-length strings by its sizes and one bounded read.
  void check_string_attribute(const std::string& object, const std::string& name) const;
  // Variable-length string attributes are read only when allowed (legacy tables); the global
  // heap is checked once, before the first such read.
  void set_allow_variable_strings(bool allow) { allow_vlen_ = allow; }

  // Whole datasets; the class (H5T_FLOAT / H5T_INTEGER) is checked first, then, before
  // anything is allocated: the shape (`expected`, else 1-D of at most `max_values` values), the
  // chunk shape, the filters and the stored bytes against the declared shape and the file size.
  // `shape_source` names where `expected` comes from, for the message.
  DatasetValues<double> read_doubles(const std::string& dataset,
                                     const std::vector<hsize_t>& expected,
                                     const std::string& shape_source) const;
  DatasetValues<std::uint32_t> read_uint32(const std::string& dataset,
                                           const std::vector<hsize_t>& expected,
                                           const std::string& shape_source) const;
  // 1-D, or also a scalar (rank 0, dims empty) when `allow_scalar` (format-2 fixed variables).
  DatasetValues<double> read_axis(const std::string& dataset, std::size_t max_values,
                                  bool allow_scalar = false) const;
  DatasetValues<std::int32_t> read_int32(const std::string& dataset, std::size_t max_values) const;
  // Names of the links in `group` (at most 1000, else an error). Only for files with checksummed
  // metadata, like check_all_string_attributes.
  std::vector<std::string> members(const std::string& group) const;
  // The shape of `dataset` (nothing else is read), at most kMaxRank dimensions.
  std::vector<hsize_t> dataset_shape(const std::string& dataset) const;
  // Whether `dataset` has the Fletcher32 filter (nothing but its creation properties is read).
  bool checksummed(const std::string& dataset) const;

  // HDF5 superblock version: >= 2 means every metadata block carries a checksum.
  unsigned superblock_version() const;
  std::uintmax_t file_size() const { return file_size_; }
  const std::string& path() const { return path_; }

 private:
  template <typename T>
  DatasetValues<T> read(const std::string& dataset, hid_t mem_type, H5T_class_t type_class,
                        const char* type_name, const std::vector<hsize_t>& expected,
                        const std::string& shape_source, std::size_t max_values,
                        bool allow_scalar = false) const;
  Hid open_dataset(const std::string& dataset) const;

  std::string path_;             // file name, for messages
  std::uintmax_t file_size_ = 0;  // bytes, at open
  Hid file_;                     // open file
  bool allow_vlen_ = false;      // variable-length strings may be read
  mutable bool heap_checked_ = false;  // global heap checked (before the first vlen read)
};

// A dataset's shape as text for messages: "[3,4]".
std::string shape_text(const std::vector<hsize_t>& dims);

// Turns HDF5's automatic error printing off for its lifetime (the loader reports errors itself)
// and restores the previous handler afterwards, so the process-wide setting is left as found.
class Hdf5ErrorsSilenced {
 public:
  Hdf5ErrorsSilenced();
  ~Hdf5ErrorsSilenced();
  Hdf5ErrorsSilenced(const Hdf5ErrorsSilenced&) = delete;
  Hdf5ErrorsSilenced& operator=(const Hdf5ErrorsSilenced&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;  // previous handler
  void* data_ = nullptr;        // its client data
};

}  // namespace railtab::lookup::detail
