// SPDX-License-Identifier: Apache-2.0
// Storage precision of format 2.2 (generator/table/storage_precision.hpp): the creep and wear
// outputs are written as float32 rounded to 20 significant bits, everything else as before.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>

#include "generator/test_tables.hpp"
#include "table/storage_precision.hpp"
#include "table/table_io.hpp"

namespace railtab {
namespace {

std::uint64_t bits_of(double x) {
  std::uint64_t b = 0;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

TEST(StoragePrecision, RoundsToTwentySignificantBitsToNearest) {
  std::mt19937_64 rng(15);
  std::uniform_real_distribution<double> mantissa(1.0, 2.0);
  std::uniform_int_distribution<int> exponent(-60, 60);
  double worst = 0.0;
  for (int i = 0; i < 200000; ++i) {
    const double v = std::ldexp(mantissa(rng), exponent(rng)) * (i % 2 ? -1.0 : 1.0);
    const float q = quantize_for_storage(v);
    const double err = std::abs(static_cast<double>(q) - v) / std::abs(v);
    worst = std::max(worst, err);
    ASSERT_LE(err, kStoredRounding) << v;
    // 19 explicit significand bits kept: the 4 low bits of float32's 23 are zero.
    std::uint32_t u = 0;
    std::memcpy(&u, &q, sizeof u);
    ASSERT_EQ(u & 0xFu, 0u) << v;
    ASSERT_EQ(quantize_for_storage(static_cast<double>(q)), q) << "rounding a stored value changes it: " << v;
    // Nearest: the neighbours 2^-19 of a binade away are not closer.
    const double step = std::ldexp(1.0, std::ilogb(static_cast<double>(q)) - kStoredSignificandBits);
    ASSERT_LE(std::abs(static_cast<double>(q) - v), 0.5 * step * (1.0 + 1e-12)) << v;
  }
  EXPECT_GT(worst, 0.9 * kStoredRounding);  // the bound is reached, not loose
  // Ties go to the even neighbour; a carry raises the exponent; sign, zero and non-finite kept.
  EXPECT_EQ(quantize_for_storage(1.0 + 0x1p-20), 1.0f);
  EXPECT_EQ(quantize_for_storage(1.0 + 3 * 0x1p-20), static_cast<float>(1.0 + 4 * 0x1p-20));
  EXPECT_EQ(quantize_for_storage(2.0 - 0x1p-22), 2.0f);
  EXPECT_EQ(quantize_for_storage(-0.75), -0.75f);
  EXPECT_EQ(bits_of(static_cast<double>(quantize_for_storage(-0.0))), bits_of(-0.0));
  EXPECT_TRUE(std::isnan(quantize_for_storage(std::numeric_limits<double>::quiet_NaN())));
  EXPECT_TRUE(std::isinf(quantize_for_storage(1e39)));
}

TEST(StoragePrecision, FormatVersionChoosesTheStorage) {
  Table t;
  EXPECT_TRUE(table_stores_float32(t));  // a table being built: the current format
  for (const auto& [version, float32] :
       {std::pair<const char*, bool>{"2.2", true}, {"2.10", true}, {"3.0", true}, {"2.1", false}, {"2.0", false},
        {"1.1", false}}) {
    t.set_attribute("format_version", version);
    EXPECT_EQ(table_stores_float32(t), float32) << version;
  }
  TableDataset fx{"fx_normalised", "1", "", {"y", "slot"}, {1, 1}, {0.5}, {}, false, 0};
  TableDataset status{"status", "1", "", {"y", "slot"}, {1, 1}, {}, {1}, true, 0};
  EXPECT_TRUE(stored_as_float32("left/creep", fx));
  EXPECT_TRUE(stored_as_float32("jumps/right/wear", fx));
  EXPECT_FALSE(stored_as_float32("left/creep", status));
  for (const char* group : {"left/geometry", "right/normal", "jumps/left/normal", "jumps", ""})
    EXPECT_FALSE(stored_as_float32(group, fx)) << group;
}

// A format-2.2 table with every part: geometry and normal (float64), creep and wear (float32),
// all over (y, load, slot) but geometry (y, slot); with `jumps` also a jump list and one-sided
// creep values in /jumps (partial: only for the types on disk).
Table table_22(bool jumps) {
  Table t;
  t.attributes = {{"format_version", "2.2"}, {"railtab_version", "0.1.0"}, {"git_commit", "abc"},
                  {"created", "2026-11-26T00:00:00Z"}, {"scene", "[scene]\nname = \"t\"\n"},
                  {"scene_name", "t"}, {"models", R"({"normal":"hertz"})"}, {"fixed_axes", R"({"eta":0.0,"phi":0.0,"roll":0.0,"xi":0.0})"}};  // every state variable: the lookup loads it
  t.axes = {{"y", "m", "lateral displacement", {-0.002, -0.001, 0.0, 0.001, 0.002}, false},
            {"load", "N", "wheel load", {5e4, 8e4, 1e5}, false},
            {"slot", "1", "contact slot", {0, 1}, true}};
  std::size_t seed = 0;
  auto dataset = [&](const std::string& name, std::vector<std::string> axes, std::vector<std::size_t> shape) {
    TableDataset d{name, "1", "test", std::move(axes), std::move(shape), {}, {}, name == "status", 0};
    // Sizes of the real outputs: radii ~0.46 m, forces ~1e4 N, areas ~1e-4 m2, wear ~1e-12 m2/m.
    const double size = name == "rolling_radius" ? 0.46 : name == "area" ? 1e-4 : name == "wear_rate" ? 1e-12
                        : name == "normal_force" || name == "fx" ? 8e4 : 1.0;
    for (std::size_t i = 0; i < d.size(); ++i) {
      if (d.is_status) d.status.push_back(1u);
      else d.values.push_back(size * (1.0 + 0.3 * std::sin(0.7 * static_cast<double>(i + ++seed))));
    }
    return d;
  };
  for (const char* wheel : {"left", "right"}) {
    for (const char* part : {"geometry", "normal", "creep", "wear"}) {
      const bool geometry = std::string(part) == "geometry";
      const std::vector<std::string> axes = geometry ? std::vector<std::string>{"y", "slot"}
                                                     : std::vector<std::string>{"y", "load", "slot"};
      const std::vector<std::size_t> shape = geometry ? std::vector<std::size_t>{5, 2} : std::vector<std::size_t>{5, 3, 2};
      TableGroup g{std::string(wheel) + "/" + part, {}};
      for (const std::string& name : required_outputs(part)) g.datasets.push_back(dataset(name, axes, shape));
      if (std::string(part) == "creep") g.datasets.push_back(dataset("normal_force", axes, shape));
      t.groups.push_back(std::move(g));
    }
  }
  if (jumps) {
    t.groups.push_back({"jumps", {dataset("left_y", {"load", "jump"}, {3, 1})}});
    t.groups.push_back({"jumps/left/creep", {dataset("fx", {"load", "jump", "side", "slot"}, {3, 1, 2, 2}),
                                             dataset("status", {"load", "jump", "side", "slot"}, {3, 1, 2, 2})}});
  }
  return t;
}

// The file type of a dataset and its quantization attribute (-1 when absent).
struct OnDisk {
  hid_t type = -1;
  int significand_bits = -1;
};
OnDisk on_disk(const std::filesystem::path& file, const std::string& dataset) {
  OnDisk out;
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t d = H5Dopen2(f, dataset.c_str(), H5P_DEFAULT);
  const hid_t type = H5Dget_type(d);
  for (hid_t known : {H5T_IEEE_F32LE, H5T_IEEE_F64LE, H5T_STD_U32LE})
    if (H5Tequal(type, known) > 0) out.type = known;
  if (H5Aexists(d, kQuantizeAttribute) > 0) {
    const hid_t a = H5Aopen(d, kQuantizeAttribute, H5P_DEFAULT);
    H5Aread(a, H5T_NATIVE_INT, &out.significand_bits);
    H5Aclose(a);
  }
  H5Tclose(type);
  H5Dclose(d);
  H5Fclose(f);
  return out;
}

TEST(StoragePrecision, CreepAndWearOutputsAreWrittenAsRoundedFloat32) {
  testing::TempDir dir("storage_precision");
  // A partial /jumps (one wheel's list, one part): the file types are all this test reads.
  write_table(table_22(true), dir / "jumps.h5", nullptr, {}, WrittenCheck::none);
  for (const char* name : {"/left/creep/fx", "/left/creep/slip_fraction", "/right/creep/normal_force",
                           "/left/wear/wear_rate", "/jumps/left/creep/fx"}) {
    const OnDisk d = on_disk(dir / "jumps.h5", name);
    EXPECT_EQ(d.type, H5T_IEEE_F32LE) << name;
    EXPECT_EQ(d.significand_bits, kStoredSignificandBits) << name;
  }
  for (const char* name : {"/left/geometry/rolling_radius", "/left/normal/area", "/left/normal/normal_force",
                           "/jumps/left_y", "/axes/y", "/left/creep/y", "/left/creep/load"}) {
    const OnDisk d = on_disk(dir / "jumps.h5", name);
    EXPECT_EQ(d.type, H5T_IEEE_F64LE) << name;
    EXPECT_EQ(d.significand_bits, -1) << name;
  }
  EXPECT_EQ(on_disk(dir / "jumps.h5", "/left/creep/status").type, H5T_STD_U32LE);
  EXPECT_EQ(on_disk(dir / "jumps.h5", "/jumps/left/creep/status").type, H5T_STD_U32LE);

  const Table t = table_22(false);
  write_table(t, dir / "t.h5");
  // Read back: the float32 outputs are the rounded values, bit for bit; the rest is untouched.
  const Table r = read_table(dir / "t.h5");
  for (const TableGroup& g : t.groups) {
    for (const TableDataset& d : g.datasets) {
      if (d.is_status) continue;
      const TableDataset* back = r.group(g.path)->find(d.name);
      ASSERT_TRUE(back) << g.path << "/" << d.name;
      for (std::size_t i = 0; i < d.values.size(); ++i) {
        const double expected = stored_as_float32(g.path, d) ? quantize_for_storage(d.values[i]) : d.values[i];
        ASSERT_EQ(bits_of(back->values[i]), bits_of(expected)) << g.path << "/" << d.name << " [" << i << "]";
      }
    }
  }
  // Written again (as merge does with shards): the same bytes, the rounding does not drift.
  write_table(r, dir / "again.h5");
  std::ifstream a(dir / "t.h5", std::ios::binary), b(dir / "again.h5", std::ios::binary);
  const std::string bytes_a{std::istreambuf_iterator<char>(a), {}}, bytes_b{std::istreambuf_iterator<char>(b), {}};
  EXPECT_GT(bytes_a.size(), 0u);
  EXPECT_TRUE(bytes_a == bytes_b) << "a 2.2 table written twice differs";
}

TEST(StoragePrecision, OlderFormatsKeepFloat64) {
  testing::TempDir dir("storage_precision_21");
  Table t = table_22(false);
  t.set_attribute("format_version", "2.1");  // e.g. merging shards written before 2.2
  write_table(t, dir / "t.h5");
  const OnDisk d = on_disk(dir / "t.h5", "/left/creep/fx");
  EXPECT_EQ(d.type, H5T_IEEE_F64LE);
  EXPECT_EQ(d.significand_bits, -1);
  testing::expect_same_datasets(t, read_table(dir / "t.h5"));
}

}  // namespace
}  // namespace railtab
