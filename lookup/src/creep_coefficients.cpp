// SPDX-License-Identifier: Apache-2.0
// Linear creep coefficients (creep_coefficients.hpp): reading, interpolation, and the public query.
#include "creep_coefficients.hpp"

#include <cmath>
#include <string>

#include "hdf5_file.hpp"
#include "jump_piece.hpp"
#include "table_data.hpp"

namespace railtab::lookup::detail {
namespace {

const char* const kNames[kCoefficients] = {
    "creep_coefficient_fx_xi", "creep_coefficient_fx_eta", "creep_coefficient_fx_phi",
    "creep_coefficient_fy_xi", "creep_coefficient_fy_eta", "creep_coefficient_fy_phi",
    "creep_coefficient_mz_xi", "creep_coefficient_mz_eta", "creep_coefficient_mz_phi"};

void check_finite(const Hdf5File& f, const std::string& ds, const std::vector<double>& v) {
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i])) f.fail("dataset " + ds + " holds a non-finite value at flat index " + std::to_string(i));
}

// The one-sided values at the jumps of wheel w (read_jumps has filled d.jumps[w]).
void read_at_jumps(const Hdf5File& f, TableData& d, int w) {
  const JumpWheel& j = d.jumps[w];
  const std::size_t ns = static_cast<std::size_t>(d.n_slots), n_load = j.n_load_nodes, count = j.n_jumps;
  std::vector<hsize_t> shape;
  if (j.load_axis) shape.push_back(n_load);
  shape.push_back(count);
  shape.push_back(2);
  shape.push_back(ns);
  std::vector<double>& out = d.coefficients.at_jump[w];
  out.assign(ns * n_load * count * 2 * kCoefficients, 0.0);
  for (int k = 0; k < kCoefficients; ++k) {
    const std::string ds = std::string("/jumps/") + (w == 0 ? "left" : "right") + "/normal/" + kNames[k];
    if (!f.exists(ds)) f.fail("missing dataset " + ds + " (the wheel groups hold the creep coefficients)");
    const auto v = f.read_doubles(ds, shape, "the jump list and the table's axes");
    if (d.checksums_verified && !v.checksummed) f.fail("dataset " + ds + " has no checksum");
    check_finite(f, ds, v.values);
    for (std::size_t i = 0; i < v.values.size(); ++i) {
      const std::size_t s = i % ns, slice = i / ns;  // slice = (load node * jumps + jump) * 2 + side
      out[(s * n_load * count * 2 + slice) * kCoefficients + static_cast<std::size_t>(k)] = v.values[i];
    }
  }
}

}  // namespace

void read_creep_coefficients(const Hdf5File& f, TableData& d) {
  static const char* const wheels[2] = {"/left/normal/", "/right/normal/"};
  int found = 0;
  for (int w = 0; w < 2; ++w)
    for (const char* name : kNames) found += f.exists(std::string(wheels[w]) + name) ? 1 : 0;
  if (found == 0) return;  // format 2.2 and older
  if (!d.has_part[kNormal]) f.fail("creep coefficients without a normal part");
  CreepCoefficientData& c = d.coefficients;
  set_normal_grid(d, c);
  std::vector<hsize_t> expected(c.size, c.size + c.n_dims);
  expected.push_back(static_cast<hsize_t>(d.n_slots));
  const std::size_t ns = static_cast<std::size_t>(d.n_slots);
  for (int w = 0; w < 2; ++w) {
    c.value[w].assign(c.nodes * ns * kCoefficients, 0.0);
    for (int k = 0; k < kCoefficients; ++k) {
      const std::string ds = std::string(wheels[w]) + kNames[k];
      if (!f.exists(ds)) f.fail("missing dataset " + ds + " (the table has other creep coefficients)");
      const auto v = f.read_doubles(ds, expected, "the normal part's axes");
      if (d.checksums_verified && !v.checksummed) f.fail("dataset " + ds + " has no checksum");
      check_finite(f, ds, v.values);
      for (std::size_t i = 0; i < v.values.size(); ++i) {
        const std::size_t node = i / ns, slot = i % ns;
        c.value[w][(slot * c.nodes + node) * kCoefficients + static_cast<std::size_t>(k)] = v.values[i];
      }
    }
    if (d.has_jumps) read_at_jumps(f, d, w);
  }
  c.present = true;
}

void interpolate_creep_coefficients(const TableData& d, int w, const AxisLoc* loc, int slot,
                                    double out[kCoefficients]) noexcept {
  const CreepCoefficientData& c = d.coefficients;
  const double* grid = c.value[w].data() + static_cast<std::size_t>(slot) * c.nodes * kCoefficients;
  if (d.has_jumps && jump_cell(d, w, loc)) {
    // One-sided: the normal part's pieces (list 0) at each load node of the cell, blended in load.
    const JumpWheel& j = d.jumps[w];
    const int nodes = j.load_axis ? 2 : 1;
    const int lc = j.load_axis ? loc[kVarLoad].i : 0;
    const double weight[2] = {j.load_axis ? 1.0 - loc[kVarLoad].t : 1.0, j.load_axis ? loc[kVarLoad].t : 0.0};
    Piece pieces[2][2];
    query_pieces(j, d.axis[kVarY], loc, nodes, pieces);
    one_sided_node_values(c, j, grid, slot_at_jump(j, c.at_jump[w], kCoefficients, slot), kCoefficients, pieces[0],
                          nodes, lc, weight, out);
    return;
  }
  interpolate_node_values(c, grid, kCoefficients, loc, out);
}

}  // namespace railtab::lookup::detail

namespace railtab::lookup {

bool Table::has_creep_coefficients() const noexcept { return data_->coefficients.present; }

bool Table::query_creep_coefficients(Wheel wheel, const State& state, CreepCoefficients& out) const noexcept {
  using namespace detail;
  out = CreepCoefficients{};
  const TableData& d = *data_;
  out.n_slots = d.n_slots;
  if (!d.coefficients.present) return false;
  const int w = static_cast<int>(wheel);
  if (w != 0 && w != 1) {
    out.query_status = status::kInvalidInput;
    return true;
  }
  // The statuses and query bits are those of query(): the normal part's at this state.
  Result r;
  query(wheel, state, r);
  out.query_status = r.status;
  for (int s = 0; s < d.n_slots; ++s) out.status[s] = r.contact[s].part_status[kNormal];
  if (r.status & status::kInvalidInput) return true;
  AxisLoc loc[kNumVars];
  double v[kNumVars];
  table_variables(d, state, v);
  for (int k = 0; k < d.coefficients.n_dims; ++k) {
    const int var = d.coefficients.var[k];
    d.axis[var].locate_fast(v[var], loc[var]);
  }
  for (int s = 0; s < d.n_slots; ++s) {
    double c[kCoefficients];
    interpolate_creep_coefficients(d, w, loc, s, c);
    for (int f = 0; f < 3; ++f)
      for (int q = 0; q < 3; ++q) out.k[s][f][q] = c[f * 3 + q];
  }
  return true;
}

}  // namespace railtab::lookup
