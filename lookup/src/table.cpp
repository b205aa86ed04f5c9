// SPDX-License-Identifier: Apache-2.0
// Table: loading entry point, accessors and the query path.
#include <algorithm>
#include <cmath>

#include "block_gradient.hpp"
#include "interpolate.hpp"
#include "low_confidence.hpp"
#include "part_spec.hpp"
#include "railtab/lookup.hpp"
#include "table_data.hpp"
#include "table_load.hpp"

namespace railtab::lookup {
namespace {

void zero_contact(Contact& c, StatusBits status) noexcept {
  for (double& v : c.value) v = 0.0;
  for (StatusBits& s : c.part_status) s = 0;
  c.status = status;
  c.reserved = 0;
}

}  // namespace

LoadError::LoadError(std::string path, const std::string& problem)
    : std::runtime_error("railtab lookup: cannot load table '" + path + "': " + problem),
      path_(std::move(path)) {}

Table::Table(std::shared_ptr<const detail::TableData> data) : data_(std::move(data)) {}

Table Table::load(const std::string& path, const LoadOptions& options) {
  return Table(detail::load_table_data(path, options));
}

namespace {

// Places every tabulated variable of `state` in its cell (loc, indexed by Var) and returns the
// query bits: kOutOfRange (clamped, or a fixed variable off its value), kInvalidInput (NaN/inf).
// With normalised creep coordinates (format 2.1) the creepages are not located here (their cell
// depends on the slot's scales, interpolate_normalised_creep): `creepage` gets them, clamped to the physical
// range of the table (kOutOfRange when clamped), or their fixed values.
StatusBits locate_state(const detail::TableData& d, const State& state, detail::AxisLoc* loc,
                        double* creepage) noexcept {
  using namespace detail;
  double v[kNumVars];
  table_variables(d, state, v);
  const CreepMap& map = d.creep_map;
  // A variable the table neither tabulates nor fixes does not affect it: ignored.
  bool finite = true, out = false;
  for (int k = 0; k < d.n_located; ++k) {
    const int var = d.located_var[k];
    const double x = v[var];
    if (!std::isfinite(x)) {
      finite = false;
      continue;
    }
    out |= d.axis[var].locate_fast(x, loc[var]);
  }
  for (int k = 0; k < d.n_clamped; ++k) {  // normalised creep coordinates' creepages
    const int c = d.clamped_var[k] - kVarXi;
    const double x = v[kVarXi + c];
    const bool ok = std::isfinite(x);  // not finite: kInvalidInput alone, as for the others
    finite &= ok;
    out |= ok && (x < map.lo[c] || x > map.hi[c]);
    creepage[c] = std::min(std::max(x, map.lo[c]), map.hi[c]);
  }
  if (map.active)
    for (int c = 0; c < 3; ++c)
      if (!map.swept[c]) creepage[c] = d.fixed[kVarXi + c] ? d.fixed_value[kVarXi + c] : 0.0;
  for (int k = 0; k < d.n_fixed; ++k) {
    const int var = d.fixed_var[k];
    const double x = v[var];
    const bool ok = std::isfinite(x);
    finite &= ok;
    out |= ok && std::abs(x - d.fixed_value[var]) > d.fixed_tolerance[var];
  }
  return (finite ? 0u : status::kInvalidInput) | (out ? status::kOutOfRange : 0u);
}
// Runs one block's kernel for slots [slot_begin, slot_end); grad (cubic only): null, or one
// BlockGradient per slot for the kernel's derivatives.
inline void interpolate_block(const detail::TableData& d, const detail::Block& block,
                              const detail::AxisLoc* loc, int slot_begin, int slot_end,
                              Contact* contact, detail::BlockGradient* grad = nullptr) noexcept {
  if (d.method == Method::kLinear) {
    block.linear(block, loc, slot_begin, slot_end, contact);
  } else if (d.method == Method::kCubic) {
    block.cubic(block, d.axis, loc, slot_begin, slot_end, contact, grad);
  } else {
    block.monotone(block, d.axis, loc, slot_begin, slot_end, contact, nullptr);
  }
}

// Format 2.1: the creep block of one slot. The slot's scales at (y, roll, load) (their reciprocals
// interpolated, creep_map.hpp) map the physical
// creepages to the block's v coordinates; the interpolated F / (mu N) minus the law, plus the law
// at the query's normalised creepage, times mu N (the creep point's own normal force, already in
// c.value[kNormalForce]: from the creep part when it has it, else from the normal part) gives N.
void interpolate_normalised_creep(const detail::TableData& d, const detail::Block& block, int w,
                                  const detail::AxisLoc* loc, const double* creepage, int slot,
                                  Contact& c, detail::BlockGradient* grad) noexcept {
  using namespace detail;
  const CreepMap& map = d.creep_map;
  double inv_scale[3];
  interpolate_scales(map, w, slot, loc, inv_scale);
  // A cell over which the block is zero with one set of statuses (FastPath::empty_creep; linear
  // value queries only): its zeros and statuses, without the creepage cells and the sum (the same bytes).
  const FastPath& fp = d.fast;
  std::size_t empty_cell = static_cast<std::size_t>(slot);
  for (int k = 0; k < fp.empty_outer; ++k)
    empty_cell = empty_cell * static_cast<std::size_t>(block.size[k] - 1) + static_cast<std::size_t>(loc[block.var[k]].i);
  const bool skip = fp.empty_outer > 0 && !grad && fp.empty_creep[w][empty_cell] == 2;
  AxisLoc slot_loc[kNumVars];
  for (int var = 0; var < kNumVars; ++var) slot_loc[var] = loc[var];
  double x[3];  // normalised creepages xi', eta', psi'
  for (int k = 0; k < 3; ++k) {
    const double inv = inv_scale[k];
    x[k] = creepage[k] * inv;
    if (map.swept[k] && !skip)
      d.axis[kVarXi + k].locate_fast(creep_coordinate_normalised(x[k] * map.kinv[k], map.lo_k[k] * inv, map.hi_k[k] * inv),
                                     slot_loc[kVarXi + k]);
  }
  if (skip) {
    for (int k = 0; k < block.n_values; ++k) c.value[block.output_of[k]] = 0.0;
    for (int p = 0; p < block.n_parts; ++p) c.part_status[block.part[p]] = fp.empty_status[w][2 * empty_cell + p];
  } else {
    interpolate_block(d, block, slot_loc, slot, slot + 1, &c, grad);
  }
  if (!d.has_part[kCreep]) return;
  const double angle = c.value[kContactAngle];
  double cos_angle = 1.0, sin_angle = 0.0;
  if (map.vertical_share) angle_cos_sin(angle, cos_angle, sin_angle);
  denormalise_creep(map, x, cos_angle, sin_angle, c.value);
}

// Interpolates slots [slot_begin, slot_end) of wheel w into contact[0 .. slot_end-slot_begin-1]
// (values, part statuses, combined status | q). The query must be valid. grads: as query_generic.
void interpolate_slots(const detail::TableData& d, int w, const detail::AxisLoc* loc,
                       const double* creepage, StatusBits q, int slot_begin, int slot_end,
                       Contact* contact, detail::BlockGradient (*grads)[kMaxSlots]) noexcept {
  using namespace detail;
  const int n = slot_end - slot_begin;
  for (int a = 0; a < d.n_absent; ++a) {
    const int p = d.absent_part[a];
    const PartSpec& spec = kPartSpecs[p];
    for (int s = 0; s < n; ++s) {
      for (int k = 0; k < spec.n_out; ++k) contact[s].value[spec.first_output + k] = 0.0;
      contact[s].part_status[p] = 0;
    }
  }
  // A cell a located contact jump may cut: one-sided (jump_side.hpp); all others: one flag test.
  const bool cut = d.has_jumps && jump_cell(d, w, loc);
  AxisLoc stencil_loc[kNumVars];  // cubic methods next to a jump: the stencil kept on the cell's side
  if (d.has_jumps && !cut && d.method != Method::kLinear) {
    std::copy(loc, loc + kNumVars, stencil_loc);
    cubic_stencil_limits(d, w, stencil_loc);
    loc = stencil_loc;
  }
  if (cut) interpolate_jump_cell(d, w, loc, creepage, slot_begin, slot_end, contact);
  else for (int b = 0; b < d.n_blocks; ++b) {
    const Block& block = d.block[w][b];
    if (d.creep_map.active && b == d.creep_block) {
      for (int s = slot_begin; s < slot_end; ++s)
        interpolate_normalised_creep(d, block, w, loc, creepage, s, contact[s - slot_begin],
                                     grads ? &grads[b][s - slot_begin] : nullptr);
      continue;
    }
    interpolate_block(d, block, loc, slot_begin, slot_end, contact, grads ? grads[b] : nullptr);
  }
  for (int s = 0; s < n; ++s) {
    mark_unpaired_contact(d.has_part[kGeometry] && d.has_part[kNormal], d.load_controlled, contact[s]);
    StatusBits any = 0, all = ~0u;
    for (int p = 0; p < kNumParts; ++p) {
      if (!d.has_part[p]) continue;
      any |= contact[s].part_status[p];
      all &= contact[s].part_status[p];
    }
    contact[s].status = (any & ~status::kConverged) | (all & status::kConverged) | q;
    contact[s].reserved = 0;
  }
  // A cubic through finite values can still overshoot the double range (values near 1.8e308):
  // such a contact is failed with zero outputs, never an infinity or NaN flagged converged. The
  // linear method weighs values by weights in [0, 1] and cannot.
  if (d.method != Method::kLinear) {
    for (int s = 0; s < n; ++s) {
      bool finite = true;
      for (const double v : contact[s].value) finite &= std::isfinite(v);
      if (!finite) zero_contact(contact[s], status::kFailed | q);
    }
  }
}

}  // namespace

StatusBits detail::query_generic(const TableData& d, int w, const State& state, int slot_begin, int slot_end,
                                 Contact* contact, BlockGradient (*grads)[kMaxSlots]) noexcept {
  AxisLoc loc[kNumVars];
  double creepage[3];
  StatusBits q = locate_state(d, state, loc, creepage);
  if (w != 0 && w != 1) q |= status::kInvalidInput;
  if (q & status::kInvalidInput) {
    for (int s = 0; s < slot_end - slot_begin; ++s) zero_contact(contact[s], status::kInvalidInput);
    return q;
  }
  interpolate_slots(d, w, loc, creepage, q, slot_begin, slot_end, contact, grads);
  return q;
}

void Table::query(Wheel wheel, const State& state, Result& result) const noexcept {
  const detail::TableData& d = *data_;
  const int wf = static_cast<int>(wheel);
  result.n_slots = d.n_slots;
  if (d.fast.query && (wf == 0 || wf == 1)) {  // fast_path.hpp; false: a variable is not finite
    StatusBits q = 0;
    if (d.fast.query(d, wf, state, 0, d.n_slots, result.contact, q)) {
      result.status = q;
      return;
    }
  }
  result.status = detail::query_generic(d, wf, state, 0, d.n_slots, result.contact, nullptr);
}

void Table::query_slot(Wheel wheel, const State& state, int slot, Contact& contact) const noexcept {
  const detail::TableData& d = *data_;
  const int wf = static_cast<int>(wheel);
  if (d.fast.query && (wf == 0 || wf == 1) && slot >= 0 && slot < d.n_slots) {
    StatusBits q = 0;
    if (d.fast.query(d, wf, state, slot, slot + 1, &contact, q)) return;
  }
  if (slot < 0 || slot >= d.n_slots) {
    zero_contact(contact, status::kInvalidInput);  // as query() does for every slot
    return;
  }
  detail::query_generic(d, wf, state, slot, slot + 1, &contact, nullptr);
}

Contact Table::query_slot(Wheel wheel, const State& state, int slot) const noexcept {
  Contact c;
  query_slot(wheel, state, slot, c);
  return c;
}

Result Table::query(Wheel wheel, const State& state) const noexcept {
  Result r;
  query(wheel, state, r);
  return r;
}

bool Table::query(std::span<const Query> queries, std::span<Result> results) const noexcept {
  if (results.size() < queries.size()) return false;
  for (std::size_t k = 0; k < queries.size(); ++k)
    query(queries[k].wheel, queries[k].state, results[k]);
  return true;
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
  return State{v[0], v[1], v[2], v[3], v[4], v[5], v[6]};
}

std::size_t Table::memory_bytes() const {
  std::size_t bytes = 0;
  for (const auto& wheel : data_->block)
    for (const auto& block : wheel) bytes += block.data.size();  // bytes (records.hpp)
  return bytes;
}

}  // namespace railtab::lookup
