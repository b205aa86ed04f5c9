// SPDX-License-Identifier: Apache-2.0
// Text summary of a table file: provenance, axes and the range of every output.
#include "table/inspect.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <nlohmann/json.hpp>
#include <sstream>

namespace railtab {
namespace {

std::string shape_text(const TableDataset& d) {
  if (d.shape.empty()) return "scalar";
  std::string s;
  for (std::size_t i = 0; i < d.shape.size(); ++i) s += fmt::format("{}{}={}", i ? " x " : "", d.axes[i], d.shape[i]);
  return s;
}

std::string bytes_text(double bytes) {
  if (bytes >= 1024.0 * 1024.0) return fmt::format("{:.1f} MiB", bytes / (1024.0 * 1024.0));
  if (bytes >= 1024.0) return fmt::format("{:.1f} KiB", bytes / 1024.0);
  return fmt::format("{:.0f} B", bytes);
}

// Cells per status bit, and cells with status 0 (no contact in that slot).
void print_status(const TableDataset& d, std::ostream& out) {
  std::array<std::size_t, 32> count{};
  std::size_t empty = 0;
  for (StatusBits s : d.status) {
    if (s == 0) ++empty;
    for (unsigned b = 0; b < 32; ++b) count[b] += (s >> b) & 1u;
  }
  out << fmt::format("      status counts ({} cells): no contact {}", d.status.size(), empty);
  for (unsigned b = 0; b < 32; ++b) {
    if (count[b] > 0) out << fmt::format(", {} {}", status::describe(1u << b), count[b]);
  }
  out << "\n";
}

nlohmann::ordered_json status_counts(const TableDataset& d) {
  std::array<std::size_t, 32> count{};
  std::size_t empty = 0;
  for (StatusBits s : d.status) {
    if (s == 0) ++empty;
    for (unsigned b = 0; b < 32; ++b) count[b] += (s >> b) & 1u;
  }
  nlohmann::ordered_json j{{"cells", d.status.size()}, {"no_contact", empty}};
  for (unsigned b = 0; b < 32; ++b)
    if (count[b] > 0) j[status::describe(1u << b)] = count[b];
  return j;
}

}  // namespace

std::string table_summary_json(const Table& table, const std::string& path, std::uintmax_t file_bytes,
                               bool checksums_verified) {
  nlohmann::ordered_json out;
  out["file"] = path;
  out["file_bytes"] = file_bytes;
  out["checksums_verified"] = checksums_verified;
  nlohmann::ordered_json attributes = nlohmann::ordered_json::object();
  for (const auto& [name, value] : table.attributes) {
    // Attributes holding JSON text (models, fixed_axes, accuracy_*) as objects, the rest as text.
    const auto parsed = nlohmann::ordered_json::parse(value, nullptr, false);
    attributes[name] = name != "scene" && parsed.is_object() ? parsed : nlohmann::ordered_json(value);
  }
  out["attributes"] = attributes;
  out["axes"] = nlohmann::ordered_json::array();
  for (const TableAxis& a : table.axes) {
    out["axes"].push_back({{"name", a.name}, {"units", a.units}, {"description", a.description},
                           {"size", a.values.size()}, {"min", a.values.front()}, {"max", a.values.back()}});
  }
  out["groups"] = nlohmann::ordered_json::array();
  for (const TableGroup& g : table.groups) {
    nlohmann::ordered_json gj{{"path", "/" + g.path}, {"datasets", nlohmann::ordered_json::array()}};
    for (const TableDataset& d : g.datasets) {
      nlohmann::ordered_json dj{{"name", d.name},   {"units", d.units}, {"description", d.description},
                                {"axes", d.axes},   {"shape", d.shape}, {"storage_bytes", d.storage_bytes}};
      if (d.is_status && d.name == "status") dj["status_counts"] = status_counts(d);  // not the jump kinds
      gj["datasets"].push_back(dj);
    }
    out["groups"].push_back(gj);
  }
  return out.dump(2);
}

void print_table_summary(const Table& table, const std::string& path, std::uintmax_t file_bytes, bool print_scene,
                         std::ostream& out) {
  out << fmt::format("{}  ({})\n", path, bytes_text(static_cast<double>(file_bytes)));
  out << "provenance:\n";
  for (const auto& [name, value] : table.attributes) {
    if (name == "scene") {
      std::size_t lines = static_cast<std::size_t>(std::count(value.begin(), value.end(), '\n'));
      out << fmt::format("  {:16} {} lines of TOML{}\n", name, lines, print_scene ? ":" : " (--scene prints it)");
      if (print_scene) {
        std::istringstream text(value);
        for (std::string line; std::getline(text, line);) out << "    | " << line << "\n";
      }
    } else {
      out << fmt::format("  {:16} {}\n", name, value);
    }
  }
  out << "axes:\n";
  for (const TableAxis& a : table.axes) {
    out << fmt::format("  {:6} {:5} values  [{:.6g}, {:.6g}] {}  {}\n", a.name, a.values.size(), a.values.front(),
                       a.values.back(), a.units, a.description);
  }
  for (const TableGroup& g : table.groups) {
    std::size_t raw = 0, stored = 0;
    for (const TableDataset& d : g.datasets) {
      raw += d.size() * (d.is_status ? sizeof(StatusBits) : sizeof(double));
      stored += d.storage_bytes;
    }
    out << fmt::format("{}  ({} datasets, {} in memory, {} on disk)\n", g.path.empty() ? "/ (root)" : "/" + g.path,
                       g.datasets.size(), bytes_text(static_cast<double>(raw)), bytes_text(static_cast<double>(stored)));
    for (const TableDataset& d : g.datasets) {
      out << fmt::format("    {:16} [{}] {}  {}\n", d.name, d.units, shape_text(d), d.description);
      if (d.is_status && d.name == "status") print_status(d, out);  // not the jump kinds
    }
  }
}

}  // namespace railtab
