// SPDX-License-Identifier: Apache-2.0
// Reads a format-1.x or 2.x table file into a Table, checking everything a consumer relies on, so
// that a damaged or foreign file fails here with the file name and the problem, not later with
// garbage. Format 2's typed attributes come back as the text the Table holds (table_writer.cpp).
#include <hdf5_hl.h>
#include <unistd.h>

#include <fmt/format.h>

#include <algorithm>
#include <charconv>

#include <nlohmann/json.hpp>

#include "core/check.hpp"
#include "core/input_files.hpp"
#include "lookup_vlen/vlen_string.hpp"
#include "table/h5_util.hpp"
#include "table/table_io.hpp"
#include "table/typed_attributes.hpp"

namespace railtab {
namespace {

using table_format::is_plain_dimension;
using table_format::kObjectAttributes;

// Names of the members (links or attributes) of an object, in creation order when the file tracks
// it, else alphabetically (files written by other tools).
herr_t collect_link(hid_t, const char* name, const H5L_info_t*, void* data) {
  static_cast<std::vector<std::string>*>(data)->emplace_back(name);
  return 0;
}
herr_t collect_attribute(hid_t, const char* name, const H5A_info_t*, void* data) {
  static_cast<std::vector<std::string>*>(data)->emplace_back(name);
  return 0;
}

std::vector<std::string> links(hid_t group, const std::string& file, const std::string& where) {
  std::vector<std::string> names;
  if (H5Literate(group, H5_INDEX_CRT_ORDER, H5_ITER_INC, nullptr, collect_link, &names) < 0) {
    names.clear();
    h5::last_error();  // clear the stack of the failed attempt
    h5::check(H5Literate(group, H5_INDEX_NAME, H5_ITER_INC, nullptr, collect_link, &names), file,
              "list members of " + where);
  }
  return names;
}

std::vector<std::string> attribute_names(hid_t object, const std::string& file) {
  std::vector<std::string> names;
  if (H5Aiterate2(object, H5_INDEX_CRT_ORDER, H5_ITER_INC, nullptr, collect_attribute, &names) < 0) {
    names.clear();
    h5::last_error();
    h5::check(H5Aiterate2(object, H5_INDEX_NAME, H5_ITER_INC, nullptr, collect_attribute, &names), file,
              "list attributes");
  }
  return names;
}

std::vector<std::string> split_axes(const std::string& text) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= text.size() && !text.empty()) {
    std::size_t comma = text.find(',', start);
    out.push_back(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

// Format 2 names: the order the sweep writes root attributes in (the reader restores it), and the
// coordinate copies in part groups (not outputs).
constexpr const char* kAttributeOrder[] = {"format_version", "railtab_version", "git_commit", "created",
                                          "scene", "scene_name", "models", "fixed_axes", "shard",
                                          "shard_y_begin", "shard_y_end", "shard_y_total", "shard_jumps",
                                          "accuracy_targets", "accuracy_achieved"};
constexpr const char* kCoordinateNames[] = {"y", "roll", "yaw", "load", "xi", "eta", "phi", "slot"};

// uint32 datasets: status bits and the jump kinds (<wheel>_kind).
bool is_uint32_dataset(const std::string& name) {
  return name == "status" || (name.size() > 5 && name.compare(name.size() - 5, 5, "_kind") == 0);
}

bool is_coordinate(const std::string& name) {
  return std::any_of(std::begin(kCoordinateNames), std::end(kCoordinateNames), [&](const char* n) { return name == n; });
}

// Known attributes first, in the sweep's order, then the others in file order.
void restore_order(std::vector<std::pair<std::string, std::string>>& attributes) {
  auto rank = [](const std::string& name) {
    const auto* it = std::find_if(std::begin(kAttributeOrder), std::end(kAttributeOrder),
                                  [&](const char* n) { return name == n; });
    return static_cast<std::size_t>(it - std::begin(kAttributeOrder));
  };
  std::stable_sort(attributes.begin(), attributes.end(),
                   [&](const auto& a, const auto& b) { return rank(a.first) < rank(b.first); });
}

class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  Table read() {
    // A regular file only (a FIFO would block every reader below), recorded as an input of the run.
    ::close(open_input_file(file_, "table file"));
    // Metadata without checksums are refused before libhdf5 parses them (lookup/src/vlen_string.hpp).
    const std::string unchecked = lookup::detail::unchecksummed_metadata_problem(file_);
    RAILTAB_CHECK(unchecked.empty(), "{}: {}", file_, unchecked);
    htri_t is_hdf5 = H5Fis_hdf5(file_.c_str());
    h5::last_error();
    RAILTAB_CHECK(is_hdf5 > 0, "{}: not an HDF5 file (or its header is damaged)", file_);
    h5::Id file(h5::check_id(H5Fopen(file_.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), file_,
                             "cannot open (truncated or damaged file?)"),
                H5Fclose);
    Table table;
    read_version(file);
    for (const std::string& name : attribute_names(file, file_)) {
      h5::Id attr(h5::check_id(H5Aopen(file, name.c_str(), H5P_DEFAULT), file_, "open attribute " + name),
                  H5Aclose);
      h5::Id type(h5::check_id(H5Aget_type(attr), file_, "attribute type " + name), H5Tclose);
      // Format 1 has string attributes only; format 2 also numbers (as text in the Table).
      if (name != "roll_mode") table.attributes.emplace_back(name, h5::read_attribute_as_text(file, name, file_));
    }
    for (const char* name : kObjectAttributes) {  // format 2: JSON objects as groups
      if (H5Lexists(file, name, H5P_DEFAULT) <= 0) continue;
      h5::Id g(h5::check_id(H5Gopen2(file, name, H5P_DEFAULT), file_, fmt::format("open /{}", name)), H5Gclose);
      table.attributes.emplace_back(name, h5::read_json_object(g, file_).dump());
    }

    RAILTAB_CHECK(H5Lexists(file, "axes", H5P_DEFAULT) > 0, "{}: missing group /axes", file_);
    h5::Id axes(h5::check_id(H5Gopen2(file, "axes", H5P_DEFAULT), file_, "open /axes"), H5Gclose);
    nlohmann::json fixed = nlohmann::json::object();
    for (const std::string& name : links(axes, file_, "/axes")) {
      if (is_scalar(axes, name)) {  // format 2: a fixed variable
        fixed[name] = read_fixed(axes, name);
      } else {
        table.axes.push_back(read_axis(axes, name));
      }
    }
    RAILTAB_CHECK(table.axis("slot"), "{}: missing axis /axes/slot", file_);
    if (!table.attribute("fixed_axes")) {  // format 2: from the scalars and roll_mode
      if (h5::has_attribute(file, "roll_mode")) fixed["roll"] = h5::read_string_attribute(file, "roll_mode", file_);
      table.attributes.emplace_back("fixed_axes", fixed.dump());
    }
    restore_order(table.attributes);

    for (const std::string& name : links(file, file_, "/")) {
      if (name == "axes" || is_coordinate(name)) continue;  // format 2: root copies of axes
      h5::Id object(h5::check_id(H5Oopen(file, name.c_str(), H5P_DEFAULT), file_, "open /" + name), H5Oclose);
      if (H5Iget_type(object) == H5I_DATASET) {
        if (!table.group("")) table.groups.push_back(TableGroup{"", {}});
        table.group("")->datasets.push_back(read_dataset(table, file, "", name));
      }
    }
    for (const char* wheel : {"left", "right"}) {
      RAILTAB_CHECK(H5Lexists(file, wheel, H5P_DEFAULT) > 0, "{}: missing group /{}", file_, wheel);
      h5::Id w(h5::check_id(H5Gopen2(file, wheel, H5P_DEFAULT), file_, fmt::format("open /{}", wheel)), H5Gclose);
      std::vector<std::string> parts = links(w, file_, std::string("/") + wheel);
      for (const char* required : {"geometry", "normal"}) {
        RAILTAB_CHECK(std::find(parts.begin(), parts.end(), std::string(required)) != parts.end(), "{}: missing group /{}/{}",
                      file_, wheel, required);
      }
      for (const std::string& part : parts) {
        std::string path = std::string(wheel) + "/" + part;
        h5::Id g(h5::check_id(H5Gopen2(w, part.c_str(), H5P_DEFAULT), file_, "open /" + path), H5Gclose);
        TableGroup group{path, {}};
        for (const std::string& name : links(g, file_, "/" + path)) {
          if (is_coordinate(name)) continue;  // format 2: the group's copies of its axes
          group.datasets.push_back(read_dataset(table, g, path, name));
        }
        for (const std::string& required : required_outputs(part)) {
          // Format 2.1 normalised creep part: fx, fy, mz are stored as <name>_normalised.
          RAILTAB_CHECK(group.find(required) || (table.attribute("creep_map") && group.find(required + "_normalised")),
                        "{}: missing dataset /{}/{}", file_, path, required);
        }
        table.groups.push_back(std::move(group));
      }
    }
    for (const char* root : {kJumpGroup, kShardJumpGroup, kErrorMapGroup}) {
      if (H5Lexists(file, root, H5P_DEFAULT) > 0) read_tree(table, file, root);
    }
    return table;
  }

 private:
  void read_version(hid_t file) const {
    RAILTAB_CHECK(h5::has_attribute(file, "format_version"),
                  "{}: not a railtab table (no format_version attribute)", file_);
    std::string version = h5::read_string_attribute(file, "format_version", file_);
    int major = -1;
    auto dot = version.find('.');
    auto [end, ec] = std::from_chars(version.data(), version.data() + (dot == std::string::npos ? version.size() : dot), major);
    RAILTAB_CHECK(ec == std::errc() && dot != std::string::npos, "{}: malformed format_version \"{}\"", file_, version);
    RAILTAB_CHECK(major >= 1 && major <= kTableFormatMajor,
                  "{}: table format version {} is not supported (this railtab reads 1.x to {}.x); regenerate the "
                  "table or use a matching railtab",
                  file_, version, kTableFormatMajor);
  }

  // The group `path` (under `parent`) and its subgroups, depth first, each group's datasets
  // before its subgroups (the order the generator writes /jumps and /jumps/<wheel>/<part> in).
  void read_tree(Table& table, hid_t parent, const std::string& path) const {
    const std::string name = path.substr(path.rfind('/') + 1);
    h5::Id g(h5::check_id(H5Gopen2(parent, name.c_str(), H5P_DEFAULT), file_, "open /" + path), H5Gclose);
    TableGroup group{path, {}};
    std::vector<std::string> subgroups;
    for (const std::string& member : links(g, file_, "/" + path)) {
      if (is_coordinate(member) || is_plain_dimension(member)) continue;  // the group's copies of its axes
      h5::Id object(h5::check_id(H5Oopen(g, member.c_str(), H5P_DEFAULT), file_, "open /" + path + "/" + member),
                    H5Oclose);
      if (H5Iget_type(object) == H5I_GROUP) subgroups.push_back(member);
      else group.datasets.push_back(read_dataset(table, g, path, member));
    }
    if (!group.datasets.empty()) table.groups.push_back(std::move(group));
    for (const std::string& sub : subgroups) read_tree(table, g, path + "/" + sub);
  }

  bool is_scalar(hid_t group, const std::string& name) const {
    h5::Id ds(h5::check_id(H5Dopen2(group, name.c_str(), H5P_DEFAULT), file_, "open /axes/" + name), H5Dclose);
    h5::Id space(h5::check_id(H5Dget_space(ds), file_, "/axes/" + name), H5Sclose);
    return H5Sget_simple_extent_ndims(space) == 0;
  }

  double read_fixed(hid_t group, const std::string& name) const {
    h5::Id ds(h5::check_id(H5Dopen2(group, name.c_str(), H5P_DEFAULT), file_, "open /axes/" + name), H5Dclose);
    double value = 0.0;
    h5::check(H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &value), file_, "read /axes/" + name);
    return value;
  }

  std::string required_attribute(hid_t object, const std::string& where, const std::string& name) const {
    RAILTAB_CHECK(h5::has_attribute(object, name), "{}: {}: missing attribute '{}'", file_, where, name);
    return h5::read_string_attribute(object, name, file_);
  }

  TableAxis read_axis(hid_t group, const std::string& name) const {
    std::string where = "/axes/" + name;
    h5::Id ds(h5::check_id(H5Dopen2(group, name.c_str(), H5P_DEFAULT), file_, "open " + where), H5Dclose);
    h5::Id space(h5::check_id(H5Dget_space(ds), file_, where), H5Sclose);
    RAILTAB_CHECK(H5Sget_simple_extent_ndims(space) == 1, "{}: {}: an axis must be 1-D", file_, where);
    hsize_t n = 0;
    H5Sget_simple_extent_dims(space, &n, nullptr);
    RAILTAB_CHECK(n >= 1, "{}: {}: empty axis", file_, where);
    TableAxis axis;
    axis.name = name;
    h5::Id type(h5::check_id(H5Dget_type(ds), file_, where), H5Tclose);
    axis.integer = H5Tget_class(type) == H5T_INTEGER;
    axis.values.resize(n);
    h5::check(H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, axis.values.data()), file_,
              "read " + where + " (truncated file?)");
    for (std::size_t i = 1; i < axis.values.size(); ++i) {
      RAILTAB_CHECK(axis.values[i] > axis.values[i - 1], "{}: {}: not strictly increasing", file_, where);
    }
    axis.units = required_attribute(ds, where, "units");
    axis.description = required_attribute(ds, where, "description");
    return axis;
  }

