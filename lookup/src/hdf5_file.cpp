// SPDX-License-Identifier: Apache-2.0
// Read-only HDF5 access for the loader (hdf5_file.hpp): every failure a LoadError naming the file.
#include "hdf5_file.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <limits>
#include <system_error>

#include "railtab/lookup.hpp"
#include "vlen_string.hpp"

namespace railtab::lookup::detail {
namespace {

// Innermost message on HDF5's error stack (e.g. "truncated file: eof = ..."), "" if none.
std::string hdf5_message() {
  std::string last;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_DOWNWARD,
      [](unsigned, const H5E_error2_t* e, void* out) -> herr_t {
        if (e->desc && *e->desc) *static_cast<std::string*>(out) = e->desc;
        return 0;
      },
      &last);
  return last;
}

std::string with_hdf5_message(const std::string& problem) {
  const std::string m = hdf5_message();
  return m.empty() ? problem : problem + " (HDF5: " + m + ")";
}

// Product of `dims`, or nullopt if it does not fit in size_t.
std::optional<std::size_t> checked_product(const std::vector<hsize_t>& dims) {
  std::size_t n = 1;
  for (hsize_t e : dims) {
    if (e > std::numeric_limits<std::size_t>::max()) return std::nullopt;
    if (e != 0 && n > std::numeric_limits<std::size_t>::max() / e) return std::nullopt;
    n *= static_cast<std::size_t>(e);
  }
  return n;
}

// What a path that is not a regular file names, for the refusal.
const char* file_kind(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

}  // namespace

std::string shape_text(const std::vector<hsize_t>& dims) {
  std::string s = "[";
  for (std::size_t i = 0; i < dims.size(); ++i) {
    if (i) s += ',';
    s += std::to_string(static_cast<unsigned long long>(dims[i]));
  }
  return s + ']';
}

Hid& Hid::operator=(Hid&& o) noexcept {
  if (this != &o) {
    if (id_ >= 0 && close_) close_(id_);
    id_ = o.id_;
    close_ = o.close_;
    o.id_ = -1;
  }
  return *this;
}

Hid::~Hid() {
  if (id_ >= 0 && close_) close_(id_);
}

Hdf5ErrorsSilenced::Hdf5ErrorsSilenced() {
  H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

Hdf5ErrorsSilenced::~Hdf5ErrorsSilenced() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }

Hdf5File::Hdf5File(const std::string& path) : path_(path) {
  // Only a regular file is opened: the raw superblock read and HDF5's open of a FIFO would wait
  // for a writer forever, and opening a device can have effects (a tape rewinds). stat follows
  // links (a link to a table is a table) and opens nothing.
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    const int err = errno;
    fail(err == ENOENT ? "no such file" : std::string("cannot read it: ") + std::strerror(err));
  }
  if (!S_ISREG(st.st_mode)) fail(std::string("it is ") + file_kind(st.st_mode) + ", not a regular file: refused");
  std::error_code ec;
  file_size_ = std::filesystem::file_size(path, ec);
  if (ec) fail("cannot read its size: " + ec.message());
  if (const std::string problem = detail::unchecksummed_metadata_problem(path); !problem.empty())
    fail(problem);
  if (H5Fis_hdf5(path.c_str()) <= 0)
    fail(with_hdf5_message("not an HDF5 file (or its superblock is corrupt)"));
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) fail(with_hdf5_message("cannot open (truncated or corrupt file?)"));
  file_ = Hid(f, H5Fclose);
}

void Hdf5File::fail(const std::string& problem) const { throw LoadError(path_, problem); }

unsigned Hdf5File::superblock_version() const {
  H5F_info2_t info{};
  if (H5Fget_info2(file_.get(), &info) < 0) fail(with_hdf5_message("cannot read the superblock"));
  return info.super.version;
}

