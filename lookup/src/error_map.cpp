// SPDX-License-Identifier: Apache-2.0
// The error map of format 2.3 (/error_map, docs/table-format.md "Error map"): read at load,
// served by Table::error_estimate for the region (y band x slot) a query lands in.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "hdf5_file.hpp"
#include "table_data.hpp"

namespace railtab::lookup {
namespace detail {
namespace {

constexpr const char* kQuantity[kErrorQuantities] = {"fx", "fy", "mz", "normal_force", "contact_angle"};

std::vector<ErrorStats> read_comparison(const Hdf5File& f, const std::string& group, std::size_t bands, int slots) {
  const std::vector<hsize_t> shape{bands, static_cast<hsize_t>(slots)};
  const std::string source = "/error_map/y_band_start and the slot axis";
  std::vector<ErrorStats> out(bands * static_cast<std::size_t>(slots));
  const auto n = f.read_doubles(group + "/samples", shape, source).values;
  for (std::size_t r = 0; r < out.size(); ++r) {
    if (!(n[r] >= 0.0)) f.fail(group + "/samples: a count that is negative or NaN");
    out[r].samples = n[r];
  }
  for (int q = 0; q < kErrorQuantities; ++q)
    for (int stat = 0; stat < 2; ++stat) {
      const std::string name = group + "/" + kQuantity[q] + (stat == 0 ? "_rms" : "_max");
      const auto v = f.read_doubles(name, shape, source).values;
      for (std::size_t r = 0; r < out.size(); ++r) {
        if (v[r] < 0.0 || std::isinf(v[r])) f.fail(name + ": an error that is negative or infinite");
        (stat == 0 ? out[r].rms : out[r].max)[q] = v[r];
      }
    }
  return out;
}

}  // namespace

void read_error_map(const Hdf5File& f, TableData& d) {
  if (!f.exists("/error_map")) return;  // before 2.3
  const auto start = f.read_axis("/error_map/y_band_start", 1'000'000).values;
  const auto end = f.read_doubles("/error_map/y_band_end", {start.size()}, "/error_map/y_band_start").values;
  for (std::size_t b = 0; b < start.size(); ++b)
    if (!(start[b] < end[b]) || (b > 0 && start[b] < end[b - 1]))
      f.fail("/error_map: y bands that are not increasing and disjoint");
  TableData::ErrorMap& m = d.error_map;
  m.band_start = start;
  m.band_end = end;
  m.table_vs_model = read_comparison(f, "/error_map/table_vs_model", start.size(), d.n_slots);
  m.exact = f.exists("/error_map/model_vs_exact");
  if (m.exact) m.model_vs_exact = read_comparison(f, "/error_map/model_vs_exact", start.size(), d.n_slots);
  const auto sampling = f.string_attribute("/", "error_map_sampling");
  m.same_model = sampling && sampling->find("\"model_vs_exact\":\"same model\"") != std::string::npos;
  m.present = true;
}

}  // namespace detail

bool Table::has_error_map() const noexcept { return data_->error_map.present; }

bool Table::error_estimate(double y, int slot, ErrorEstimate& estimate) const noexcept {
  estimate = ErrorEstimate{};
  const detail::TableData::ErrorMap& m = data_->error_map;
  if (!m.present || !(y == y) || slot < 0 || slot >= data_->n_slots) return false;
  // The band whose [start, end] holds y (the upper one on a shared edge).
  const auto it = std::upper_bound(m.band_start.begin(), m.band_start.end(), y);
  if (it == m.band_start.begin()) return false;
  const std::size_t b = static_cast<std::size_t>(it - m.band_start.begin()) - 1;
  if (y > m.band_end[b]) return false;
  const std::size_t r = b * static_cast<std::size_t>(data_->n_slots) + static_cast<std::size_t>(slot);
  estimate.available = 1;
  estimate.exact_measured = m.exact ? 1 : 0;
  estimate.same_model = m.same_model ? 1 : 0;
  estimate.y_band_start = m.band_start[b];
  estimate.y_band_end = m.band_end[b];
  estimate.table_vs_model = m.table_vs_model[r];
  if (m.exact) estimate.model_vs_exact = m.model_vs_exact[r];
  return true;
}

}  // namespace railtab::lookup
