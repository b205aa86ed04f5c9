// SPDX-License-Identifier: Apache-2.0
// The CSV of `railtab export`: walks the creep part's nodes of a table file, maps normalised creep
// coordinates back to physical creepages, and asks the lookup for the forces at each node state.
#include "export/table_csv.hpp"

#include <fmt/format.h>

#include <array>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/check.hpp"
#include "core/status.hpp"
#include "kernel/creep_map.hpp"
#include "railtab/lookup.hpp"
#include "table/output_file.hpp"
#include "table/table_io.hpp"

namespace railtab {
namespace {

namespace lk = railtab::lookup;

constexpr const char* kHeader =
    "wheel,y_m,roll_rad,load_N,xi,eta,phi_rad_per_m,slot,fx_N,fy_N,mz_Nm,normal_force_N,contact_angle_rad,"
    "track_lateral_N,track_vertical_N,status,status_names\n";
constexpr std::array<const char*, 3> kCreepages = {"xi", "eta", "phi"};

// Flat index into `d` of the node whose index along each named axis is `at` (axes `d` lacks are
// ignored: the normal part has no creepage axes).
std::size_t flat_index(const TableDataset& d, const std::map<std::string, std::size_t>& at) {
  std::size_t k = 0;
  for (std::size_t a = 0; a < d.axes.size(); ++a) k = k * d.shape[a] + at.at(d.axes[a]);
  return k;
}

const TableDataset& dataset(const Table& t, const std::string& group, const std::string& name,
                            const std::filesystem::path& path) {
  const TableGroup* g = t.group(group);
  const TableDataset* d = g ? g->find(name) : nullptr;
  RAILTAB_CHECK(d != nullptr, "{}: no dataset /{}/{}", path.string(), group, name);
  return *d;
}

}  // namespace

std::string table_csv(const std::filesystem::path& path, std::size_t& rows) {
  const lk::Table lookup = [&] {
    try {
      return lk::Table::load(path.string());
    } catch (const lk::LoadError& e) {
      throw Error(e.what());
    }
  }();
  RAILTAB_CHECK(lookup.has_part(lk::kCreep), "{}: the table has no creep part: no creep forces to export", path.string());
  const Table table = read_table(path);

  // Normalised creep coordinates: the physical range and knee of each swept creepage.
  struct Map {
    bool normalised = false;
    double lo = 0.0, hi = 0.0, knee = 1.0;
  };
  std::array<Map, 3> maps{};
  if (const std::string* text = table.attribute("creep_map")) {
    const nlohmann::json j = nlohmann::json::parse(*text);
    for (std::size_t c = 0; c < kCreepages.size(); ++c) {
      const std::string name = kCreepages[c];
      if (!j.contains(name + "_min")) continue;  // not swept
      maps[c] = {true, j.at(name + "_min").get<double>(), j.at(name + "_max").get<double>(),
                 j.value(name + "_knee", 1.0)};
    }
  }
  const std::vector<double>* roll_by_y = nullptr;
  if (const TableGroup* root = table.group("")) {
    if (const TableDataset* d = root->find("equilibrium_roll")) roll_by_y = &d->values;
  }

  std::string out = kHeader;
  rows = 0;
  for (int w = 0; w < 2; ++w) {
    const std::string side = w == 0 ? "left" : "right";
    const TableDataset& node_status = dataset(table, side + "/creep", "status", path);
    std::array<const TableDataset*, 3> scales{};
    for (std::size_t c = 0; c < kCreepages.size(); ++c) {
      if (maps[c].normalised)
        scales[c] = &dataset(table, side + "/normal", std::string("creep_scale_") + kCreepages[c], path);
    }
    std::map<std::string, std::size_t> at;
    for (std::size_t k = 0; k < node_status.size(); ++k) {
      // The node's index along each axis (C order, last fastest).
      std::size_t rest = k;
      for (std::size_t a = node_status.axes.size(); a-- > 0;) {
        at[node_status.axes[a]] = rest % node_status.shape[a];
        rest /= node_status.shape[a];
      }
      const int slot = static_cast<int>(at.at("slot"));
      lk::State s = lookup.default_state();
      double* state[] = {&s.y, &s.roll, &s.load, &s.xi, &s.eta, &s.phi};
      for (int v = 0; v < lk::kNumVariables; ++v) {
        const std::string name = lk::variable_name(v);
        const TableAxis* axis = table.axis(name);
        if (!at.count(name) || !axis) continue;  // fixed (default_state has it) or following the equilibrium
        const double node = axis->values[at[name]];
        *state[v] = node;
        if (v >= lk::kXi && maps[static_cast<std::size_t>(v - lk::kXi)].normalised) {
          const std::size_t c = static_cast<std::size_t>(v - lk::kXi);
          const double scale = scales[c]->values[flat_index(*scales[c], at)];
          *state[v] = creep_map::physical(node, maps[c].lo, maps[c].hi, scale * maps[c].knee);
        }
      }
      const lk::Result r = lookup.query(static_cast<lk::Wheel>(w), s);
      const lk::TrackForces f = lk::track_forces(static_cast<lk::Wheel>(w), r);
      const lk::Contact& c = r.contact[slot];
      // Roll following the equilibrium is not a query input; the CSV gives the node's roll.
      const double roll = roll_by_y && at.count("y") ? (*roll_by_y)[at["y"]] : s.roll;
      const StatusBits bits = node_status.status[k];
      std::string names = status::describe(bits);
      for (char& ch : names) ch = ch == ',' ? ' ' : ch;  // one CSV field, no quoting
      out += fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},"
                         "{:.17g},{:.17g},{},{}\n",
                         side, s.y, roll, s.load, s.xi, s.eta, s.phi, slot, c.value[lk::kFx], c.value[lk::kFy],
                         c.value[lk::kMz], c.value[lk::kNormalForce], c.value[lk::kContactAngle], f.lateral[slot],
                         f.vertical[slot], bits, names);
      ++rows;
    }
  }
  return out;
}

std::size_t write_table_csv(const std::filesystem::path& table, const std::filesystem::path& output) {
  check_output_path(output, {table});
  std::size_t rows = 0;
  const std::string text = table_csv(table, rows);
  write_text_file(output, text, {table});
  return rows;
}

}  // namespace railtab
