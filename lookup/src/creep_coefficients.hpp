// SPDX-License-Identifier: Apache-2.0
// The normal part's linear creep coefficients (format 2.3, `creep_coefficient_<f>_<c>`;
// docs/lookup.md "Linear creep coefficients"): read at load, interpolated over the normal part's
// axes (y, roll, load) by the creep scales' own functions (interpolate_node_values in
// creep_map.cpp: multilinear; one_sided_node_values in jump_piece.hpp in a cell a located contact
// jump may cut: the normal part's pieces), never blended across a jump.
#pragma once

#include <cstddef>
#include <vector>

#include "creep_map.hpp"
#include "grid.hpp"

namespace railtab::lookup::detail {

class Hdf5File;
struct TableData;

inline constexpr int kCoefficients = 9;  // [fx, fy, mz] x [xi, eta, phi], force-major

struct CreepCoefficientData : NodeGrid {  // on the normal part's grid
  bool present = false;  // the table has them (format 2.3); false: 2.2 and older
  // value[wheel][(slot * nodes + node) * 9 + k]: the grid's coefficients.
  std::vector<double> value[2];
  // at_jump[wheel][(((slot * load nodes + load node) * jumps + jump) * 2 + side) * 9 + k]: the
  // one-sided values at the jumps (/jumps/<wheel>/normal/creep_coefficient_*), as JumpWheel's.
  std::vector<double> at_jump[2];
};

// Reads the nine datasets of both wheels (and of /jumps when the table has jumps; call after
// read_jumps). A table with none of them keeps `present` false; one with some but not all, or with
// a non-finite value, is refused (Hdf5File::fail).
void read_creep_coefficients(const Hdf5File& f, TableData& d);

// The slot's nine coefficients of wheel w at the located (y, roll, load) (loc indexed by Var).
void interpolate_creep_coefficients(const TableData& d, int w, const AxisLoc* loc, int slot,
                                    double out[kCoefficients]) noexcept;

}  // namespace railtab::lookup::detail
