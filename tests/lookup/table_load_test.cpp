// SPDX-License-Identifier: Apache-2.0
// Loading: every bad file is an error at load, of type LoadError, naming the file and the problem.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "lookup/lookup_test_util.hpp"
#include "lookup/table_fixture.hpp"
#include "railtab/lookup.hpp"

namespace railtab::lookup {
namespace {

using testing::FixtureSpec;
using testing::linspace;
using testing::TempFile;

FixtureSpec tiny_spec() {
  FixtureSpec spec;
  spec.axes = {{0, linspace(-0.01, 0.01, 5)}, {5, linspace(-1.0, 1.0, 3)}};
  spec.fixed = {{1, 0.0}, {2, 78500.0}, {3, 0.0}, {4, 0.0}};
  spec.value = [](int, int, int, int, const double* x) { return x[0] + x[5]; };
  return spec;
}

// Loads `path` expecting a LoadError whose message names the file and contains `problem`.
void expect_load_error(const std::string& path, const std::string& problem) {
  try {
    Table::load(path);
    ADD_FAILURE() << "loaded " << path << " without error, expected: " << problem;
  } catch (const LoadError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find(problem), std::string::npos) << what;
    EXPECT_EQ(e.path(), path);
  }
}

// Tables with checksummed metadata (HDF5 superblock >= 2) load with either string kind; without
// Fletcher32 on the datasets they are flagged unverified.
TEST(TableLoad, GoodTableLoadsWithEitherStringKind) {
  for (bool fixed_length : {false, true}) {
    TempFile file("good");
    FixtureSpec spec = tiny_spec();
    spec.checksums = false;
    spec.checksummed_metadata = true;
    spec.fixed_length_strings = fixed_length;
    testing::write_fixture(file.path, spec);
    const Table t = Table::load(file.path);
    EXPECT_EQ(t.format_version(), "1.0");
    EXPECT_EQ(t.fixed_axes().size(), 4u);
    EXPECT_FALSE(t.checksums_verified());
    ASSERT_EQ(t.axes().size(), 2u);
    EXPECT_EQ(t.axes()[0].units, "m");
    EXPECT_EQ(t.axes()[1].units, "rad/m");
  }
}

// Format-1.0 tables (HDF5 superblock 0: metadata without checksums) are refused before libhdf5
// parses them (a corrupt one made libhdf5 read freed memory, found by fuzzing), whichever
// string kind they use, with a message naming the file, the cause and the command that
// regenerates them.
TEST(TableLoad, Format10TablesAreRefusedWithTheCommandThatRegeneratesThem) {
  for (bool fixed_length : {false, true}) {
    TempFile file("format10");
    FixtureSpec spec = tiny_spec();
    spec.checksums = false;
    spec.fixed_length_strings = fixed_length;
    testing::write_fixture(file.path, spec);
    try {
      (void)Table::load(file.path);
      ADD_FAILURE() << "a format-1.0 table loaded";
    } catch (const LoadError& e) {
      const std::string what = e.what();
      EXPECT_EQ(e.path(), file.path);
      EXPECT_NE(what.find(file.path), std::string::npos) << what;
      EXPECT_NE(what.find("HDF5 superblock version 0"), std::string::npos) << what;
      EXPECT_NE(what.find("written by an old railtab (table format 1.0, no checksums)"),
                std::string::npos) << what;
      EXPECT_NE(what.find("regenerate it with `railtab generate <scene.toml>`"),
                std::string::npos) << what;
    }
  }
}

TEST(TableLoad, MissingFile) {
  expect_load_error(testing::temp_table("does_not_exist"), "no such file");
}

TEST(TableLoad, NotAnHdf5File) {
  TempFile file("text");
  std::ofstream(file.path) << "y,fx\n0,1\n";
  expect_load_error(file.path, "not an HDF5 file");
}

TEST(TableLoad, TruncatedFile) {
  TempFile file("truncated");
  testing::write_fixture(file.path, testing::scene_sized_spec());  // chunked, ~1 MB
  const auto size = std::filesystem::file_size(file.path);
  for (double keep : {0.5, 0.95}) {
    std::filesystem::resize_file(file.path, static_cast<std::uintmax_t>(size * keep));
    expect_load_error(file.path, "");
  }
}

TEST(TableLoad, MissingDataset) {
  TempFile file("missing");
  FixtureSpec spec = tiny_spec();
  spec.omit_dataset = "/right/creep/fy";
  testing::write_fixture(file.path, spec);
  expect_load_error(file.path, "missing dataset /right/creep/fy");
}

TEST(TableLoad, MissingStatus) {
  TempFile file("missing_status");
  FixtureSpec spec = tiny_spec();
  spec.omit_dataset = "/left/geometry/status";
  testing::write_fixture(file.path, spec);
  expect_load_error(file.path, "missing dataset /left/geometry/status");
}

TEST(TableLoad, UnknownMajorVersion) {
  TempFile file("v3");
  FixtureSpec spec = tiny_spec();
  spec.format_version = "3.0";
  testing::write_fixture(file.path, spec);
  expect_load_error(file.path, "unsupported format_version '3.0'");
}

// Format 2 stores each fixed variable as a scalar dataset /axes/<name> (typed, with units)
// instead of the JSON attribute fixed_axes; format 1 files still load (the tests above).
TEST(TableLoad, Version2FixedVariablesAsScalarDatasets) {
  TempFile file("v2");
  FixtureSpec spec = tiny_spec();
  spec.format_version = "2.0";
  spec.fixed_as_datasets = true;
  testing::write_fixture(file.path, spec);
  const Table t = Table::load(file.path);
  EXPECT_EQ(t.format_version(), "2.0");
  ASSERT_EQ(t.fixed_axes().size(), 4u);
  EXPECT_EQ(t.fixed_axes()[1].first, "load");
  EXPECT_EQ(t.fixed_axes()[1].second, 78500.0);
  State s = t.default_state();
  EXPECT_EQ(s.load, 78500.0);
  Result r;
  t.query(Wheel::kLeft, s, r);
  EXPECT_FALSE(r.status & status::kOutOfRange);
  s.load = 60000.0;  // off the fixed value
  t.query(Wheel::kLeft, s, r);
  EXPECT_TRUE(r.status & status::kOutOfRange);
}

// 1.0 (tiny_spec's default), 1.1 (integrity: checksums) and 1.2 (the creep part's per-creepage
// normal outputs, which this reader ignores) all load and report their version.
TEST(TableLoad, KnownMinorVersionsLoad) {
  for (const char* v : {"1.0", "1.1", "1.2"}) {
    TempFile file(std::string("v_") + v);
    FixtureSpec spec = tiny_spec();
    spec.format_version = v;
    testing::write_fixture(file.path, spec);
    EXPECT_EQ(Table::load(file.path).format_version(), v);
  }
}

TEST(TableLoad, NewerMinorVersionLoads) {
  TempFile file("v1_7");
  FixtureSpec spec = tiny_spec();
  spec.format_version = "1.7";
  testing::write_fixture(file.path, spec);
  EXPECT_EQ(Table::load(file.path).format_version(), "1.7");
}

TEST(TableLoad, MalformedVersion) {
  TempFile file("vx");
  FixtureSpec spec = tiny_spec();
  spec.format_version = "one";
  testing::write_fixture(file.path, spec);
  expect_load_error(file.path, "not of the form MAJOR.MINOR");
}

TEST(TableLoad, WrongAxesAttribute) {
  TempFile file("axes_attr");
  FixtureSpec spec = tiny_spec();
  spec.wrong_axes_dataset = "/left/normal/area";
  testing::write_fixture(file.path, spec);
  expect_load_error(file.path, "/left/normal/area has axes='slot,y', expected 'y,slot'");
}

TEST(TableLoad, WrongShape) {
  // Replace /axes/phi by a 4-node axis: creep and wear datasets (3 phi nodes) no longer fit.
  TempFile file("shape");
  testing::write_fixture(file.path, tiny_spec());
  {
    const hid_t f = H5Fopen(file.path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(f, 0);
    ASSERT_GE(H5Ldelete(f, "/axes/phi", H5P_DEFAULT), 0);
    const hsize_t n = 4;
    const double phi[4] = {-1, 0, 0.5, 1};
    const hid_t space = H5Screate_simple(1, &n, nullptr);
    const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);  // as the fixture: checksummed
    H5Pset_chunk(dcpl, 1, &n);
    H5Pset_fletcher32(dcpl);
    const hid_t d = H5Dcreate2(f, "/axes/phi", H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl,
                               H5P_DEFAULT);
    H5Pclose(dcpl);
    H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, phi);
    H5Dclose(d);
    H5Sclose(space);
    H5Fclose(f);
  }
  expect_load_error(file.path, "/left/creep/fx has shape [5,3,2], but the table's axes (y,phi,slot) need [5,4,2]");
}

