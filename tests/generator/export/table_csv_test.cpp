// SPDX-License-Identifier: Apache-2.0
// railtab export's CSV (generator/export/table_csv): on a small table with physical creepage axes,
// every row's state is a node of the file and its forces and status are that node's stored values
// (read back from the file, not through the lookup); errors name the table or the output.
#include "export/table_csv.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "core/check.hpp"
#include "engine/sweep.hpp"
#include "generator/test_tables.hpp"
#include "kernel/contact_kernel.hpp"
#include "scene/scene.hpp"
#include "table/table_io.hpp"

namespace railtab::table_csv_test {  // own namespace: unity builds compile several test files as one
namespace {

constexpr const char* kScene = R"(
[scene]
name = "small"
[profiles]
wheel = "s1002"
rail = "uic60"
[contact]
normal_model = "hertz"
[grid]
y = [-0.004, 0.0, 0.0035, 0.008]
equilibrium_roll = true
load = [60e3, 90e3]
xi = [-0.002, 0.0, 0.002]
eta = [-0.001, 0.001]
)";

std::vector<std::vector<std::string>> parse_csv(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> fields;
    std::istringstream l(line);
    for (std::string f; std::getline(l, f, ',');) fields.push_back(f);
    rows.push_back(fields);
  }
  return rows;
}

const TableDataset& find(const Table& t, const std::string& group, const std::string& name) {
  const TableDataset* d = t.group(group)->find(name);
  EXPECT_NE(d, nullptr) << group << "/" << name;
  return *d;
}

TEST(TableCsv, RowsAreTheFilesNodesWithTheirStoredValues) {
  testing::TempDir dir("table_csv");
  const Scene scene = parse_scene(kScene, "small.toml");
  const SweepResult r = run_sweep(scene, make_contact_kernel(scene), SweepOptions{});
  ASSERT_EQ(r.summary.failures, 0u) << r.summary.first_failure;
  const auto path = dir / "small.h5";
  write_table(r.table, path);
  const Table stored = read_table(path);  // the values as the file holds them (float32 creep outputs)

  std::size_t n = 0;
  const auto rows = parse_csv(table_csv(path, n));
  ASSERT_EQ(rows.size(), n + 1);
  const std::vector<std::string> header = rows[0];
  EXPECT_EQ(header[1], "y_m");
  EXPECT_EQ(header[8], "fx_N");
  const auto column = [&](const std::string& name) {
    for (std::size_t k = 0; k < header.size(); ++k)
      if (header[k] == name) return k;
    ADD_FAILURE() << "no column " << name;
    return std::size_t{0};
  };
  // 4 y x 2 loads x 3 xi x 2 eta x 2 slots per wheel, in the creep datasets' order, left first.
  const std::size_t per_wheel = find(stored, "left/creep", "fx").size();
  ASSERT_EQ(per_wheel, 4u * 2 * 3 * 2 * 2);
  ASSERT_EQ(n, 2 * per_wheel);
  const TableAxis& y = *stored.axis("y");
  const TableAxis& xi = *stored.axis("xi");
  const TableAxis& eta = *stored.axis("eta");
  const TableAxis& load = *stored.axis("load");
  const std::vector<double>& roll = find(stored, "", "equilibrium_roll").values;
  int loaded = 0;
  for (std::size_t row = 0; row < n; ++row) {
    const auto& f = rows[row + 1];
    const std::string side = row < per_wheel ? "left" : "right";
    const std::size_t k = row % per_wheel;
    // C order (y, load, xi, eta, slot), slot fastest.
    const std::size_t slot = k % 2, ie = (k / 2) % 2, ix = (k / 4) % 3, il = (k / 12) % 2, iy = k / 24;
    SCOPED_TRACE(side + " row " + std::to_string(row));
    EXPECT_EQ(f[column("wheel")], side);
    EXPECT_EQ(std::stod(f[column("y_m")]), y.values[iy]);
    EXPECT_EQ(std::stod(f[column("roll_rad")]), roll[iy]);
    EXPECT_EQ(std::stod(f[column("load_N")]), load.values[il]);
    EXPECT_EQ(std::stod(f[column("xi")]), xi.values[ix]);
    EXPECT_EQ(std::stod(f[column("eta")]), eta.values[ie]);
    EXPECT_EQ(std::stod(f[column("phi_rad_per_m")]), 0.0);
    EXPECT_EQ(std::stoul(f[column("slot")]), slot);
    EXPECT_EQ(std::stod(f[column("fx_N")]), find(stored, side + "/creep", "fx").values[k]);
    EXPECT_EQ(std::stod(f[column("fy_N")]), find(stored, side + "/creep", "fy").values[k]);
    EXPECT_EQ(std::stod(f[column("mz_Nm")]), find(stored, side + "/creep", "mz").values[k]);
    EXPECT_EQ(std::stod(f[column("normal_force_N")]), find(stored, side + "/creep", "normal_force").values[k]);
    EXPECT_EQ(std::stod(f[column("contact_angle_rad")]),
              find(stored, side + "/geometry", "contact_angle").values[iy * 2 + slot]);
    EXPECT_EQ(std::stoul(f[column("status")]), find(stored, side + "/creep", "status").status[k]);
    loaded += std::stod(f[column("normal_force_N")]) > 0.0 && std::stod(f[column("fx_N")]) != 0.0;
  }
  EXPECT_GT(loaded, 50);  // the comparison saw real creep forces
}

TEST(TableCsv, ErrorsNameTheInput) {
  testing::TempDir dir("table_csv_errors");
  std::size_t n = 0;
  const auto missing = dir / "missing.h5";
  try {
    table_csv(missing, n);
    ADD_FAILURE() << "no error for a missing table";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
  }
  // A table without creep part: the sweep always writes one, so it is removed (the format makes
  // creep and wear optional; the lookup loads such a table).
  const Scene scene = parse_scene(kScene, "small.toml");
  Table table = run_sweep(scene, make_contact_kernel(scene), SweepOptions{}).table;
  std::erase_if(table.groups, [](const TableGroup& g) {
    return g.path.ends_with("/creep") || g.path.ends_with("/wear");
  });
  const auto path = dir / "normal_only.h5";
  write_table(table, path);
  try {
    table_csv(path, n);
    ADD_FAILURE() << "no error for a table without creep part";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no creep part"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
  const std::string unwritable = "/proc/railtab-not-writable/out.csv";
  try {
    write_table_csv(path, unwritable);
    ADD_FAILURE() << "no error for an unwritable output";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(unwritable), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace railtab::table_csv_test
