// SPDX-License-Identifier: Apache-2.0
// Table files (generator/table/): write/read round trip, dimension scales, compression,
// interrupted writes.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <hdf5_hl.h>

#include <cmath>
#include <fstream>

#include "core/check.hpp"
#include "generator/test_tables.hpp"
#include "table/interrupt.hpp"
#include "table/loadable_check.hpp"
#include "table/table_io.hpp"

namespace railtab {
namespace {

// A small but complete format-2.0 table: y x slot geometry and y x load x slot normal parts.
Table small_table(std::size_t ny = 3) {
  Table t;
  t.attributes = {{"format_version", "2.0"}, {"railtab_version", "0.1.0"}, {"git_commit", "abc"},
                  {"created", "2024-01-01T00:00:00Z"}, {"scene", "[scene]\nname = \"t\"\n"},
                  {"scene_name", "t"}, {"models", R"({"normal":"hertz"})"}, {"fixed_axes", R"({"eta":0.0,"phi":0.0,"roll":0.0,"xi":0.0})"}};  // every state variable: the lookup loads it
  TableAxis y{"y", "m", "lateral displacement", {}, false};
  for (std::size_t i = 0; i < ny; ++i) y.values.push_back(-0.001 + 0.001 * static_cast<double>(i));
  t.axes = {y, {"load", "N", "wheel load", {5e4, 8e4}, false}, {"slot", "1", "contact slot", {0, 1}, true}};
  for (const char* wheel : {"left", "right"}) {
    for (const char* part : {"geometry", "normal"}) {
      TableGroup g{std::string(wheel) + "/" + part, {}};
      bool normal = std::string(part) == "normal";
      std::vector<std::string> axes = normal ? std::vector<std::string>{"y", "load", "slot"}
                                             : std::vector<std::string>{"y", "slot"};
      std::vector<std::size_t> shape = normal ? std::vector<std::size_t>{ny, 2, 2} : std::vector<std::size_t>{ny, 2};
      for (const std::string& name : required_outputs(part)) {
        TableDataset d{name, "m", "test output " + name, axes, shape, {}, {}, name == "status", 0};
        for (std::size_t i = 0; i < d.size(); ++i) {
          if (d.is_status) d.status.push_back(static_cast<StatusBits>(i % 3 == 0 ? 1 : 5));
          else d.values.push_back(std::sin(static_cast<double>(i) + static_cast<double>(name.size())));
        }
        g.datasets.push_back(std::move(d));
      }
      t.groups.push_back(std::move(g));
    }
  }
  return t;
}

// Writes `t` unchecked to `path` and returns the lookup's problem with it ("" when it loads).
std::string lookup_refusal_text(const Table& t, const std::filesystem::path& path) {
  write_table(t, path, nullptr, {}, WrittenCheck::none);
  return lookup_refusal(path, false).value_or("");
}

TEST(TableWriter, RoundTripKeepsEverything) {
  testing::TempDir dir("writer_roundtrip");
  Table t = small_table();
  write_table(t, dir / "t.h5");
  EXPECT_EQ(dir.files(), std::vector<std::string>{"t.h5"});  // no temporary file left
  Table r = read_table(dir / "t.h5");
  EXPECT_EQ(r.attributes, t.attributes);
  testing::expect_same_datasets(t, r);
  for (const TableAxis& a : t.axes) {
    EXPECT_EQ(r.axis(a.name)->units, a.units);
    EXPECT_EQ(r.axis(a.name)->description, a.description);
    EXPECT_EQ(r.axis(a.name)->integer, a.integer);
  }
  const TableDataset* d = r.group("left/normal")->find("area");
  ASSERT_TRUE(d);
  EXPECT_EQ(d->units, "m");
  EXPECT_EQ(d->description, "test output area");
  EXPECT_GT(d->storage_bytes, 0u);
  // Dataset order is the writing order (creation order tracked).
  EXPECT_EQ(r.group("left/geometry")->datasets.front().name, "contact_angle");
}

TEST(TableWriter, AxesAreDimensionScalesAttachedToEveryDimension) {
  testing::TempDir dir("writer_scales");
  write_table(small_table(), dir / "t.h5");
  hid_t f = H5Fopen((dir / "t.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  hid_t y = H5Dopen2(f, "/axes/y", H5P_DEFAULT);
  hid_t slot = H5Dopen2(f, "/axes/slot", H5P_DEFAULT);
  hid_t load = H5Dopen2(f, "/axes/load", H5P_DEFAULT);
  hid_t d = H5Dopen2(f, "/right/normal/max_pressure", H5P_DEFAULT);
  EXPECT_GT(H5DSis_scale(y), 0);
  EXPECT_GT(H5DSis_scale(slot), 0);
  // Format 2: each part group holds its own copies of its axes (xarray/netCDF find coordinates
  // only in the group or its ancestors), and the datasets are attached to those.
  hid_t gy = H5Dopen2(f, "/right/normal/y", H5P_DEFAULT);
  hid_t gload = H5Dopen2(f, "/right/normal/load", H5P_DEFAULT);
  hid_t gslot = H5Dopen2(f, "/right/normal/slot", H5P_DEFAULT);
  EXPECT_GT(H5DSis_scale(gy), 0);
  EXPECT_GT(H5DSis_attached(d, gy, 0), 0);
  EXPECT_GT(H5DSis_attached(d, gload, 1), 0);
  EXPECT_GT(H5DSis_attached(d, gslot, 2), 0);
  // The fixed roll is a scalar dataset in /axes, not an attribute holding JSON.
  hid_t roll = H5Dopen2(f, "/axes/roll", H5P_DEFAULT);
  ASSERT_GE(roll, 0);
  hid_t space = H5Dget_space(roll);
  EXPECT_EQ(H5Sget_simple_extent_ndims(space), 0);
  EXPECT_EQ(H5Aexists(f, "fixed_axes"), 0);
  H5Sclose(space);
  for (hid_t id : {y, slot, load, d, gy, gload, gslot, roll}) H5Dclose(id);
  H5Fclose(f);
}

TEST(TableWriter, LargeDatasetsAreCompressed) {
  testing::TempDir dir("writer_chunks");
  Table t = small_table(3000);  // 3000 x 2 x 2 doubles = 96 KiB per normal dataset
  write_table(t, dir / "t.h5");
  hid_t f = H5Fopen((dir / "t.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  hid_t d = H5Dopen2(f, "/left/normal/area", H5P_DEFAULT);
  hid_t dcpl = H5Dget_create_plist(d);
  EXPECT_EQ(H5Pget_layout(dcpl), H5D_CHUNKED);
  EXPECT_EQ(H5Pget_nfilters(dcpl), 3);  // shuffle + deflate + fletcher32 (format 1.1)
  H5Pclose(dcpl);
  H5Dclose(d);
  // 24 KiB of statuses: compressed too (above 4 KiB; the STRIPES table's one-sided statuses
  // at the jumps are 55 KB each and compress to ~1 KB).
  hid_t status = H5Dopen2(f, "/left/geometry/status", H5P_DEFAULT);
  dcpl = H5Dget_create_plist(status);
  EXPECT_EQ(H5Pget_nfilters(dcpl), 3);
  H5Pclose(dcpl);
  H5Dclose(status);
  H5Fclose(f);
  testing::expect_same_datasets(t, read_table(dir / "t.h5"));

  write_table(small_table(), dir / "small.h5");
  f = H5Fopen((dir / "small.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  hid_t small = H5Dopen2(f, "/left/normal/area", H5P_DEFAULT);
  dcpl = H5Dget_create_plist(small);
  // 96 B: not worth compressing, but one chunk so that it carries its checksum (format 1.1).
  EXPECT_EQ(H5Pget_layout(dcpl), H5D_CHUNKED);
  EXPECT_EQ(H5Pget_nfilters(dcpl), 1);  // fletcher32 only
  H5Pclose(dcpl);
  H5Dclose(small);
  H5Fclose(f);
}

TEST(TableWriter, InconsistentTableWritesNothing) {
  testing::TempDir dir("writer_bad");
  Table t = small_table();
  t.groups[0].datasets[0].values.pop_back();
  EXPECT_THROW(write_table(t, dir / "t.h5"), Error);
  EXPECT_TRUE(dir.files().empty());
}

// The writer's last check: a table the lookup would refuse (here a NaN output, or y nodes 5e-324
// apart) never replaces the target, and the error names the target and the lookup's problem.
TEST(TableWriter, TableTheLookupRefusesIsNotWritten) {
  testing::TempDir dir("writer_lookup_check");
  const std::filesystem::path target = dir / "t.h5";
  write_table(small_table(2), target);
  Table nan = small_table(5);
  ASSERT_FALSE(nan.groups[0].datasets[0].is_status);
  nan.groups[0].datasets[0].values[1] = std::nan("");
  Table subnormal = small_table(3);
  subnormal.axes[0].values = {0.0, 5e-324, 1e-323};
  for (const Table* bad : {&nan, &subnormal}) {
    try {
      write_table(*bad, target);
      ADD_FAILURE() << "a table the lookup refuses was written";
    } catch (const Error& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find(target.string() + ": not written: the lookup would refuse"), std::string::npos) << m;
      EXPECT_EQ(m.find(".tmp."), std::string::npos) << "names the temporary: " << m;
    }
    EXPECT_EQ(dir.files(), std::vector<std::string>{"t.h5"});  // no temporary left
    EXPECT_EQ(read_table(target).axis("y")->values.size(), 2u);  // the old file is intact
  }
  EXPECT_NE(std::string(lookup_refusal_text(nan, dir / "nan.h5")).find("non-finite"), std::string::npos);
}

// An error found while the file is written (a value beyond float32's range in a float32 output,
// as a Young's modulus of 1e300 once made) names the output asked for, never its temporary, and
// leaves nothing behind.
TEST(TableWriter, ErrorsNameTheTargetNotTheTemporary) {
  testing::TempDir dir("writer_names_target");
  const std::filesystem::path target = dir / "t.h5";
  Table t = small_table();
  t.set_attribute("format_version", "2.2");  // creep and wear outputs stored as float32
  TableGroup wear = t.groups[0];
  wear.path = "left/wear";
  ASSERT_FALSE(wear.datasets[0].is_status);
  wear.datasets[0].values[1] = 1e300;
  t.groups.push_back(wear);
  try {
    write_table(t, target);
    ADD_FAILURE() << "a value beyond float32 was written";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind(target.string() + ": ", 0), 0u) << m;
    EXPECT_NE(m.find("exceeds the float32 range"), std::string::npos) << m;
    EXPECT_EQ(m.find(".tmp"), std::string::npos) << "names the temporary: " << m;
  }
  EXPECT_TRUE(dir.files().empty());
}

TEST(TableWriter, CancelRemovesTemporaryAndKeepsOldTarget) {
  testing::TempDir dir("writer_cancel");
  std::filesystem::path target = dir / "t.h5";
  write_table(small_table(2), target);
  std::atomic<bool> cancel{true};
  EXPECT_THROW(write_table(small_table(5), target, &cancel), Interrupted);
  EXPECT_EQ(dir.files(), std::vector<std::string>{"t.h5"});
  EXPECT_EQ(read_table(target).axis("y")->values.size(), 2u);  // the old file is intact
}

TEST(TableReader, RejectsUnknownMajorVersion) {
  testing::TempDir dir("reader_version");
  Table t = small_table();
  t.set_attribute("format_version", "3.0");
  write_table(t, dir / "t.h5", nullptr, {}, WrittenCheck::none);  // the lookup refuses it too
  try {
    read_table(dir / "t.h5");
    FAIL() << "version 3.0 accepted";
  } catch (const Error& e) {
    std::string m = e.what();
    EXPECT_NE(m.find((dir / "t.h5").string()), std::string::npos) << m;
    EXPECT_NE(m.find("format version 3.0 is not supported"), std::string::npos) << m;
  }
  t.set_attribute("format_version", "2.7");  // newer minor: accepted
  write_table(t, dir / "t.h5");
  EXPECT_NO_THROW(read_table(dir / "t.h5"));
}

TEST(TableReader, RejectsTruncatedFile) {
  testing::TempDir dir("reader_truncated");
  write_table(small_table(3000), dir / "t.h5");
  auto size = std::filesystem::file_size(dir / "t.h5");
  std::filesystem::copy_file(dir / "t.h5", dir / "cut.h5");
  std::filesystem::resize_file(dir / "cut.h5", size / 2);
  try {
    read_table(dir / "cut.h5");
    FAIL() << "truncated file accepted";
  } catch (const Error& e) {
    std::string m = e.what();
    EXPECT_NE(m.find("cut.h5"), std::string::npos) << m;
    EXPECT_NE(m.find("truncated"), std::string::npos) << m;
  }
}

TEST(TableReader, RejectsMissingDatasetsAndForeignFiles) {
  testing::TempDir dir("reader_missing");
  Table t = small_table();
  std::erase_if(t.group("right/normal")->datasets, [](const auto& d) { return d.name == "area"; });
  write_table(t, dir / "t.h5", nullptr, {}, WrittenCheck::none);  // incomplete on purpose: for the reader
  try {
    read_table(dir / "t.h5");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("missing dataset /right/normal/area"), std::string::npos) << e.what();
  }
  std::ofstream(dir / "text.h5") << "not hdf5";
  EXPECT_THROW(read_table(dir / "text.h5"), Error);
  EXPECT_THROW(read_table(dir / "absent.h5"), Error);
  t = small_table();
  t.remove_attribute("format_version");
  write_table(t, dir / "nover.h5", nullptr, {}, WrittenCheck::none);
  EXPECT_THROW(read_table(dir / "nover.h5"), Error);
}

}  // namespace
}  // namespace railtab

namespace railtab {
namespace {

// Format integrity (since 1.1): every dataset with HDF5's Fletcher32 checksum
// (a scalar: compact, inside its checksummed object header), the HDF5 1.10 file format (metadata
// checksums) and fixed-length string attributes everywhere (string arrays of format 2 too).
struct Failures {
  std::vector<std::string> list;
  std::string object;   // the object whose attributes are being checked
  int strings = 0;      // string attributes seen
};

herr_t check_attribute(hid_t loc, const char* name, const H5A_info_t*, void* data) {
  auto& f = *static_cast<Failures*>(data);
  const hid_t a = H5Aopen(loc, name, H5P_DEFAULT);
  const hid_t t = H5Aget_type(a);
  if (H5Tget_class(t) == H5T_STRING) {
    ++f.strings;
    if (H5Tis_variable_str(t) > 0) f.list.push_back(f.object + "/" + name + ": variable-length");
  }
  H5Tclose(t);
  H5Aclose(a);
  return 0;
}

herr_t check_object(hid_t loc, const char* name, const H5O_info_t* info, void* data) {
  auto& f = *static_cast<Failures*>(data);
  const hid_t o = H5Oopen(loc, name, H5P_DEFAULT);
  f.object = name;
  H5Aiterate2(o, H5_INDEX_NAME, H5_ITER_NATIVE, nullptr, check_attribute, &f);
  H5Oclose(o);
  if (info->type != H5O_TYPE_DATASET) return 0;
  const hid_t d = H5Dopen2(loc, name, H5P_DEFAULT);
  const hid_t dcpl = H5Dget_create_plist(d);
  const bool fletcher = H5Pget_filter_by_id2(dcpl, H5Z_FILTER_FLETCHER32, nullptr, nullptr, nullptr, 0,
                                             nullptr, nullptr) >= 0;
  if (!fletcher && H5Pget_layout(dcpl) != H5D_COMPACT) f.list.push_back(std::string(name) + ": no checksum");
  H5Pclose(dcpl);
  H5Dclose(d);
  return 0;
}

TEST(TableWriter, EveryDatasetAndTheMetadataAreChecksummed) {
  testing::TempDir dir("writer_checksums");
  Table t = small_table();
  TableDataset scalar{"scalar", "rad", "a scalar root dataset", {}, {}, {0.25}, {}, false, 0};
  t.groups.push_back(TableGroup{"", {scalar}});
  write_table(t, dir / "t.h5");
  const hid_t f = H5Fopen((dir / "t.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  H5F_info2_t info{};
  ASSERT_GE(H5Fget_info2(f, &info), 0);
  EXPECT_GE(info.super.version, 2u);  // superblock 2+: checksummed metadata
  Failures failures;
  ASSERT_GE(H5Ovisit(f, H5_INDEX_NAME, H5_ITER_NATIVE, check_object, &failures), 0);
  failures.object = "/";
  ASSERT_GE(H5Aiterate2(f, H5_INDEX_NAME, H5_ITER_NATIVE, nullptr, check_attribute, &failures), 0);
  EXPECT_TRUE(failures.list.empty()) << failures.list.front();
  EXPECT_GT(failures.strings, 20);  // units, descriptions, axes, provenance, slot_names, flags ...
  H5Fclose(f);
  Table r = read_table(dir / "t.h5");  // fixed-length UTF-8 strings read back exactly
  EXPECT_EQ(r.attributes, t.attributes);
  testing::expect_same_datasets(t, r);
}

// A flipped byte in a dataset's data is a read error, never a different table.
TEST(TableWriter, FlippedDataByteFailsTheChecksum) {
  testing::TempDir dir("writer_flip");
  write_table(small_table(), dir / "t.h5");
  const std::string path = (dir / "t.h5").string();
  haddr_t addr = HADDR_UNDEF;
  {
    const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    const hid_t d = H5Dopen2(f, "/left/geometry/contact_angle", H5P_DEFAULT);
    hsize_t origin[2] = {0, 0};
    unsigned mask = 0;
    hsize_t size = 0;
    H5Dget_chunk_info_by_coord(d, origin, &mask, &addr, &size);
    H5Dclose(d);
    H5Fclose(f);
  }
  ASSERT_NE(addr, HADDR_UNDEF);
  {
    std::fstream io(path, std::ios::in | std::ios::out | std::ios::binary);
    io.seekg(static_cast<std::streamoff>(addr + 5));
    char c = 0;
    io.get(c);
    io.seekp(static_cast<std::streamoff>(addr + 5));
    io.put(static_cast<char>(c ^ 0x01));
  }
  EXPECT_THROW(read_table(dir / "t.h5"), Error);
}

}  // namespace
}  // namespace railtab