TEST(TableLoad, FixedAxesMustParse) {
  TempFile file("fixed");
  FixtureSpec spec = tiny_spec();
  spec.fixed = {{5, 0.0}};  // phi is also an axis
  testing::write_fixture(file.path, spec);
  expect_load_error(file.path, "'phi' is both an axis and in fixed_axes");
}

// The generator writes "roll":"equilibrium" when roll follows the kinematic equilibrium at each y
// (docs/table-format.md): the table loads, roll is neither tabulated nor fixed. A query that sets
// a roll is answered at the equilibrium and flagged out_of_range (never silently), a NaN roll is
// invalid input; roll left at 0 (default_state) is the equilibrium.
TEST(TableLoad, EquilibriumRollLoadsAndFlagsAQueriedRoll) {
  TempFile file("equilibrium_roll");
  FixtureSpec spec = tiny_spec();
  spec.fixed = {{2, 78500.0}, {3, 0.0}, {4, 0.0}};  // roll (1) follows the equilibrium instead
  spec.fixed_text = "\"roll\":\"equilibrium\"";
  testing::write_fixture(file.path, spec);
  const Table t = Table::load(file.path);
  for (const auto& [name, value] : t.fixed_axes()) EXPECT_NE(name, "roll");
  State s = t.default_state();
  Result a;
  Result b;
  t.query(Wheel::kLeft, s, a);
  s.roll = 0.01;
  t.query(Wheel::kLeft, s, b);
  EXPECT_FALSE(a.status & status::kOutOfRange);
  EXPECT_TRUE(b.status & status::kOutOfRange);
  EXPECT_TRUE(b.contact[0].status & status::kOutOfRange);
  EXPECT_EQ(a.contact[0].value[0], b.contact[0].value[0]);  // answered at the equilibrium
  Contact c;
  t.query_slot(Wheel::kLeft, s, 0, c);
  EXPECT_TRUE(c.status & status::kOutOfRange);
  s.roll = std::nan("");
  t.query(Wheel::kLeft, s, b);
  EXPECT_TRUE(b.status & status::kInvalidInput);
}

TEST(TableLoad, FixedAxesTextOnlyForEquilibriumRoll) {
  TempFile file("fixed_text");
  FixtureSpec spec = tiny_spec();
  spec.fixed = {{1, 0.0}, {3, 0.0}, {4, 0.0}};
  spec.fixed_text = "\"load\":\"heavy\"";
  testing::write_fixture(file.path, spec);
  expect_load_error(file.path, "fixed_axes value of 'load' must be a number");
}

TEST(TableLoad, NoPartsIsAnError) {
  TempFile file("no_parts");
  FixtureSpec spec = tiny_spec();
  spec.parts = {};
  testing::write_fixture(file.path, spec);
  expect_load_error(file.path, "no part found");
}

TEST(TableLoad, NonFiniteValuesAreRejected) {
  TempFile file("nan");
  FixtureSpec spec = tiny_spec();
  spec.value = [](int wheel, int part, int, int, const double* x) {
    return (wheel == 1 && part == 3 && x[0] > 0.0) ? std::nan("") : 1.0;
  };
  testing::write_fixture(file.path, spec);
  expect_load_error(file.path, "/right/wear/wear_rate holds a non-finite value");
}

}  // namespace
}  // namespace railtab::lookup
