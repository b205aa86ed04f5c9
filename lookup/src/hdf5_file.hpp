// Read-only access to one HDF5 file for the loader. Every failure throws LoadError naming the
// file, the object and, when HDF5 has one, its own innermost error message. Used at load only;
// the query path never touches HDF5.
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

// A dataset read whole, converted to the requested memory type.
template <typename T>
struct DatasetValues {
  std::vector<hsize_t> dims;  // shape in the file, C order
  std::vector<T> values;      // prod(dims) values, C order
};

class Hdf5File {
 public:
  explicit Hdf5File(const std::string& path);  // opens read-only; throws LoadError

  [[noreturn]] void fail(const std::string& problem) const;  // throws LoadError for this file

  // Whether an object (group or dataset) exists at an absolute path like "/left/geometry".
  bool exists(const std::string& object) const;
  // A string attribute of an object ("/" = root): absent -> nullopt; not a string -> error.
  std::optional<std::string> string_attribute(const std::string& object,
                                              const std::string& name) const;
  // Whole datasets; `type_class` (H5T_FLOAT / H5T_INTEGER) is checked first.
  DatasetValues<double> read_doubles(const std::string& dataset, H5T_class_t type_class) const;
  DatasetValues<std::uint32_t> read_uint32(const std::string& dataset) const;
  DatasetValues<std::int32_t> read_int32(const std::string& dataset) const;

  const std::string& path() const { return path_; }

 private:
  template <typename T>
  DatasetValues<T> read(const std::string& dataset, hid_t mem_type, H5T_class_t type_class,
                        const char* type_name) const;

  std::string path_;  // file name, for messages
  Hid file_;          // open file
};

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
