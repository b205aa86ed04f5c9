// SPDX-License-Identifier: Apache-2.0
// Hostile and corrupt tables: every one is a LoadError naming the file
// and the problem, before anything large is allocated; nothing reaches the query path.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "lookup/lookup_test_util.hpp"
#include "lookup/table_fixture.hpp"
#include "railtab/lookup.hpp"

namespace railtab::lookup::table_hostile_test {  // own namespace: unity builds compile several test files as one
namespace {

using testing::FixtureSpec;
using testing::linspace;
using testing::TempFile;

FixtureSpec small_spec() {
  FixtureSpec spec;
  spec.axes = {{0, linspace(-0.01, 0.01, 5)}, {5, linspace(-1.0, 1.0, 3)}};
  spec.fixed = {{1, 0.0}, {2, 78500.0}, {3, 0.0}, {4, 0.0}};
  spec.value = [](int, int part, int out, int slot, const double* x) {
    return 1.0 + part + 0.1 * out + slot + 10.0 * x[0] + x[5];
  };
  return spec;
}

// The LoadError's message for `path`, "" (and a test failure) if it loads.
std::string load_error(const std::string& path, const LoadOptions& options = {}) {
  try {
    Table::load(path, options);
  } catch (const LoadError& e) {
    EXPECT_EQ(e.path(), path);
    return e.what();
  }
  ADD_FAILURE() << path << " loaded without error";
  return "";
}

std::string data_file(const char* name) { return std::string(RAILTAB_TEST_DATA_DIR) + "/" + name; }

long max_rss_kib() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

// The hostile files (tests/data/*.h5) are format-1.0 tables (superblock 0): since
// the raw superblock check they are refused before libhdf5 sees them. The checks they once
// reached are tested on checksummed tables written afresh.
constexpr const char* kOldTable = "written by an old railtab (table format 1.0, no checksums)";

// Regression: a y axis of uniform subnormal spacing (1e-310) passed the load
// checks, then 1/h = inf gave a negative cell index and a crash at query time.
TEST(HostileTable, SubnormalAxisSpacingIsRefusedAtLoad) {
  const std::string msg = load_error(data_file("axis_subnormal_spacing.h5"));
  EXPECT_NE(msg.find(kOldTable), std::string::npos) << msg;
  // The same axis written afresh (checksummed table): refused by the axis check.
  TempFile file("subnormal");
  FixtureSpec spec = small_spec();
  spec.axes[0].second = {0.0, 1e-310, 2e-310, 3e-310};
  testing::write_fixture(file.path, spec);
  const std::string fresh = load_error(file.path);
  EXPECT_NE(fresh.find("axis /axes/y has a cell width (index 0 to 1) whose reciprocal is not finite"),
            std::string::npos) << fresh;
}

// An axis spanning more than the largest double: its mean spacing overflows.
TEST(HostileTable, AxisWhoseSpanOverflowsIsRefused) {
  TempFile file("span");
  FixtureSpec spec = small_spec();
  spec.axes[0].second = {-1.5e308, 0.0, 1.5e308};
  testing::write_fixture(file.path, spec);
  const std::string msg = load_error(file.path);
  EXPECT_NE(msg.find("axis /axes/y has a"), std::string::npos) << msg;
}

// Regression: a 98 KB file whose /axes/eta declares 1e9 nodes made the loader
// allocate 7.8 GB before rejecting it. Now the extent is refused before any allocation.
TEST(HostileTable, AxisDeclaring1e9NodesIsRefusedBeforeAllocating) {
  const long before = max_rss_kib();
  const std::string msg = load_error(data_file("axis_declares_1e9_nodes.h5"));
  EXPECT_NE(msg.find(kOldTable), std::string::npos) << msg;
  // The same axis in a checksummed table (superblock 3, so it reaches the extent check): a fresh
  // fixture (railtab_lookup_write_fixture) whose /axes/eta h5py replaced by a chunked, unwritten,
  // Fletcher32 dataset of shape (1e9,), made a dimension scale again (124 KB file).
  const std::string fresh = load_error(data_file("axis_declares_1e9_nodes_checksummed.h5"));
  EXPECT_NE(fresh.find("dataset /axes/eta declares shape [1000000000], more than 1000000 values"), std::string::npos)
      << fresh;
  EXPECT_LT(max_rss_kib() - before, 64 * 1024) << "peak memory grew by more than 64 MiB";
}

// Regression: one flipped byte in a variable-length string attribute's heap
// reference crashed inside libhdf5's variable-length read. Now the reference is checked against
// the global heap first.
TEST(HostileTable, CorruptStringAttributeIsAnError) {
  const std::string msg = load_error(data_file("corrupt_string_attribute.h5"));
  EXPECT_NE(msg.find(kOldTable), std::string::npos) << msg;
}

// Shard files, fixed_axes naming unknown variables or missing some, and
// malformed versions are refused with a message naming the file and the problem.
TEST(HostileTable, ShardFilesAreRefused) {
  TempFile file("shard");
  FixtureSpec spec = small_spec();
  spec.extra_root_attributes = {{"shard", "2/4"}, {"shard_y_begin", "2"}};
  testing::write_fixture(file.path, spec);
  const std::string msg = load_error(file.path);
  EXPECT_NE(msg.find(file.path), std::string::npos);
  EXPECT_NE(msg.find("it is shard 2/4 of a table"), std::string::npos) << msg;
  EXPECT_NE(msg.find("railtab merge"), std::string::npos) << msg;
}

TEST(HostileTable, FixedAxesWithAnUnknownVariableAreRefused) {
  TempFile file("unknown_fixed");
  FixtureSpec spec = small_spec();
  spec.fixed_text = "\"speed\":30.0";
  testing::write_fixture(file.path, spec);
  EXPECT_NE(load_error(file.path).find("fixed_axes names 'speed', not a state variable"),
            std::string::npos);
}

TEST(HostileTable, FixedAxesMissingAVariableAreRefused) {
  TempFile file("missing_fixed");
  FixtureSpec spec = small_spec();
  spec.fixed = {{1, 0.0}, {2, 78500.0}, {4, 0.0}};  // xi neither an axis nor fixed
  spec.complete_fixed = false;
  testing::write_fixture(file.path, spec);
  EXPECT_NE(load_error(file.path).find("state variable 'xi' is neither an axis"),
            std::string::npos);
}

TEST(HostileTable, FixedAxesListingAVariableTwiceAreRefused) {
  TempFile file("twice_fixed");
  FixtureSpec spec = small_spec();
  spec.fixed_text = "\"load\":1.0";
  testing::write_fixture(file.path, spec);
  EXPECT_NE(load_error(file.path).find("lists 'load' twice"), std::string::npos);
}

TEST(HostileTable, MalformedVersionsAreRefused) {
  for (const char* v : {"1.0.0", "1.", ".1", "1", " 1.0", "1.0 ", "+1.0", "1.-1", "1.0a", "01234567.0", ""}) {
    TempFile file("version");
    FixtureSpec spec = small_spec();
    spec.format_version = v;
    testing::write_fixture(file.path, spec);
    const std::string msg = load_error(file.path);
    EXPECT_NE(msg.find("is not of the form MAJOR.MINOR"), std::string::npos) << v << ": " << msg;
  }
}

// A table path that is a FIFO, a character device or a directory is refused at once, before
// anything opens it (a FIFO without a writer would block the first read forever), naming the path
// and what it is. alarm() turns a blocking load into a failed (killed) test instead of a hang.
TEST(TableInputFile, FifoIsRefusedWithoutBlocking) {
  TempFile fifo("fifo");
  ASSERT_EQ(::mkfifo(fifo.path.c_str(), 0600), 0);
  ::alarm(20);
  const std::string msg = load_error(fifo.path);
  ::alarm(0);
  EXPECT_NE(msg.find("'" + fifo.path + "': it is a FIFO, not a regular file: refused"), std::string::npos) << msg;
}

TEST(TableInputFile, DeviceAndDirectoryAreRefusedNamingWhatTheyAre) {
  const std::string device = load_error("/dev/null");
  EXPECT_NE(device.find("'/dev/null': it is a character device, not a regular file: refused"), std::string::npos)
      << device;
  TempFile dir("dir");
  ASSERT_EQ(::mkdir(dir.path.c_str(), 0700), 0);
  const std::string directory = load_error(dir.path);
  EXPECT_NE(directory.find("'" + dir.path + "': it is a directory, not a regular file: refused"), std::string::npos)
      << directory;
  // A missing file is "no such file", not a guess between missing and irregular.
  const std::string missing = load_error(dir.path + "/none.h5");
  EXPECT_NE(missing.find("none.h5': no such file"), std::string::npos) << missing;
}

// A symbolic link to a table is a table: the check follows links.
TEST(TableInputFile, SymbolicLinkToATableLoads) {
  TempFile table("target");
  testing::write_fixture(table.path, small_spec());
  TempFile link("link");
  ASSERT_EQ(::symlink(table.path.c_str(), link.path.c_str()), 0);
  EXPECT_NO_THROW(Table::load(link.path));
}

// Byte offset in the file of the first chunk of `dataset` (every fixture dataset is chunked).
haddr_t chunk_address(const std::string& path, const char* dataset) {
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t d = H5Dopen2(f, dataset, H5P_DEFAULT);
  hsize_t origin[8] = {};
  unsigned mask = 0;
  haddr_t addr = HADDR_UNDEF;
  hsize_t size = 0;
  H5Dget_chunk_info_by_coord(d, origin, &mask, &addr, &size);
  H5Dclose(d);
  H5Fclose(f);
  return addr;
}

void flip_byte(const std::string& path, std::uint64_t offset) {
  std::fstream io(path, std::ios::in | std::ios::out | std::ios::binary);
  io.seekg(static_cast<std::streamoff>(offset));
  char c = 0;
  io.get(c);
  io.seekp(static_cast<std::streamoff>(offset));
  io.put(static_cast<char>(c ^ 0x10));
}

// Every dataset carries a Fletcher32 checksum; a flipped data byte is a load
// error, not a different answer.
TEST(TableIntegrity, FlippedDataByteFailsTheChecksum) {
  TempFile file("flip");
  testing::write_fixture(file.path, small_spec());
  ASSERT_TRUE(Table::load(file.path).checksums_verified());
  const haddr_t addr = chunk_address(file.path, "/left/creep/fx");
  ASSERT_NE(addr, HADDR_UNDEF);
  flip_byte(file.path, addr + 13);
  const std::string msg = load_error(file.path);
  EXPECT_NE(msg.find("cannot read dataset /left/creep/fx"), std::string::npos) << msg;
}

// A table with checksummed metadata but no Fletcher32 on its datasets (another writer's) loads,
// flagged unverified; a flipped data byte then goes unnoticed, which is why the flag exists and
// require_checksums refuses such a table. A format-1.0 table is refused either way.
TEST(TableIntegrity, UnverifiedTablesLoadFlaggedOrAreRefusedOnRequest) {
  TempFile file("legacy");
  FixtureSpec spec = small_spec();
  spec.checksums = false;
  spec.checksummed_metadata = true;
  testing::write_fixture(file.path, spec);
  EXPECT_FALSE(Table::load(file.path).checksums_verified());
  TempFile old("format10");
  spec.checksummed_metadata = false;
  testing::write_fixture(old.path, spec);
  EXPECT_NE(load_error(old.path).find(kOldTable), std::string::npos);
  LoadOptions strict;
  strict.require_checksums = true;
  EXPECT_NE(load_error(file.path, strict).find("it has no checksums"), std::string::npos);
}

// A checksummed table where one dataset lacks the checksum (e.g. replaced by hand) is refused.
TEST(TableIntegrity, MixedChecksumsAreRefused) {
  TempFile file("mixed");
  testing::write_fixture(file.path, small_spec());
  {
    const hid_t f = H5Fopen(file.path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(f, 0);
    ASSERT_GE(H5Ldelete(f, "/axes/phi", H5P_DEFAULT), 0);
    const hsize_t n = 3;
    const double phi[3] = {-1, 0, 1};
    const hid_t space = H5Screate_simple(1, &n, nullptr);
    const hid_t d = H5Dcreate2(f, "/axes/phi", H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT,
                               H5P_DEFAULT);
    H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, phi);
    H5Dclose(d);
    H5Sclose(space);
    H5Fclose(f);
  }
  EXPECT_NE(load_error(file.path).find("dataset /axes/phi has no checksum but /axes/slot has one"),
            std::string::npos);
}

// Variable-length string attributes belong to legacy tables only: a checksummed table stores
// fixed-length strings (their bytes are inside checksummed metadata).
TEST(TableIntegrity, VariableLengthStringsInAChecksummedTableAreRefused) {
  TempFile file("vlen");
  testing::write_fixture(file.path, small_spec());
  {
    const hid_t f = H5Fopen(file.path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(f, 0);
    ASSERT_GE(H5Adelete(f, "scene_name"), 0);
    const hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, H5T_VARIABLE);
    const hid_t space = H5Screate(H5S_SCALAR);
    const hid_t a = H5Acreate2(f, "scene_name", type, space, H5P_DEFAULT, H5P_DEFAULT);
    const char* text = "vlen";
    H5Awrite(a, type, &text);
    H5Aclose(a);
    H5Sclose(space);
    H5Tclose(type);
    H5Fclose(f);
  }
  EXPECT_NE(load_error(file.path).find("attribute scene_name of / is a variable-length string"),
            std::string::npos);
}

// Variable-length strings of an unverified table are read from the checked global heap: the
// values are exact.
TEST(TableIntegrity, LegacyVariableLengthStringsReadExactly) {
  TempFile file("vlen_legacy");
  FixtureSpec spec = small_spec();
  spec.checksums = false;
  spec.checksummed_metadata = true;
  testing::write_fixture(file.path, spec);
  const Table t = Table::load(file.path);
  EXPECT_EQ(t.format_version(), "1.0");
  EXPECT_EQ(t.scene_name(), "fixture");
  EXPECT_EQ(t.fixed_axes().size(), 4u);
}

}  // namespace
}  // namespace railtab::lookup::table_hostile_test
