// Writes a Table as an HDF5 file, format 1.0: /axes as dimension scales, every dataset with units,
// description and axes attributes and its dimensions attached to the scales, chunked + shuffle +
// deflate above 64 KiB. Written through an OutputFile (TARGET.tmp.<pid>, synced, renamed when complete).
#include <hdf5_hl.h>

#include <fmt/format.h>

#include <map>
#include <system_error>

#include "table/h5_util.hpp"
#include "table/interrupt.hpp"
#include "table/output_file.hpp"
#include "table/table_io.hpp"

namespace railtab {
namespace {

constexpr std::size_t kCompressAbove = 64 * 1024;  // datasets above this are chunked [B]
constexpr std::size_t kChunkTarget = 256 * 1024;   // chunk size aimed at [B]
constexpr unsigned kDeflateLevel = 4;

std::string join_axes(const std::vector<std::string>& axes) {
  std::string out;
  for (const auto& a : axes) out += (out.empty() ? "" : ",") + a;
  return out;
}

// The table must be consistent before anything touches the disk.
void validate(const Table& table, const std::string& file) {
  for (const TableAxis& axis : table.axes) {
    RAILTAB_CHECK(!axis.values.empty(), "{}: axis '{}' is empty", file, axis.name);
    for (std::size_t i = 1; i < axis.values.size(); ++i) {
      RAILTAB_CHECK(axis.values[i] > axis.values[i - 1], "{}: axis '{}' is not strictly increasing", file,
                    axis.name);
    }
  }
  for (const TableGroup& group : table.groups) {
    for (const TableDataset& d : group.datasets) {
      RAILTAB_CHECK(d.axes.size() == d.shape.size(), "{}: {}/{}: axes and shape differ in rank", file,
                    group.path, d.name);
      for (std::size_t i = 0; i < d.axes.size(); ++i) {
        const TableAxis* axis = table.axis(d.axes[i]);
        RAILTAB_CHECK(axis, "{}: {}/{}: unknown axis '{}'", file, group.path, d.name, d.axes[i]);
        RAILTAB_CHECK(axis->values.size() == d.shape[i], "{}: {}/{}: dimension {} has {} entries, axis '{}' {}",
                      file, group.path, d.name, i, d.shape[i], d.axes[i], axis->values.size());
      }
      std::size_t stored = d.is_status ? d.status.size() : d.values.size();
      RAILTAB_CHECK(stored == d.size(), "{}: {}/{}: holds {} values, shape needs {}", file, group.path, d.name,
                    stored, d.size());
    }
  }
}

class Writer {
 public:
  Writer(const Table& table, std::string file, const std::atomic<bool>* cancel)
      : table_(table), file_(std::move(file)), cancel_(cancel) {}

  void write() {
    h5::Id fcpl(h5::check_id(H5Pcreate(H5P_FILE_CREATE), file_, "file creation properties"), H5Pclose);
    track_order(fcpl);
    check(H5Pset_attr_creation_order(fcpl, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED), "attribute order");
    hid_t raw = H5Fcreate(file_.c_str(), H5F_ACC_TRUNC, fcpl, H5P_DEFAULT);
    h5::Id file(h5::check_id(raw, file_, "create file"), H5Fclose);
    {
      for (const auto& [name, value] : table_.attributes) h5::write_string_attribute(file, name, value, file_);
      write_axes(file);
      for (const TableGroup& group : table_.groups) {
        h5::Id g = open_group(file, group.path);
        for (const TableDataset& d : group.datasets) {
          poll_cancel();
          write_dataset(g.get() == H5I_INVALID_HID ? file.get() : g.get(), group.path, d);
        }
      }
      scales_.clear();
    }
    check(H5Fclose(file.release()), "close file");
  }

 private:
  void check(long long status, const std::string& what) const { h5::check(status, file_, what); }

  void poll_cancel() const {
    if (cancel_ && cancel_->load()) throw Interrupted(fmt::format("{}: writing interrupted", file_));
  }

  void track_order(hid_t plist) const {
    check(H5Pset_link_creation_order(plist, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED), "link order");
  }

  h5::Id make_group(hid_t parent, const std::string& name) {
    if (H5Lexists(parent, name.c_str(), H5P_DEFAULT) > 0) {
      return h5::Id(h5::check_id(H5Gopen2(parent, name.c_str(), H5P_DEFAULT), file_, "open group " + name),
                    H5Gclose);
    }
    h5::Id gcpl(h5::check_id(H5Pcreate(H5P_GROUP_CREATE), file_, "group properties"), H5Pclose);
    track_order(gcpl);
    check(H5Pset_attr_creation_order(gcpl, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED), "attribute order");
    return h5::Id(h5::check_id(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, gcpl, H5P_DEFAULT), file_,
                               "create group " + name),
                  H5Gclose);
  }

