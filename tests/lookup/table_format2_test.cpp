// SPDX-License-Identifier: Apache-2.0
// Format 2.0 (docs/table-format.md): fixed variables as compact scalar datasets /axes/<name>,
// roll_mode, always checksummed; the checks of format 1's fixed_axes carried over (unknown or
// missing variables refused), string arrays checked like single strings. Format 1.1 still loads.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "lookup/lookup_test_util.hpp"
#include "lookup/table_fixture.hpp"
#include "railtab/lookup.hpp"

namespace railtab::lookup {
namespace {

using testing::FixtureSpec;
using testing::linspace;
using testing::TempFile;

FixtureSpec v2_spec() {
  FixtureSpec spec;
  spec.format_version = "2.0";
  spec.fixed_as_datasets = true;
  spec.axes = {{0, linspace(-0.01, 0.01, 5)}, {5, linspace(-1.0, 1.0, 3)}};
  spec.fixed = {{1, 0.0}, {2, 78500.0}, {3, 0.0}, {4, 0.0}};
  spec.value = [](int, int part, int out, int slot, const double* x) {
    return 1.0 + part + 0.1 * out + slot + 10.0 * x[0] + x[5];
  };
  return spec;
}

std::string load_error(const std::string& path) {
  try {
    Table::load(path);
  } catch (const LoadError& e) {
    return e.what();
  }
  ADD_FAILURE() << path << " loaded without error";
  return "";
}

// Adds a float64 scalar dataset `name` to `path` (compact or contiguous).
void add_scalar(const std::string& path, const char* name, double value, bool compact) {
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  if (compact) H5Pset_layout(dcpl, H5D_COMPACT);
  const hid_t d = H5Dcreate2(f, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  ASSERT_GE(d, 0);
  H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &value);
  H5Dclose(d);
  H5Pclose(dcpl);
  H5Sclose(space);
  H5Fclose(f);
}

// Adds a 1-D string-array attribute to `object` of `path`: fixed-length (size = longest) or
// variable-length.
void add_string_array(const std::string& path, const char* object, const char* name,
                      const std::vector<std::string>& values, bool variable) {
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  const hid_t o = H5Oopen(f, object, H5P_DEFAULT);
  const hid_t type = H5Tcopy(H5T_C_S1);
  const hsize_t n = values.size();
  const hid_t space = H5Screate_simple(1, &n, nullptr);
  std::size_t size = 1;
  for (const auto& v : values) size = std::max(size, v.size());
  H5Tset_size(type, variable ? H5T_VARIABLE : size);
  const hid_t a = H5Acreate2(o, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  if (variable) {
    std::vector<const char*> p;
    for (const auto& v : values) p.push_back(v.c_str());
    H5Awrite(a, type, p.data());
  } else {
    std::string bytes(size * n, '\0');
    for (std::size_t i = 0; i < n; ++i) bytes.replace(i * size, values[i].size(), values[i]);
    H5Awrite(a, type, bytes.data());
  }
  H5Aclose(a);
  H5Sclose(space);
  H5Tclose(type);
  H5Oclose(o);
  H5Fclose(f);
}

TEST(TableFormat2, LoadsWithChecksumsAndFixedScalars) {
  TempFile file("v2ok");
  testing::write_fixture(file.path, v2_spec());
  add_string_array(file.path, "/axes/slot", "slot_names", {"tread", "flange"}, false);
  const Table t = Table::load(file.path);
  EXPECT_EQ(t.format_version(), "2.0");
  EXPECT_TRUE(t.checksums_verified());
  ASSERT_EQ(t.fixed_axes().size(), 4u);
  EXPECT_EQ(t.fixed_axes()[1].first, "load");
  EXPECT_EQ(t.default_state().load, 78500.0);
}

TEST(TableFormat2, Format11StillLoads) {
  TempFile file("v11");
  FixtureSpec spec = v2_spec();
  spec.format_version = "1.1";
  spec.fixed_as_datasets = false;
  testing::write_fixture(file.path, spec);
  const Table t = Table::load(file.path);
  EXPECT_EQ(t.format_version(), "1.1");
  EXPECT_TRUE(t.checksums_verified());
  EXPECT_EQ(t.default_state().load, 78500.0);
}

TEST(TableFormat2, WithoutChecksumsIsRefused) {
  TempFile file("v2nock");
  FixtureSpec spec = v2_spec();
  spec.checksums = false;
  spec.checksummed_metadata = true;  // else refused earlier, by its superblock 0
  testing::write_fixture(file.path, spec);
  EXPECT_NE(load_error(file.path).find("format_version '2.0' but no checksums"), std::string::npos);
}

TEST(TableFormat2, MissingVariableIsRefused) {
  TempFile file("v2missing");
  FixtureSpec spec = v2_spec();
  spec.fixed = {{1, 0.0}, {2, 78500.0}, {4, 0.0}};  // xi neither an axis nor fixed
  spec.complete_fixed = false;
  testing::write_fixture(file.path, spec);
  const std::string msg = load_error(file.path);
  EXPECT_NE(msg.find("state variable 'xi' is neither an axis nor a fixed value"), std::string::npos) << msg;
}

TEST(TableFormat2, UnknownDatasetInAxesIsRefused) {
  TempFile file("v2unknown");
  testing::write_fixture(file.path, v2_spec());
  add_scalar(file.path, "/axes/speed", 30.0, true);
  const std::string msg = load_error(file.path);
  EXPECT_NE(msg.find("/axes/speed is not a state variable"), std::string::npos) << msg;
}

TEST(TableFormat2, FixedScalarNotCompactIsRefused) {
  TempFile file("v2contiguous");
  FixtureSpec spec = v2_spec();
  spec.fixed = {{1, 0.0}, {2, 78500.0}, {4, 0.0}};
  spec.complete_fixed = false;
  testing::write_fixture(file.path, spec);
  add_scalar(file.path, "/axes/xi", 0.0, false);  // contiguous: no checksum would cover it
  const std::string msg = load_error(file.path);
  EXPECT_NE(msg.find("fixed variable /axes/xi is not stored compact"), std::string::npos) << msg;
}

TEST(TableFormat2, FixedAxesAttributeIsRefused) {
  TempFile file("v2json");
  FixtureSpec spec = v2_spec();
  spec.extra_root_attributes = {{"fixed_axes", "{\"load\":1.0}"}};
  testing::write_fixture(file.path, spec);
  EXPECT_NE(load_error(file.path).find("root attribute fixed_axes in a format-2 table"), std::string::npos);
}

TEST(TableFormat2, RollModeEquilibriumLoadsAndOtherModesAreRefused) {
  FixtureSpec spec = v2_spec();
  spec.fixed = {{2, 78500.0}, {3, 0.0}, {4, 0.0}};  // roll: neither axis nor fixed
  spec.complete_fixed = false;
  {
    TempFile file("v2roll");
    spec.extra_root_attributes = {{"roll_mode", "equilibrium"}};
    testing::write_fixture(file.path, spec);
    const Table t = Table::load(file.path);
    EXPECT_EQ(t.fixed_axes().size(), 3u);
    // roll is not an input of this table: a queried roll is flagged, never silently ignored.
    State s = t.default_state();
    EXPECT_EQ(s.roll, 0.0);
    EXPECT_FALSE(t.query(Wheel::kLeft, s).status & status::kOutOfRange);
    s.roll = -0.002;
    EXPECT_TRUE(t.query(Wheel::kRight, s).status & status::kOutOfRange);
  }
  {
    TempFile file("v2rollbad");
    spec.extra_root_attributes = {{"roll_mode", "kinematic"}};
    testing::write_fixture(file.path, spec);
    EXPECT_NE(load_error(file.path).find("roll_mode is 'kinematic'"), std::string::npos);
  }
  {
    TempFile file("v2rollnone");
    spec.extra_root_attributes = {};
    testing::write_fixture(file.path, spec);
    EXPECT_NE(load_error(file.path).find("state variable 'roll' is neither"), std::string::npos);
  }
  {
    TempFile file("v2rollboth");
    FixtureSpec both = v2_spec();  // roll fixed at 0 AND following the equilibrium
    both.extra_root_attributes = {{"roll_mode", "equilibrium"}};
    testing::write_fixture(file.path, both);
    EXPECT_NE(load_error(file.path).find("but /axes/roll exists too"), std::string::npos);
  }
}

// A table that stores half of a symmetric yaw axis says so with yaw_symmetry = "even"; any other
// symmetry, or the attribute without a yaw axis that starts at 0, is refused: the lookup would
// fold a queried yaw onto nodes that are not there.
TEST(TableFormat2, YawSymmetryNeedsEvenAndAYawAxisFromZero) {
  struct Case {
    const char* symmetry;  // the root attribute yaw_symmetry of a fixture without a yaw axis
    const char* message;   // what the refusal must say
  };
  for (const Case& c : {Case{"odd", "root attribute yaw_symmetry is 'odd'"},
                        Case{"even", "needs a yaw axis starting at 0"}}) {
    TempFile file(std::string("v2yaw") + c.symmetry);
    FixtureSpec spec = v2_spec();
    spec.extra_root_attributes = {{"yaw_symmetry", c.symmetry}};
    testing::write_fixture(file.path, spec);
    const std::string msg = load_error(file.path);
    EXPECT_NE(msg.find(c.message), std::string::npos) << c.symmetry << ": " << msg;
  }
}

TEST(TableFormat2, VariableLengthStringArrayIsRefused) {
  TempFile file("v2vlenarray");
  testing::write_fixture(file.path, v2_spec());
  add_string_array(file.path, "/axes/slot", "slot_names", {"tread", "flange"}, true);
  const std::string msg = load_error(file.path);
  EXPECT_NE(msg.find("attribute slot_names of /axes/slot is an array of variable-length strings"),
            std::string::npos) << msg;
}

}  // namespace
}  // namespace railtab::lookup
