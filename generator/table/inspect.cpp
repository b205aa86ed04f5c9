// SPDX-License-Identifier: Apache-2.0
// Text summary of a table file: provenance, axes and the range of every output.
#include "table/inspect.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
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

// The error map (format 2.3): a dataset of /error_map/<comparison>, or nullptr.
const TableDataset* error_dataset(const Table& table, const std::string& comparison, const std::string& name) {
  const TableGroup* g = table.group(std::string(kErrorMapGroup) + "/" + comparison);
  return g ? g->find(name) : nullptr;
}

std::string slot_text(std::size_t slot) {  // = lookup::slot_name
  return slot == 0 ? "tread" : slot == 1 ? "flange" : fmt::format("slot{}", slot);
}

std::string number_text(double v, const char* format) {
  return std::isnan(v) ? std::string("-") : fmt::format(fmt::runtime(format), v);
}

// Per region (y band x slot) with samples: the table against its model and the model against the
// exact model (fx, fy as % of mu N, normal force %, contact angle mrad); then the worst regions.
void print_error_map(const Table& table, std::ostream& out) {
  const TableGroup* root = table.group(kErrorMapGroup);
  const TableDataset* n = error_dataset(table, "table_vs_model", "samples");
  if (!root || !n || !root->find("y_band_start") || !root->find("y_band_end")) return;
  const std::vector<double>& y0 = root->find("y_band_start")->values;
  const std::vector<double>& y1 = root->find("y_band_end")->values;
  const bool exact = error_dataset(table, "model_vs_exact", "samples") != nullptr;
  auto value = [&](const char* comparison, const char* name, std::size_t r) {
    const TableDataset* d = error_dataset(table, comparison, name);
    return d && r < d->values.size() ? d->values[r] : std::nan("");
  };
  out << "error map (/error_map; fx, fy in % of mu N, N in %; max over the region, n samples):\n";
  out << fmt::format("  {:>17} {:6} | {:>4} {:>6} {:>6} {:>6} {:>6} {:>7} | {}\n", "y band [mm]", "slot", "n",
                     "fx rms", "fx max", "fy rms", "fy max", "N max", exact ? "model vs exact: n fx max fy max N max"
                                                                            : "model vs exact: same model");
  const std::size_t slots = n->shape.size() == 2 ? n->shape[1] : 2;
  struct Worst {
    double error;
    std::size_t region;
  };
  std::vector<Worst> worst_table, worst_exact;
  for (std::size_t r = 0; r < n->values.size(); ++r) {
    const std::size_t band = r / slots, slot = r % slots;
    const double ne = exact ? value("model_vs_exact", "samples", r) : 0.0;
    if (!(n->values[r] > 0.0) && !(ne > 0.0)) continue;
    std::string line = fmt::format("  {:>7.2f} .. {:>6.2f} {:6} | {:>4.0f} {:>6} {:>6} {:>6} {:>6} {:>7} |", 1e3 * y0[band],
                                   1e3 * y1[band], slot_text(slot), n->values[r],
                                   number_text(value("table_vs_model", "fx_rms", r), "{:.2f}"),
                                   number_text(value("table_vs_model", "fx_max", r), "{:.2f}"),
                                   number_text(value("table_vs_model", "fy_rms", r), "{:.2f}"),
                                   number_text(value("table_vs_model", "fy_max", r), "{:.2f}"),
                                   number_text(value("table_vs_model", "normal_force_max", r), "{:.2f}"));
    if (exact)
      line += fmt::format(" {:>2.0f} {:>6} {:>6} {:>6}", ne, number_text(value("model_vs_exact", "fx_max", r), "{:.2f}"),
                          number_text(value("model_vs_exact", "fy_max", r), "{:.2f}"),
                          number_text(value("model_vs_exact", "normal_force_max", r), "{:.2f}"));
    out << line << "\n";
    auto creep_max = [&](const char* c) {
      const double a = value(c, "fx_max", r), b = value(c, "fy_max", r);
      return std::isnan(a) ? b : std::isnan(b) ? a : std::max(a, b);
    };
    if (!std::isnan(creep_max("table_vs_model"))) worst_table.push_back({creep_max("table_vs_model"), r});
    if (exact && !std::isnan(creep_max("model_vs_exact"))) worst_exact.push_back({creep_max("model_vs_exact"), r});
  }
  auto print_worst = [&](std::vector<Worst>& w, const char* what) {
    std::stable_sort(w.begin(), w.end(), [](const Worst& a, const Worst& b) { return a.error > b.error; });
    out << fmt::format("  worst regions, {} (max of fx, fy in % of mu N):", what);
    for (std::size_t k = 0; k < std::min<std::size_t>(3, w.size()); ++k)
      out << fmt::format("{} {:.2f} at y {:.2f} .. {:.2f} mm {}", k ? "," : "", w[k].error, 1e3 * y0[w[k].region / slots],
                         1e3 * y1[w[k].region / slots], slot_text(w[k].region % slots));
    out << "\n";
  };
  print_worst(worst_table, "table vs model");
  if (exact) print_worst(worst_exact, "model vs exact");
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
  print_error_map(table, out);
}

}  // namespace railtab
