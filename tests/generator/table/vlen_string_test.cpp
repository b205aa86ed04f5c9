// SPDX-License-Identifier: Apache-2.0
// Variable-length string attributes (format-1.0 tables, h5py's default) in the generator's table
// reader (generator/table/h5_util.cpp, typed_attributes.cpp): read with the lookup's bounded
// reader, never with libhdf5's variable-length read (`railtab inspect` once crashed inside
// that read on 2 in 1000 damaged format-1.0 tables).
#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "core/check.hpp"
#include "table/h5_util.hpp"
#include "table/table_io.hpp"
#include "table/typed_attributes.hpp"

namespace railtab {
namespace {

// Writes `values` as a variable-length UTF-8 string attribute (scalar when `scalar`).
void write_vlen(hid_t object, const char* name, const std::vector<const char*>& values, bool scalar) {
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  const hsize_t n = values.size();
  const hid_t space = scalar ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &n, nullptr);
  const hid_t attr = H5Acreate2(object, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(attr, 0);
  ASSERT_GE(H5Awrite(attr, type, values.data()), 0);
  H5Aclose(attr);
  H5Sclose(space);
  H5Tclose(type);
}

TEST(VlenStrings, LegacyVariableLengthStringsReadExactly) {
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("railtab_vlen_" + std::to_string(::getpid()) + ".h5")).string();
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const hid_t group = H5Gcreate2(file, "models", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  write_vlen(file, "scene", {"[scene]\nname = \"wörn\"\n"}, true);
  write_vlen(file, "empty", {""}, true);
  write_vlen(group, "names", {"fx", "", "spin_moment", "units: N·m"}, false);
  H5Gclose(group);
  H5Fclose(file);

  const hid_t in = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(in, 0);
  EXPECT_EQ(h5::read_string_attribute(in, "scene", path), "[scene]\nname = \"wörn\"\n");
  EXPECT_EQ(h5::read_string_attribute(in, "empty", path), "");
  EXPECT_EQ(h5::read_attribute_as_text(in, "scene", path), "[scene]\nname = \"wörn\"\n");
  const hid_t models = H5Gopen2(in, "models", H5P_DEFAULT);
  const nlohmann::json read = h5::read_json_object(models, path);
  EXPECT_EQ(read.at("names"), nlohmann::json({"fx", "", "spin_moment", "units: N·m"})) << read.dump();
  H5Gclose(models);
  H5Fclose(in);
  std::filesystem::remove(path);
}

// tests/data/corrupt_string_attribute.h5: one byte of the heap reference of the `axes` attribute
// of /right/normal/max_pressure changed (h5dump -A crashes on it with SIGSEGV). Before: the
// generator's reader crashed the same way; now: an error naming the problem.
// The generator's table reader (inspect, merge, generate --resume) refuses a format-1.0 table
// (HDF5 superblock 0, metadata without checksums) before libhdf5 opens it, with the command
// that regenerates it (libhdf5 is not safe on corrupt unchecksummed metadata, found by fuzzing).
TEST(TableReaderRefusal, Format10TableIsRefusedBeforeOpening) {
  const std::string path = RAILTAB_SOURCE_DIR "/tests/data/corrupt_string_attribute.h5";
  try {
    (void)read_table(path);
    ADD_FAILURE() << "a format-1.0 table was read";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(path), std::string::npos) << msg;
    EXPECT_NE(msg.find("HDF5 superblock version 0"), std::string::npos) << msg;
    EXPECT_NE(msg.find("table format 1.0, no checksums"), std::string::npos) << msg;
    EXPECT_NE(msg.find("regenerate it with `railtab generate <scene.toml>`"), std::string::npos) << msg;
  }
}

TEST(VlenStrings, CorruptHeapReferenceIsAnErrorNotACrash) {
  const std::string path = RAILTAB_SOURCE_DIR "/tests/data/corrupt_string_attribute.h5";
  h5::silence_errors();
  const hid_t in = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(in, 0);
  const hid_t dataset = H5Dopen2(in, "/right/normal/max_pressure", H5P_DEFAULT);
  ASSERT_GE(dataset, 0);
  try {
    (void)h5::read_string_attribute(dataset, "axes", path);
    ADD_FAILURE() << "a corrupt heap reference was read";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("corrupt_string_attribute.h5"), std::string::npos) << msg;
    EXPECT_NE(msg.find("global heap"), std::string::npos) << msg;
  }
  H5Dclose(dataset);
  H5Fclose(in);
}

}  // namespace
}  // namespace railtab
