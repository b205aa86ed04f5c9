// Table: loading entry point, accessors and the query path.
#include <algorithm>
#include <cmath>

#include "interpolate.hpp"
#include "part_spec.hpp"
#include "railtab/lookup.hpp"
#include "table_data.hpp"
#include "table_load.hpp"

namespace railtab::lookup {
namespace {

// A fixed (untabulated) variable counts as "at its fixed value" within this relative tolerance
// (absolute below magnitude 1): round-off in the caller's state must not flag kOutOfRange.
constexpr double kFixedTolerance = 1e-9;

void zero_contact(Contact& c, StatusBits status) noexcept {
  for (double& v : c.value) v = 0.0;
  for (StatusBits& s : c.part_status) s = 0;
  c.status = status;
}

}  // namespace

LoadError::LoadError(std::string path, const std::string& problem)
    : std::runtime_error("railtab lookup: cannot load table '" + path + "': " + problem),
      path_(std::move(path)) {}

Table::Table(std::shared_ptr<const detail::TableData> data) : data_(std::move(data)) {}

Table Table::load(const std::string& path, const LoadOptions& options) {
  return Table(detail::load_table_data(path, options));
}

void Table::query(Wheel wheel, const State& state, Result& result) const noexcept {
  using namespace detail;
  const TableData& d = *data_;
  const double v[kNumVars] = {state.y, state.roll, state.load, state.xi, state.eta, state.phi};
  AxisLoc loc[kNumVars];
  StatusBits q = 0;  // query bits, ORed into every slot
  for (int var = 0; var < kNumVars; ++var) {
    if (d.tabulated[var]) {
      if (!std::isfinite(v[var])) q |= status::kInvalidInput;
      else if (d.axis[var].locate(v[var], loc[var])) q |= status::kOutOfRange;
    } else if (d.fixed[var]) {
      const double f = d.fixed_value[var];
      if (!std::isfinite(v[var])) q |= status::kInvalidInput;
      else if (std::abs(v[var] - f) > kFixedTolerance * std::max(1.0, std::abs(f)))
        q |= status::kOutOfRange;
    }  // a variable the table neither tabulates nor fixes does not affect it: ignored
  }
  const int w = static_cast<int>(wheel);
  if (w != 0 && w != 1) q |= status::kInvalidInput;
  const int ns = d.n_slots;
  result.n_slots = ns;
  result.status = q;
  if (q & status::kInvalidInput) {
    for (int s = 0; s < ns; ++s) zero_contact(result.contact[s], status::kInvalidInput);
    return;
  }

  StatusBits any[kMaxSlots] = {}, all[kMaxSlots] = {~0u, ~0u, ~0u, ~0u};
  static_assert(kMaxSlots == 4, "initialiser lists kMaxSlots entries");
  for (int p = 0; p < kNumParts; ++p) {
    if (d.has_part[p]) continue;
    const PartSpec& spec = kPartSpecs[p];
    for (int s = 0; s < ns; ++s) {
      for (int k = 0; k < spec.n_out; ++k) result.contact[s].value[spec.first_output + k] = 0.0;
      result.contact[s].part_status[p] = 0;
    }
  }
  double values[kMaxValues];
  StatusBits block_status[kMaxStatuses];
  for (int b = 0; b < d.n_blocks; ++b) {
    const Block& block = d.block[w][b];
    if (d.method == Method::kLinear)
      interpolate_linear(block, loc, values, block_status);
    else
      interpolate_cubic(block, d.axis, loc, d.method == Method::kMonotoneCubic, values,
                        block_status);
    // Scatter in record order: parts, slots, outputs; then statuses: parts, slots.
    const double* src = values;
    const StatusBits* st = block_status;
    for (int k = 0; k < block.n_parts; ++k) {
      const int p = block.part[k];
      const PartSpec& spec = kPartSpecs[p];
      for (int s = 0; s < ns; ++s, src += spec.n_out) {
        double* out = result.contact[s].value + spec.first_output;
        for (int o = 0; o < spec.n_out; ++o) out[o] = src[o];
      }
      for (int s = 0; s < ns; ++s, ++st) {
        result.contact[s].part_status[p] = *st;
        any[s] |= *st;
        all[s] &= *st;
      }
    }
  }
  for (int s = 0; s < ns; ++s)
    result.contact[s].status =
        (any[s] & ~status::kConverged) | (all[s] & status::kConverged) | q;
}

Result Table::query(Wheel wheel, const State& state) const noexcept {
  Result r;
  query(wheel, state, r);
  return r;
}

void Table::query(std::span<const Query> queries, std::span<Result> results) const noexcept {
  const std::size_t n = std::min(queries.size(), results.size());
  for (std::size_t k = 0; k < n; ++k) query(queries[k].wheel, queries[k].state, results[k]);
}

const std::string& Table::path() const { return data_->path; }
Method Table::method() const { return data_->method; }
int Table::n_slots() const { return data_->n_slots; }
bool Table::has_part(Part part) const {
  return part >= 0 && part < kNumParts && data_->has_part[part];
}
const std::vector<AxisInfo>& Table::axes() const { return data_->axes_info; }
const std::vector<std::pair<std::string, double>>& Table::fixed_axes() const {
  return data_->fixed_list;
}
const std::string& Table::format_version() const { return data_->format_version; }
const std::string& Table::scene_name() const { return data_->scene_name; }

State Table::default_state() const {
  const detail::TableData& d = *data_;
  double v[detail::kNumVars] = {};
  for (int var = 0; var < detail::kNumVars; ++var)
    if (d.fixed[var]) v[var] = d.fixed_value[var];
  return State{v[0], v[1], v[2], v[3], v[4], v[5]};
}

std::size_t Table::memory_bytes() const {
  std::size_t bytes = 0;
  for (const auto& wheel : data_->block)
    for (const auto& block : wheel) bytes += block.data.size() * sizeof(double);
  return bytes;
}

}  // namespace railtab::lookup
