// SPDX-License-Identifier: Apache-2.0
// Writes a Table as an HDF5 file, format 2.x (docs/table-format.md): /axes as dimension scales and
// fixed variables as scalar datasets beside them; every part group holds its own copies of its
// axes as dimension scales (so xarray/netCDF open any group with coordinates); every dataset with
// units, description and axes attributes; status datasets with CF flag_masks/flag_meanings; JSON
// root attributes stored typed (typed_attributes.hpp); chunked + shuffle + deflate above 4 KiB;
// from format 2.2 the creep and wear outputs as rounded float32 (table/storage_precision.hpp);
// integrity as in format 1.1: every array dataset with a Fletcher32 checksum (scalars compact, in
// their checksummed object header), HDF5 1.10 file format (metadata checksums), fixed-length
// string attributes; no object timestamps, so equal inputs (and SOURCE_DATE_EPOCH) give equal bytes. Written through
// an OutputFile (TARGET.tmp.<pid>, locked, synced, renamed only when complete).
#include <hdf5_hl.h>

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <system_error>

#include <nlohmann/json.hpp>

#include "table/h5_util.hpp"
#include "table/interrupt.hpp"
#include "table/loadable_check.hpp"
#include "table/output_file.hpp"
#include "table/storage_precision.hpp"
#include "table/table_io.hpp"
#include "table/typed_attributes.hpp"