  // "left/geometry" -> /left/geometry (created as needed); "" -> invalid id meaning the root.
  h5::Id open_group(hid_t file, const std::string& path) {
    h5::Id current;
    hid_t parent = file;
    std::size_t start = 0;
    while (start < path.size()) {
      std::size_t slash = path.find('/', start);
      std::string part = path.substr(start, slash == std::string::npos ? std::string::npos : slash - start);
      current = make_group(parent, part);
      parent = current.get();
      start = slash == std::string::npos ? path.size() : slash + 1;
    }
    return current;
  }

  void write_axes(hid_t file) {
    h5::Id group = make_group(file, "axes");
    for (const TableAxis& axis : table_.axes) {
      std::string what = "write axis " + axis.name;
      hsize_t n = axis.values.size();
      h5::Id space(h5::check_id(H5Screate_simple(1, &n, nullptr), file_, what), H5Sclose);
      hid_t type = axis.integer ? H5T_STD_I32LE : H5T_IEEE_F64LE;
      h5::Id ds(h5::check_id(H5Dcreate2(group, axis.name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT,
                                        H5P_DEFAULT),
                             file_, what),
                H5Dclose);
      if (axis.integer) {
        std::vector<int> data(axis.values.begin(), axis.values.end());
        check(H5Dwrite(ds, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()), what);
      } else {
        check(H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, axis.values.data()), what);
      }
      check(H5DSset_scale(ds, axis.name.c_str()), what + " (dimension scale)");
      h5::write_string_attribute(ds, "units", axis.units, file_);
      h5::write_string_attribute(ds, "description", axis.description, file_);
      scales_.emplace(axis.name, std::move(ds));
    }
  }

  void write_dataset(hid_t parent, const std::string& group, const TableDataset& d) {
    std::string what = fmt::format("write dataset {}/{}", group, d.name);
    std::vector<hsize_t> dims(d.shape.begin(), d.shape.end());
    h5::Id space(h5::check_id(dims.empty() ? H5Screate(H5S_SCALAR)
                                           : H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
                              file_, what),
                 H5Sclose);
    h5::Id dcpl(h5::check_id(H5Pcreate(H5P_DATASET_CREATE), file_, what), H5Pclose);
    std::size_t element = d.is_status ? sizeof(std::uint32_t) : sizeof(double);
    if (!dims.empty() && d.size() * element > kCompressAbove && H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0) {
      // Chunks span the fast dimensions whole; the slow ones are halved until a chunk fits.
      std::vector<hsize_t> chunk = dims;
      auto bytes = [&] {
        std::size_t b = element;
        for (hsize_t c : chunk) b *= c;
        return b;
      };
      for (std::size_t i = 0; i < chunk.size() && bytes() > kChunkTarget; ++i) {
        while (chunk[i] > 1 && bytes() > kChunkTarget) chunk[i] = (chunk[i] + 1) / 2;
      }
      check(H5Pset_chunk(dcpl, static_cast<int>(chunk.size()), chunk.data()), what + " (chunk)");
      check(H5Pset_shuffle(dcpl), what + " (shuffle)");
      check(H5Pset_deflate(dcpl, kDeflateLevel), what + " (deflate)");
    }
    hid_t file_type = d.is_status ? H5T_STD_U32LE : H5T_IEEE_F64LE;
    h5::Id ds(h5::check_id(H5Dcreate2(parent, d.name.c_str(), file_type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT),
                           file_, what),
              H5Dclose);
    if (d.is_status) {
      check(H5Dwrite(ds, H5T_NATIVE_UINT32, H5S_ALL, H5S_ALL, H5P_DEFAULT, d.status.data()), what);
    } else {
      check(H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, d.values.data()), what);
    }
    h5::write_string_attribute(ds, "units", d.units, file_);
    h5::write_string_attribute(ds, "description", d.description, file_);
    h5::write_string_attribute(ds, "axes", join_axes(d.axes), file_);
    for (std::size_t i = 0; i < d.axes.size(); ++i) {
      check(H5DSattach_scale(ds, scales_.at(d.axes[i]), static_cast<unsigned>(i)),
            fmt::format("{} (attach scale {})", what, d.axes[i]));
    }
  }

  const Table& table_;
  std::string file_;
  const std::atomic<bool>* cancel_;
  std::map<std::string, h5::Id> scales_;  // open axis datasets by name, for H5DSattach_scale
};

}  // namespace

void write_table(const Table& table, const std::filesystem::path& target, const std::atomic<bool>* cancel,
                 const std::vector<std::filesystem::path>& inputs) {
  h5::silence_errors();
  validate(table, target.string());
  OutputFile file(target, inputs);  // removes its temporary unless committed
  Writer(table, file.temporary().string(), cancel).write();
  file.commit();
}

}  // namespace railtab
