#include "hdf5_file.hpp"

#include <filesystem>
#include <system_error>

#include "railtab/lookup.hpp"

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

}  // namespace

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
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail("no such file");
  if (H5Fis_hdf5(path.c_str()) <= 0)
    fail(with_hdf5_message("not an HDF5 file (or its superblock is corrupt)"));
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) fail(with_hdf5_message("cannot open (truncated or corrupt file?)"));
  file_ = Hid(f, H5Fclose);
}

void Hdf5File::fail(const std::string& problem) const { throw LoadError(path_, problem); }

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

std::optional<std::string> Hdf5File::string_attribute(const std::string& object,
                                                      const std::string& name) const {
  const std::string where = "attribute " + name + " of " + object;
  if (H5Aexists_by_name(file_.get(), object.c_str(), name.c_str(), H5P_DEFAULT) <= 0)
    return std::nullopt;
  Hid attr(H5Aopen_by_name(file_.get(), object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
           H5Aclose);
  if (attr.get() < 0) fail(with_hdf5_message("cannot open " + where));
  Hid type(H5Aget_type(attr.get()), H5Tclose);
  if (H5Tget_class(type.get()) != H5T_STRING) fail(where + " is not a string");
  Hid space(H5Aget_space(attr.get()), H5Sclose);
  if (H5Sget_simple_extent_npoints(space.get()) != 1) fail(where + " is not a single string");

  Hid mem(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_cset(mem.get(), H5Tget_cset(type.get()));
  if (H5Tis_variable_str(type.get()) > 0) {
    // Variable length (h5py's default): HDF5 allocates, we free.
    H5Tset_size(mem.get(), H5T_VARIABLE);
    char* text = nullptr;
    if (H5Aread(attr.get(), mem.get(), &text) < 0) fail(with_hdf5_message("cannot read " + where));
    std::string out = text ? text : "";
    H5free_memory(text);
    return out;
  }
  const std::size_t size = H5Tget_size(type.get());
  H5Tset_size(mem.get(), size);
  H5Tset_strpad(mem.get(), H5T_STR_NULLPAD);
  std::string out(size, '\0');
  if (H5Aread(attr.get(), mem.get(), out.data()) < 0)
    fail(with_hdf5_message("cannot read " + where));
  out.resize(out.find('\0') == std::string::npos ? size : out.find('\0'));
  return out;
}

template <typename T>
DatasetValues<T> Hdf5File::read(const std::string& dataset, hid_t mem_type,
                                H5T_class_t type_class, const char* type_name) const {
  if (!exists(dataset)) fail("missing dataset " + dataset);
  Hid d(H5Dopen2(file_.get(), dataset.c_str(), H5P_DEFAULT), H5Dclose);
  if (d.get() < 0) fail(with_hdf5_message("cannot open dataset " + dataset));
  Hid type(H5Dget_type(d.get()), H5Tclose);
  if (H5Tget_class(type.get()) != type_class)
    fail("dataset " + dataset + " is not of " + type_name + " type");
  Hid space(H5Dget_space(d.get()), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) fail(with_hdf5_message("cannot read the shape of " + dataset));
  DatasetValues<T> out;
  out.dims.resize(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space.get(), out.dims.data(), nullptr);
  std::size_t n = 1;
  for (hsize_t e : out.dims) n *= static_cast<std::size_t>(e);
  out.values.resize(n);
  if (n > 0 && H5Dread(d.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.values.data()) < 0)
    fail(with_hdf5_message("cannot read dataset " + dataset + " (truncated or corrupt file?)"));
  return out;
}

DatasetValues<double> Hdf5File::read_doubles(const std::string& dataset,
                                             H5T_class_t type_class) const {
  return read<double>(dataset, H5T_NATIVE_DOUBLE, type_class,
                      type_class == H5T_FLOAT ? "floating-point" : "integer");
}

DatasetValues<std::uint32_t> Hdf5File::read_uint32(const std::string& dataset) const {
  return read<std::uint32_t>(dataset, H5T_NATIVE_UINT32, H5T_INTEGER, "integer");
}

DatasetValues<std::int32_t> Hdf5File::read_int32(const std::string& dataset) const {
  return read<std::int32_t>(dataset, H5T_NATIVE_INT32, H5T_INTEGER, "integer");
}

}  // namespace railtab::lookup::detail