namespace railtab {
namespace {

using table_format::is_plain_dimension;
using table_format::kObjectAttributes;

// Compressed above 4 KiB: the default table's one-sided statuses at the jumps (55 KB each, 220 KB
// in all) shrink to 150-330 B; the datasets below (normal part, axes) stay one plain chunk.
constexpr std::size_t kCompressAbove = 4 * 1024;  // datasets above this are compressed [B]
constexpr std::size_t kChunkTarget = 256 * 1024;  // chunk size aimed at [B]
// zlib's default. On the default table: level 4 1,656,771 B, 6 1,626,587 B, 9 1,620,259 B, and
// compressing its datasets takes 0.20 s, 0.36 s and 2.2 s (docs/table-format.md).
constexpr unsigned kDeflateLevel = 6;

// Root attributes whose text is an integer: stored as int64.
constexpr const char* kIntegerAttributes[] = {"shard_y_begin", "shard_y_end", "shard_y_total"};
// Units of the state variables, for fixed ones (scalar datasets /axes/<name>).
constexpr std::pair<const char*, const char*> kStateUnits[] = {{"y", "m"},   {"roll", "rad"}, {"yaw", "rad"},
                                                               {"load", "N"}, {"xi", "1"},     {"eta", "1"},
                                                               {"phi", "rad/m"}};

template <std::size_t N>
bool one_of(const std::string& name, const char* const (&names)[N]) {
  return std::any_of(std::begin(names), std::end(names), [&](const char* n) { return name == n; });
}

// CF flag attributes of a status dataset: every named bit of src/core/status.hpp.
std::pair<std::vector<std::uint32_t>, std::string> status_flags() {
  std::vector<std::uint32_t> masks;
  std::string meanings;
  for (int bit = 0; bit < 32; ++bit) {
    const std::string name = status::describe(1u << bit);
    if (name == "none") continue;
    masks.push_back(1u << bit);
    meanings += (meanings.empty() ? "" : " ") + name;
  }
  return {masks, meanings};
}
std::string join_axes(const std::vector<std::string>& axes) {
  std::string out;
  for (const auto& a : axes) out += (out.empty() ? "" : ",") + a;
  return out;
}


// The float32 image of a float64 output (format 2.2, table/storage_precision.hpp). A finite value
// beyond float32's range is an error, never an infinity in the file.
std::vector<float> to_float32(const std::vector<double>& values, const std::string& file, const std::string& what) {
  std::vector<float> out(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    out[i] = quantize_for_storage(values[i]);
    RAILTAB_CHECK(std::isfinite(out[i]) || !std::isfinite(values[i]),
                  "{}: {}: value {} at flat index {} exceeds the float32 range", file, what, values[i], i);
  }
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
        if (is_plain_dimension(d.axes[i])) continue;  // e.g. the jump list (no coordinate)
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
  // Creates `created` (the output's temporary); every message names `file`, the output the user
  // asked for: the temporary is gone by the time the message is read.
  Writer(const Table& table, std::string created, std::string file, const std::atomic<bool>* cancel)
      : table_(table), created_(std::move(created)), file_(std::move(file)), cancel_(cancel),
        float32_(table_stores_float32(table)) {}

  void write() {
    h5::Id fcpl(h5::check_id(H5Pcreate(H5P_FILE_CREATE), file_, "file creation properties"), H5Pclose);
    track_order(fcpl);
    check(H5Pset_attr_creation_order(fcpl, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED), "attribute order");
    check(H5Pset_obj_track_times(fcpl, false), "no timestamps");
    // Integrity (docs/table-format.md, "Integrity"): the HDF5 1.10 file format checksums every
    // metadata block (superblock, object headers with their attributes, chunk indexes).
    h5::Id fapl(h5::check_id(H5Pcreate(H5P_FILE_ACCESS), file_, "file access properties"), H5Pclose);
    check(H5Pset_libver_bounds(fapl, H5F_LIBVER_V110, H5F_LIBVER_LATEST), "file format version");
    hid_t raw = H5Fcreate(created_.c_str(), H5F_ACC_TRUNC, fcpl, fapl);
    h5::Id file(h5::check_id(raw, file_, "create file"), H5Fclose);
    {
      for (const auto& [name, value] : table_.attributes) write_root_attribute(file, name, value);
      write_axes(file);
      for (const TableGroup& group : table_.groups) {
        h5::Id g = open_group(file, group.path);
        const hid_t parent = g.get() == H5I_INVALID_HID ? file.get() : g.get();
        write_coordinates(parent, group);
        for (const TableDataset& d : group.datasets) {
          poll_cancel();
          write_dataset(parent, group.path, d);
        }
        local_scales_.clear();
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
    check(H5Pset_obj_track_times(gcpl, false), "no timestamps");
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

  // Text attributes as the format stores them: JSON objects as groups, integers as int64,
  // fixed_axes as scalar datasets in /axes (write_axes), everything else as strings.
  void write_root_attribute(hid_t file, const std::string& name, const std::string& value) {
    if (name == "fixed_axes") return;
    if (one_of(name, kObjectAttributes)) {
      const nlohmann::json j = nlohmann::json::parse(value, nullptr, false);
      if (j.is_object()) {
        h5::Id gcpl(h5::check_id(H5Pcreate(H5P_GROUP_CREATE), file_, "group properties"), H5Pclose);
        check(H5Pset_obj_track_times(gcpl, false), "no timestamps");
        h5::Id g = make_group(file, name);
        h5::write_json_object(g, j, file_, gcpl);
        return;
      }
    }
    if (one_of(name, kIntegerAttributes)) {
      std::int64_t n = 0;
      const auto [ptr, ec] = std::from_chars(value.data(), value.data() + value.size(), n);
      RAILTAB_CHECK(ec == std::errc() && ptr == value.data() + value.size(), "{}: attribute {} = '{}' is not an integer",
                    file_, name, value);
      h5::write_int64_attribute(file, name, n, file_);
      return;
    }
    h5::write_string_attribute(file, name, value, file_);
  }

  // A 1-D axis dataset, made a dimension scale, in `group` (/axes, or a part group's copy).
  h5::Id write_axis(hid_t group, const TableAxis& axis) {
    std::string what = "write axis " + axis.name;
    hsize_t n = axis.values.size();
    h5::Id space(h5::check_id(H5Screate_simple(1, &n, nullptr), file_, what), H5Sclose);
    hid_t type = axis.integer ? H5T_STD_I32LE : H5T_IEEE_F64LE;
    h5::Id dcpl = checksummed_layout({n}, what);
    h5::Id ds(h5::check_id(H5Dcreate2(group, axis.name.c_str(), type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT),
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
    if (axis.name == "slot") {
      // Slot meaning stored, not only described: names and the CF flag_values/flag_meanings.
      std::vector<std::string> names;
      std::vector<std::int32_t> values;
      for (std::size_t i = 0; i < axis.values.size(); ++i) {
        names.push_back(i == 0 ? "tread" : i == 1 ? "flange" : fmt::format("slot{}", i));  // = lookup::slot_name
        values.push_back(static_cast<std::int32_t>(i));
      }
      std::string meanings;
      for (const std::string& name : names) meanings += (meanings.empty() ? "" : " ") + name;
      h5::write_string_array_attribute(ds, "slot_names", names, file_);
      h5::write_int32_array_attribute(ds, "flag_values", values, file_);
      h5::write_string_attribute(ds, "flag_meanings", meanings, file_);
    }
    return ds;
  }

  // A fixed state variable: a scalar float64 dataset with units.
  void write_fixed(hid_t group, const std::string& name, double value) {
    std::string what = "write fixed variable " + name;
    h5::Id space(h5::check_id(H5Screate(H5S_SCALAR), file_, what), H5Sclose);
    h5::Id dcpl = checksummed_layout({}, what);
    h5::Id ds(h5::check_id(H5Dcreate2(group, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT),
                           file_, what),
              H5Dclose);
    check(H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &value), what);
    const char* units = "1";
    for (const auto& [state, u] : kStateUnits)
      if (name == state) units = u;
    h5::write_string_attribute(ds, "units", units, file_);
    h5::write_string_attribute(ds, "description", "fixed value: " + name + " is not tabulated", file_);
  }

  // Fixed variables of the root attribute fixed_axes (JSON text in memory), in its order.
  void parse_fixed() {
    const std::string* text = table_.attribute("fixed_axes");
    if (!text) return;
    const nlohmann::json j = nlohmann::json::parse(*text, nullptr, false);
    RAILTAB_CHECK(j.is_object(), "{}: fixed_axes is not a JSON object: {}", file_, *text);
    for (const auto& [name, value] : j.items()) {
      if (value.is_number()) {
        fixed_.emplace_back(name, value.get<double>());
      } else {
        RAILTAB_CHECK(name == "roll" && value == "equilibrium", "{}: fixed_axes: '{}' must be a number", file_, name);
        roll_equilibrium_ = true;
      }
    }
  }

  void write_axes(hid_t file) {
    h5::Id group = make_group(file, "axes");
    for (const TableAxis& axis : table_.axes) scales_.emplace(axis.name, write_axis(group, axis));
    parse_fixed();
    for (const auto& [name, value] : fixed_) write_fixed(group, name, value);
    // Roll following the kinematic equilibrium is neither an axis nor fixed (/equilibrium_roll).
    if (roll_equilibrium_) h5::write_string_attribute(file, "roll_mode", "equilibrium", file_);
  }

  // The group's own copies of the axes its datasets use (dimension scales, attached instead of
  // /axes: netCDF and xarray find coordinates only in the group itself or its ancestors), and the
  // fixed variables as scalars, named in each dataset's CF `coordinates` attribute.
  void write_coordinates(hid_t group, const TableGroup& g) {
    for (const TableDataset& d : g.datasets) {
      for (const std::string& name : d.axes) {
        if (local_scales_.count(name)) continue;
        if (is_plain_dimension(name)) {  // an index coordinate 0..n-1 (netCDF needs a scale per dimension)
          TableAxis index{name, "1", name + " index", {}, true};
          for (std::size_t k = 0; k < d.shape[static_cast<std::size_t>(&name - d.axes.data())]; ++k)
            index.values.push_back(static_cast<double>(k));
          local_scales_.emplace(name, write_axis(group, index));
          continue;
        }
        local_scales_.emplace(name, write_axis(group, *table_.axis(name)));
      }
    }
    for (const auto& [name, value] : fixed_) write_fixed(group, name, value);
    coordinates_.clear();
    for (const auto& [name, value] : fixed_) coordinates_ += (coordinates_.empty() ? "" : " ") + name;
    write_equilibrium_roll(group, g);
  }

  // With roll following the equilibrium, a part group over y also gets roll(y): a copy of
  // /equilibrium_roll named `roll` on the group's y, listed in `coordinates` (xarray shows it).
  void write_equilibrium_roll(hid_t group, const TableGroup& g) {
    const TableGroup* root = table_.group("");
    const TableDataset* roll = root ? root->find("equilibrium_roll") : nullptr;
    if (!roll_equilibrium_ || g.path.empty() || !roll || roll->axes != std::vector<std::string>{"y"} ||
        !local_scales_.count("y")) {
      return;
    }
    TableDataset copy = *roll;
    copy.name = "roll";
    write_dataset(group, g.path, copy, /*coordinate=*/true);
    coordinates_ += (coordinates_.empty() ? "" : " ") + std::string("roll");
  }

  // Creation properties of a dataset without timestamps.
  h5::Id untimed_dcpl(const std::string& what) const {
    h5::Id dcpl(h5::check_id(H5Pcreate(H5P_DATASET_CREATE), file_, what), H5Pclose);
    check(H5Pset_obj_track_times(dcpl, false), what + " (no timestamps)");
    return dcpl;
  }

  // Creation properties of an uncompressed dataset with its checksum: one chunk holding it all,
  // with HDF5's Fletcher32 filter (a filter needs a chunked layout). A scalar cannot be
  // chunked: compact instead, its bytes inside the (checksummed) object header.
  h5::Id checksummed_layout(const std::vector<hsize_t>& dims, const std::string& what) const {
    h5::Id dcpl = untimed_dcpl(what);
    if (dims.empty()) {
      check(H5Pset_layout(dcpl, H5D_COMPACT), what + " (compact)");
      return dcpl;
    }
    check(H5Pset_chunk(dcpl, static_cast<int>(dims.size()), dims.data()), what + " (chunk)");
    check(H5Pset_fletcher32(dcpl), what + " (checksum)");
    return dcpl;
  }

  // `coordinate`: a coordinate copy (roll(y)), which names no further coordinates itself.
  void write_dataset(hid_t parent, const std::string& group, const TableDataset& d, bool coordinate = false) {
    std::string what = fmt::format("write dataset {}/{}", group, d.name);
    std::vector<hsize_t> dims(d.shape.begin(), d.shape.end());
    h5::Id space(h5::check_id(dims.empty() ? H5Screate(H5S_SCALAR)
                                           : H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
                              file_, what),
                 H5Sclose);
    const bool single = float32_ && !coordinate && stored_as_float32(group, d);
    std::size_t element = d.is_status ? sizeof(std::uint32_t) : single ? sizeof(float) : sizeof(double);
    const bool compress = !dims.empty() && d.size() * element > kCompressAbove && H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0;
    h5::Id dcpl = compress ? untimed_dcpl(what) : checksummed_layout(dims, what);
    if (compress) {
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
      check(H5Pset_fletcher32(dcpl), what + " (checksum)");
    }
    hid_t file_type = d.is_status ? H5T_STD_U32LE : single ? H5T_IEEE_F32LE : H5T_IEEE_F64LE;
    h5::Id ds(h5::check_id(H5Dcreate2(parent, d.name.c_str(), file_type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT),
                           file_, what),
              H5Dclose);
    if (d.is_status) {
      check(H5Dwrite(ds, H5T_NATIVE_UINT32, H5S_ALL, H5S_ALL, H5P_DEFAULT, d.status.data()), what);
    } else if (single) {  // rounded here, not by HDF5's conversion: one rounding rule, checked range
      const std::vector<float> rounded = to_float32(d.values, file_, what);
      check(H5Dwrite(ds, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, rounded.data()), what);
      h5::write_int32_attribute(ds, kQuantizeAttribute, kStoredSignificandBits, file_);
    } else {
      check(H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, d.values.data()), what);
    }
    h5::write_string_attribute(ds, "units", d.units, file_);
    h5::write_string_attribute(ds, "description", d.description, file_);
    h5::write_string_attribute(ds, "axes", join_axes(d.axes), file_);
    if (!coordinate && !coordinates_.empty()) h5::write_string_attribute(ds, "coordinates", coordinates_, file_);
    if (d.is_status && d.name == "status") {  // other uint32 datasets (jump kinds) are not status bits
      static const auto flags = status_flags();
      h5::write_uint32_array_attribute(ds, "flag_masks", flags.first, file_);
      h5::write_string_attribute(ds, "flag_meanings", flags.second, file_);
    }
    for (std::size_t i = 0; i < d.axes.size(); ++i) {
      check(H5DSattach_scale(ds, local_scales_.at(d.axes[i]), static_cast<unsigned>(i)),
            fmt::format("{} (attach scale {})", what, d.axes[i]));
    }
  }

  const Table& table_;
  std::string created_;  // the file H5Fcreate makes (the temporary)
  std::string file_;
  const std::atomic<bool>* cancel_;
  bool float32_;                                // format >= 2.2: creep and wear outputs as float32
  std::map<std::string, h5::Id> scales_;        // open /axes datasets by name
  std::map<std::string, h5::Id> local_scales_;  // the current group's axis copies, for H5DSattach_scale
  std::vector<std::pair<std::string, double>> fixed_;  // fixed variables (from fixed_axes)
  bool roll_equilibrium_ = false;               // fixed_axes says "roll":"equilibrium"
  std::string coordinates_;                     // CF `coordinates` of the current group's datasets
};

}  // namespace

void write_table(const Table& table, const std::filesystem::path& target, const std::atomic<bool>* cancel,
                 const std::vector<std::filesystem::path>& inputs, WrittenCheck check) {
  h5::silence_errors();
  validate(table, target.string());
  OutputFile file(target, inputs);  // removes its temporary unless committed
  Writer(table, file.temporary().string(), target.string(), cancel).write();
  // A shard of a single y node is no table the lookup can load (an axis needs 2 nodes): merge
  // checks its values, and the lookup the merged table.
  const TableAxis* y = table.axis("y");
  const bool shard = table.attribute("shard") != nullptr;
  if (check == WrittenCheck::lookup && !(shard && y && y->values.size() < 2)) check_loadable(file.temporary(), target, shard);
  file.commit();
}

}  // namespace railtab