bool Hdf5File::exists(const std::string& object) const {
  // H5Lexists needs every intermediate link to exist, so walk the path one component at a time.
  std::size_t pos = 1;
  while (pos <= object.size()) {
    const std::size_t next = object.find('/', pos);
    const std::string prefix = object.substr(0, next);
    if (H5Lexists(file_.get(), prefix.c_str(), H5P_DEFAULT) <= 0) return false;
    if (next == std::string::npos) break;
    pos = next + 1;
  }
  return H5Oexists_by_name(file_.get(), object.c_str(), H5P_DEFAULT) > 0;
}

bool Hdf5File::has_attribute(const std::string& object, const std::string& name) const {
  return H5Aexists_by_name(file_.get(), object.c_str(), name.c_str(), H5P_DEFAULT) > 0;
}

std::optional<std::string> Hdf5File::string_attribute(const std::string& object,
                                                      const std::string& name) const {
  const std::string where = "attribute " + name + " of " + object;
  if (!has_attribute(object, name)) return std::nullopt;
  Hid attr(H5Aopen_by_name(file_.get(), object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
           H5Aclose);
  if (attr.get() < 0) fail(with_hdf5_message("cannot open " + where));
  Hid type(H5Aget_type(attr.get()), H5Tclose);
  if (type.get() < 0) fail(with_hdf5_message("cannot read the type of " + where));
  if (H5Tget_class(type.get()) != H5T_STRING) fail(where + " is not a string");
  Hid space(H5Aget_space(attr.get()), H5Sclose);
  if (space.get() < 0 || H5Sget_simple_extent_npoints(space.get()) != 1)
    fail(where + " is not a single string");

  if (H5Tis_variable_str(type.get()) > 0) {
    if (!allow_vlen_)
      fail(where + " is a variable-length string: a checksummed table (format 1.1) stores "
                   "fixed-length strings only");
    Hid fcpl(H5Fget_create_plist(file_.get()), H5Pclose);
    RawFileLayout layout{path_, file_size_};
    hsize_t user_block = 0;
    if (fcpl.get() < 0 || H5Pget_userblock(fcpl.get(), &user_block) < 0 ||
        H5Pget_sizes(fcpl.get(), &layout.sizeof_addr, &layout.sizeof_size) < 0)
      fail(with_hdf5_message("cannot read the file creation properties"));
    layout.base = user_block;
    std::string out;
    const std::string problem =
        read_vlen_string_attribute(attr.get(), layout, kMaxAttributeBytes, out);
    if (!problem.empty()) fail(where + ": " + problem);
    return out;
  }
  // Fixed length: the declared size must be what is stored, then one bounded copy.
  const std::size_t size = H5Tget_size(type.get());
  if (size == 0 || size > kMaxAttributeBytes)
    fail(where + " declares " + std::to_string(size) + " bytes (limit " +
         std::to_string(kMaxAttributeBytes) + ")");
  if (H5Aget_storage_size(attr.get()) != size)
    fail(where + " declares " + std::to_string(size) + " bytes but stores " +
         std::to_string(static_cast<unsigned long long>(H5Aget_storage_size(attr.get()))));
  Hid mem(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_cset(mem.get(), H5Tget_cset(type.get()));  // HDF5 converts no ASCII <-> UTF-8
  H5Tset_size(mem.get(), size);
  H5Tset_strpad(mem.get(), H5T_STR_NULLPAD);
  std::string out(size, '\0');
  if (H5Aread(attr.get(), mem.get(), out.data()) < 0)
    fail(with_hdf5_message("cannot read " + where));
  out.resize(out.find('\0') == std::string::npos ? size : out.find('\0'));
  return out;
}

void Hdf5File::check_all_string_attributes() const {
  // Objects first (names collected, then checked: no exception may unwind through libhdf5).
  std::vector<std::string> objects{"/"};
  const auto collect = [](hid_t, const char* name, const H5O_info_t*, void* out) -> herr_t {
    if (std::string(name) != ".") static_cast<std::vector<std::string>*>(out)->push_back(std::string("/") + name);
    return 0;
  };
  if (H5Ovisit(file_.get(), H5_INDEX_NAME, H5_ITER_NATIVE, collect, &objects) < 0)
    fail(with_hdf5_message("cannot walk the objects of the file"));
  constexpr std::size_t kMaxObjects = 100000;  // a table has a few hundred
  if (objects.size() > kMaxObjects) fail("more than " + std::to_string(kMaxObjects) + " objects");
  for (const std::string& object : objects) {
    struct Found {
      std::vector<std::string> names;
    } found;
    const auto strings = [](hid_t loc, const char* name, const H5A_info_t*, void* out) -> herr_t {
      const hid_t a = H5Aopen(loc, name, H5P_DEFAULT);
      if (a < 0) return -1;
      const hid_t t = H5Aget_type(a);
      if (t >= 0 && H5Tget_class(t) == H5T_STRING) static_cast<Found*>(out)->names.emplace_back(name);
      if (t >= 0) H5Tclose(t);
      H5Aclose(a);
      return 0;
    };
    Hid obj(H5Oopen(file_.get(), object.c_str(), H5P_DEFAULT), H5Oclose);
    if (obj.get() < 0) fail(with_hdf5_message("cannot open " + object));
    hsize_t index = 0;
    if (H5Aiterate2(obj.get(), H5_INDEX_NAME, H5_ITER_NATIVE, &index, strings, &found) < 0)
      fail(with_hdf5_message("cannot list the attributes of " + object));
    for (const std::string& name : found.names) check_string_attribute(object, name);
  }
}

void Hdf5File::check_string_attribute(const std::string& object, const std::string& name) const {
  const std::string where = "attribute " + name + " of " + object;
  Hid attr(H5Aopen_by_name(file_.get(), object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
           H5Aclose);
  if (attr.get() < 0) fail(with_hdf5_message("cannot open " + where));
  Hid space(H5Aget_space(attr.get()), H5Sclose);
  const hssize_t n = space.get() < 0 ? -1 : H5Sget_simple_extent_npoints(space.get());
  if (n < 0) fail(with_hdf5_message("cannot read the shape of " + where));
  if (n == 1) {  // a single string: the checks and the bounded read of string_attribute
    string_attribute(object, name);
    return;
  }
  // An array of strings (format 2: slot_names, json_members): fixed-length, bounded, stored
  // size = declared size, then one bounded copy.
  Hid type(H5Aget_type(attr.get()), H5Tclose);
  if (type.get() < 0) fail(with_hdf5_message("cannot read the type of " + where));
  if (H5Tis_variable_str(type.get()) != 0)
    fail(where + " is an array of variable-length strings: a checksummed table stores "
                 "fixed-length strings only");
  const std::size_t size = H5Tget_size(type.get());
  const auto count = static_cast<std::size_t>(n);
  if (size == 0 || size > kMaxAttributeBytes || count > kMaxAttributeBytes / size)
    fail(where + " declares " + std::to_string(count) + " strings of " + std::to_string(size) +
         " bytes (limit " + std::to_string(kMaxAttributeBytes) + " bytes)");
  if (H5Aget_storage_size(attr.get()) != size * count)
    fail(where + " declares " + std::to_string(size * count) + " bytes but stores " +
         std::to_string(static_cast<unsigned long long>(H5Aget_storage_size(attr.get()))));
  if (count == 0) return;
  Hid mem(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_cset(mem.get(), H5Tget_cset(type.get()));
  H5Tset_size(mem.get(), size);
  H5Tset_strpad(mem.get(), H5T_STR_NULLPAD);
  std::string bytes(size * count, '\0');
  if (H5Aread(attr.get(), mem.get(), bytes.data()) < 0) fail(with_hdf5_message("cannot read " + where));
}

std::vector<std::string> Hdf5File::members(const std::string& group) const {
  constexpr std::size_t kMaxMembers = 1000;  // /axes holds at most 7
  struct Found {
    std::vector<std::string> names;
    bool too_many = false;
  } found;
  const auto collect = [](hid_t, const char* name, const H5L_info_t*, void* out) -> herr_t {
    auto* f = static_cast<Found*>(out);
    if (f->names.size() >= kMaxMembers) {
      f->too_many = true;
      return 1;  // stop
    }
    f->names.emplace_back(name);
    return 0;
  };
  Hid g(H5Gopen2(file_.get(), group.c_str(), H5P_DEFAULT), H5Gclose);
  if (g.get() < 0) fail(with_hdf5_message("cannot open group " + group));
  if (H5Literate(g.get(), H5_INDEX_NAME, H5_ITER_NATIVE, nullptr, collect, &found) < 0)
    fail(with_hdf5_message("cannot list the members of " + group));
  if (found.too_many) fail("group " + group + " has more than " + std::to_string(kMaxMembers) + " members");
  return found.names;
}

Hid Hdf5File::open_dataset(const std::string& dataset) const {
  if (!exists(dataset)) fail("missing dataset " + dataset);
  Hid d(H5Dopen2(file_.get(), dataset.c_str(), H5P_DEFAULT), H5Dclose);
  if (d.get() < 0) fail(with_hdf5_message("cannot open dataset " + dataset));
  return d;
}

std::vector<hsize_t> Hdf5File::dataset_shape(const std::string& dataset) const {
  const Hid d = open_dataset(dataset);
  Hid space(H5Dget_space(d.get()), H5Sclose);
  const int rank = space.get() < 0 ? -1 : H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) fail(with_hdf5_message("cannot read the shape of " + dataset));
  if (rank > kMaxRank)
    fail("dataset " + dataset + " has " + std::to_string(rank) + " dimensions (limit " +
         std::to_string(kMaxRank) + ")");
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  return dims;
}

bool Hdf5File::checksummed(const std::string& dataset) const {
  const Hid d = open_dataset(dataset);
  Hid dcpl(H5Dget_create_plist(d.get()), H5Pclose);
  if (dcpl.get() < 0) fail(with_hdf5_message("cannot read the properties of " + dataset));
  return H5Pget_filter_by_id2(dcpl.get(), H5Z_FILTER_FLETCHER32, nullptr, nullptr, nullptr, 0,
                              nullptr, nullptr) >= 0;
}

template <typename T>
DatasetValues<T> Hdf5File::read(const std::string& dataset, hid_t mem_type,
                                H5T_class_t type_class, const char* type_name,
                                const std::vector<hsize_t>& expected,
                                const std::string& shape_source, std::size_t max_values,
                                bool allow_scalar) const {
  const Hid d = open_dataset(dataset);
  Hid type(H5Dget_type(d.get()), H5Tclose);
  if (type.get() < 0 || H5Tget_class(type.get()) != type_class)
    fail("dataset " + dataset + " is not of " + type_name + " type");
  const std::size_t element = H5Tget_size(type.get());
  if (element == 0 || element > 8)
    fail("dataset " + dataset + " has " + std::to_string(element) + "-byte elements");
  Hid space(H5Dget_space(d.get()), H5Sclose);
  const int rank = space.get() < 0 ? -1 : H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) fail(with_hdf5_message("cannot read the shape of " + dataset));
  if (rank > kMaxRank)
    fail("dataset " + dataset + " has " + std::to_string(rank) + " dimensions (limit " +
         std::to_string(kMaxRank) + ")");
  DatasetValues<T> out;
  out.dims.resize(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space.get(), out.dims.data(), nullptr);

  // Everything below is checked before the values are allocated.
  if (!expected.empty() && out.dims != expected)
    fail("dataset " + dataset + " has shape " + shape_text(out.dims) + ", but " + shape_source +
         " need " + shape_text(expected));
  if (expected.empty() && rank != 1 && !(allow_scalar && rank == 0))
    fail("dataset " + dataset + " is not 1-D" + (allow_scalar ? " nor a scalar" : "") +
         ", shape " + shape_text(out.dims));
  const auto n = checked_product(out.dims);
  if (!n || *n > max_values)
    fail("dataset " + dataset + " declares shape " + shape_text(out.dims) + ", more than " +
         std::to_string(max_values) + " values");
  const double declared = static_cast<double>(*n) * static_cast<double>(element);
  Hid dcpl(H5Dget_create_plist(d.get()), H5Pclose);
  if (dcpl.get() < 0) fail(with_hdf5_message("cannot read the properties of " + dataset));
  const int n_filters = H5Pget_nfilters(dcpl.get());
  if (n_filters < 0) fail(with_hdf5_message("cannot read the filters of " + dataset));
  bool compressed = false;
  for (int k = 0; k < n_filters; ++k) {
    unsigned flags = 0;
    std::size_t n_values = 0;
    const H5Z_filter_t id = H5Pget_filter2(dcpl.get(), static_cast<unsigned>(k), &flags,
                                           &n_values, nullptr, 0, nullptr, nullptr);
    if (id == H5Z_FILTER_FLETCHER32) out.checksummed = true;
    else if (id == H5Z_FILTER_DEFLATE) compressed = true;
    else if (id != H5Z_FILTER_SHUFFLE)
      fail("dataset " + dataset + " uses HDF5 filter " + std::to_string(id) +
           " (a table uses shuffle, deflate and fletcher32 only)");
  }
  const H5D_layout_t layout = H5Pget_layout(dcpl.get());
  out.compact = layout == H5D_COMPACT;
  if (layout == H5D_CHUNKED) {
    std::vector<hsize_t> chunk(static_cast<std::size_t>(rank));
    if (H5Pget_chunk(dcpl.get(), rank, chunk.data()) != rank)
      fail(with_hdf5_message("cannot read the chunk shape of " + dataset));
    const auto chunk_values = checked_product(chunk);
    if (!chunk_values || *chunk_values > kMaxChunkBytes / element)
      fail("dataset " + dataset + " declares chunks of shape " + shape_text(chunk) +
           ", over " + std::to_string(kMaxChunkBytes) + " bytes");
  }
  const auto stored = static_cast<double>(H5Dget_storage_size(d.get()));
  if (stored > static_cast<double>(file_size_))
    fail("dataset " + dataset + " claims " + std::to_string(static_cast<unsigned long long>(stored)) +
         " bytes of storage, more than the file's " + std::to_string(file_size_));
  // Uncompressed data occupy at least their declared size; compressed data at least
  // 1/kMaxCompressionRatio of it. A shape that the stored bytes cannot hold is corrupt.
  if (*n > 0 && stored * (compressed ? kMaxCompressionRatio : 1.0) < declared)
    fail("dataset " + dataset + " declares shape " + shape_text(out.dims) + " (" +
         std::to_string(static_cast<unsigned long long>(declared)) + " bytes) but stores only " +
         std::to_string(static_cast<unsigned long long>(stored)) + " bytes");
  out.values.resize(*n);
  if (*n > 0 && H5Dread(d.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.values.data()) < 0)
    fail(with_hdf5_message("cannot read dataset " + dataset +
                           " (truncated or corrupt file, or a checksum mismatch?)"));
  return out;
}

DatasetValues<double> Hdf5File::read_doubles(const std::string& dataset,
                                             const std::vector<hsize_t>& expected,
                                             const std::string& shape_source) const {
  return read<double>(dataset, H5T_NATIVE_DOUBLE, H5T_FLOAT, "floating-point", expected,
                      shape_source, std::numeric_limits<std::size_t>::max());
}

DatasetValues<std::uint32_t> Hdf5File::read_uint32(const std::string& dataset,
                                                   const std::vector<hsize_t>& expected,
                                                   const std::string& shape_source) const {
  return read<std::uint32_t>(dataset, H5T_NATIVE_UINT32, H5T_INTEGER, "integer", expected,
                             shape_source, std::numeric_limits<std::size_t>::max());
}

DatasetValues<double> Hdf5File::read_axis(const std::string& dataset, std::size_t max_values,
                                          bool allow_scalar) const {
  return read<double>(dataset, H5T_NATIVE_DOUBLE, H5T_FLOAT, "floating-point", {}, "", max_values,
                      allow_scalar);
}

DatasetValues<std::int32_t> Hdf5File::read_int32(const std::string& dataset,
                                                 std::size_t max_values) const {
  return read<std::int32_t>(dataset, H5T_NATIVE_INT32, H5T_INTEGER, "integer", {}, "",
                            max_values);
}

}  // namespace railtab::lookup::detail