  TableDataset read_dataset(const Table& table, hid_t group, const std::string& path, const std::string& name) const {
    std::string where = "/" + (path.empty() ? name : path + "/" + name);
    h5::Id ds(h5::check_id(H5Dopen2(group, name.c_str(), H5P_DEFAULT), file_, "open " + where), H5Dclose);
    TableDataset d;
    d.name = name;
    d.units = required_attribute(ds, where, "units");
    d.description = required_attribute(ds, where, "description");
    d.axes = split_axes(required_attribute(ds, where, "axes"));
    h5::Id space(h5::check_id(H5Dget_space(ds), file_, where), H5Sclose);
    int rank = H5Sget_simple_extent_ndims(space);
    RAILTAB_CHECK(rank == static_cast<int>(d.axes.size()), "{}: {}: rank {} but {} axes named", file_, where,
                  rank, d.axes.size());
    std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
    if (rank > 0) H5Sget_simple_extent_dims(space, dims.data(), nullptr);
    for (int i = 0; i < rank; ++i) {
      if (is_plain_dimension(d.axes[static_cast<std::size_t>(i)])) continue;  // a list index: any extent
      const TableAxis* axis = table.axis(d.axes[static_cast<std::size_t>(i)]);
      RAILTAB_CHECK(axis, "{}: {}: axis '{}' not in /axes", file_, where, d.axes[static_cast<std::size_t>(i)]);
      RAILTAB_CHECK(axis->values.size() == dims[static_cast<std::size_t>(i)],
                    "{}: {}: dimension {} has {} entries but axis '{}' has {}", file_, where, i,
                    dims[static_cast<std::size_t>(i)], axis->name, axis->values.size());
    }
    d.shape.assign(dims.begin(), dims.end());
    h5::Id type(h5::check_id(H5Dget_type(ds), file_, where), H5Tclose);
    d.is_status = H5Tget_class(type) == H5T_INTEGER;
    RAILTAB_CHECK(d.is_status == is_uint32_dataset(name), "{}: {}: {} dataset expected", file_, where,
                  is_uint32_dataset(name) ? "uint32" : "float64");
    std::string what = "read " + where + " (truncated or damaged file?)";
    if (d.is_status) {
      d.status.resize(d.size());
      h5::check(H5Dread(ds, H5T_NATIVE_UINT32, H5S_ALL, H5S_ALL, H5P_DEFAULT, d.status.data()), file_, what);
    } else {
      d.values.resize(d.size());
      h5::check(H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, d.values.data()), file_, what);
    }
    d.storage_bytes = H5Dget_storage_size(ds);
    return d;
  }

  std::string file_;
};

}  // namespace

Table read_table(const std::filesystem::path& path) {
  h5::silence_errors();
  return Reader(path.string()).read();
}

}  // namespace railtab
