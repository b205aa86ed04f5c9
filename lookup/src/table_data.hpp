// SPDX-License-Identifier: Apache-2.0
// In-memory layout of a loaded table, built by table_load.cpp and read by the query path.
//
// Parts of one wheel that are tabulated over the same axes (creep and wear always; geometry and
// normal when load is not swept) share one BLOCK, so a query walks each set of corners once.
// A block is SLOT-MAJOR: one grid per contact slot, one after the other, so a query for one
// slot (Table::query_slot) touches only that slot's outputs. Each slot grid stores its nodes in
// C order (first axis slowest, the file's order without the slot axis), one RECORD per node.
//
// The QUERY layout of a record (made at load from the file's arrays, block_layout.cpp):
//     [ values of part a, part b, .. | CELL statuses as uint32: part a, part b, .. |
//       zero padding to a multiple of 16 bytes ]
// where the cell status of a node is the status of the interpolation cell whose lowest corner
// it is: every bit but kEveryCorner's ORed over the cell's 2^D corner nodes, those ANDed
// (docs/lookup.md). A query reads the statuses of one record (the cell's corner 0) instead of
// folding 2^D of them, with the same result. Nodes on the last node of an axis start no
// cell; they keep their own status.
// Values are doubles, or floats when every value of the block (both wheels, its one-sided values
// at the jumps too) is exactly a float: format 2.2 stores the creep and wear outputs as float32
// (records.hpp; narrow_exact_blocks). The default creep + wear record is 6 values (the creep
// part's with its per-creepage normal force, wear) + 2 statuses: 56 bytes padded to 64 as
// doubles (1.15 MB per wheel and slot for the default scene), 32 as floats (0.58 MB). Strides
// and offsets are in bytes; the data start on a 64-byte boundary.
#pragma once

#include <cmath>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "creep_coefficients.hpp"
#include "creep_map.hpp"
#include "fast_path.hpp"
#include "grid.hpp"
#include "jump_side.hpp"
#include "railtab/lookup.hpp"
#include "records.hpp"

namespace railtab::lookup::detail {

// Status bits a cell (or a one-sided piece) carries only when EVERY node it is built from carries
// them: converged, and full_slip (a cell with one saturated corner is not a saturated state: a
// state at zero creepage must not read full_slip from its cell's far corners). Every other bit is
// ORed over the nodes (docs/lookup.md, "What a query returns").
inline constexpr StatusBits kEveryCorner = status::kConverged | status::kFullSlip;

inline constexpr int kMaxDims = kNumVars;  // a block tabulates at most y, roll, yaw, load, xi, eta, phi
inline constexpr int kMaxSlotValues = kNumOutputs;  // values in one slot record, at most

struct Block;
// Multilinear kernel for one block, chosen at load by the block's dimension and value counts:
// writes the values and part statuses of slots [slot_begin, slot_end) into
// contact[slot - slot_begin] (interpolate.hpp).
using LinearKernel = void (*)(const Block& block, const AxisLoc* loc, int slot_begin,
                              int slot_end, Contact* contact) noexcept;
struct BlockGradient;  // block_gradient.hpp
// Cubic (tensor Hermite) kernel, chosen at load by the block's value count (interpolate.hpp).
// grad: null, or one BlockGradient per slot that also receives the values' derivatives.
using CubicKernel = void (*)(const Block& block, const Axis* axes, const AxisLoc* loc,
                             int slot_begin, int slot_end, Contact* contact, BlockGradient* grad) noexcept;

struct Block {
  int n_dims = 0;                     // tabulated axes (slot excluded), 0..kMaxDims
  int var[kMaxDims] = {};             // state variable (Var) of each dimension, in file order
  int size[kMaxDims] = {};            // nodes along each dimension
  std::size_t stride[kMaxDims] = {};  // bytes between neighbouring nodes along each dimension
  int n_parts = 0;                    // parts stored in this block
  int part[kNumParts] = {};           // which (Part), in file order
  int n_values = 0;                   // values per slot record: sum over its parts of outputs
  int value_bytes = 8;                // bytes per value: 8 (double) or 4 (float)
  int record = 0;                     // bytes per record (record_bytes)
  int status_offset = 0;              // bytes before the cell statuses (n_values x value_bytes)
  int first_output = -1;              // Output of value 0 when the parts' outputs are one
                                      // contiguous run of Contact::value (always in format 1.0)
  int output_of[kMaxSlotValues] = {}; // Output of each value (the creep part's per-creepage
                                      // normal force goes to kNormalForce)
  std::size_t slot_size = 0;          // bytes per slot grid (nodes x record)
  LinearKernel linear = nullptr;      // multilinear kernel
  CubicKernel cubic = nullptr;        // tensor cubic Hermite kernel
  CubicKernel monotone = nullptr;     // monotone cubic kernel (no derivatives: grad unused)
  RecordBytes data;                   // n_slots grids, see the layout above
};

// Fills a block whose shape (dims, sizes, parts, values) is set with the query layout, double
// values: the node values values[(slot * nodes + node) * n_values + k] and node statuses
// status[(slot * nodes + node) * n_parts + p] (nodes in C order); folds the cell statuses, sets
// record, strides and kernels (block_layout.cpp).
void prepare_query_layout(Block& block, const std::vector<double>& values, const std::vector<StatusBits>& status,
                          int n_slots);

struct TableData;
// After the blocks and their one-sided values at the jumps are read (as doubles): the creep and
// wear block, when its values, both wheels and jump samples, are all exactly floats (format 2.2
// stores them as float32), is rewritten with float values (Block::value_bytes 4, the same
// statuses, strides scaled, kernels chosen again). Its multilinear sums then run in float
// (weighted_sum.hpp): within a few float roundings of the double sums, far below the stored
// rounding of 2^-20. RAILTAB_LOOKUP_NO_FLOAT_RECORDS=1 keeps every block double (to compare the
// two). block_layout.cpp.
void narrow_exact_blocks(TableData& d);

struct TableData {
  std::string path;                   // file loaded
  Method method = Method::kLinear;    // interpolation method
  std::string format_version;         // root attribute, e.g. "1.0"
  std::string scene_name;             // root attribute ("" if absent)
  int n_slots = 0;                    // contact slots (1..kMaxSlots)
  bool tabulated[kNumVars] = {};      // variable is an axis of the table
  Axis axis[kNumVars];                // its nodes (only where tabulated)
  bool fixed[kNumVars] = {};          // variable is listed in fixed_axes
  double fixed_value[kNumVars] = {};  // its value, SI
  int n_tabulated = 0;                // tabulated variables, and which (Var), in table order:
  int tabulated_var[kNumVars] = {};   // the query locates only these
  int n_located = 0;                  // tabulated variables placed on their axis (all but the
  int located_var[kNumVars] = {};     // creepages of normalised creep coordinates), which
  int n_clamped = 0;                  // tabulated creepages of normalised creep coordinates
  int clamped_var[kNumVars] = {};     // (only clamped to their physical range at first)
  int n_fixed = 0;                    // fixed variables, and which (Var)
  int fixed_var[kNumVars] = {};
  double fixed_tolerance[kNumVars] = {};  // |query - fixed_value| above this: kOutOfRange
  bool yaw_absent = false;            // the table has no yaw (no /axes/yaw): in fixed_var at 0, not
                                      // in fixed[] / fixed_list (a table computed at yaw 0)
  bool roll_equilibrium = false;      // roll follows the equilibrium (roll_mode): in fixed_var at 0,
                                      // not in fixed[] / fixed_list (not a fixed value of the table)
  bool yaw_even = false;              // root attribute yaw_symmetry = "even": the yaw axis holds the
                                      // non-negative half (every output is even in yaw); queried at |yaw|
  int n_absent = 0;                   // parts not in the table, and which (their outputs are 0)
  int absent_part[kNumParts] = {};
  bool has_part[kNumParts] = {};      // part present (for both wheels)
  int n_blocks = 0;                   // blocks per wheel
  Block block[2][kNumParts];          // [wheel][block], same block structure for both wheels
  std::vector<AxisInfo> axes_info;    // public copy of the axes, file order
  std::vector<std::pair<std::string, double>> fixed_list;  // public copy of fixed_axes
  bool checksums_verified = false;    // every dataset had Fletcher32, metadata checksummed
  CreepMap creep_map;                 // format 2.1 normalised creep coordinates (creep_map.hpp)
  int creep_block = -1;               // block holding the creep part (-1: none)
  bool has_jumps = false;             // the file has /jumps (format 2.1): one-sided jump cells
  bool load_controlled = false;       // format 2.1 or later (set with format_version): railtab
                                      // generate's values under load control (the low_confidence
                                      // rules that trust physics)
  JumpWheel jumps[2];                 // per wheel (jump_side.hpp)
  FastPath fast;                      // the fused query when the table has its shape (fast_path.hpp)
  CreepCoefficientData coefficients;  // format 2.3 linear creep coefficients (creep_coefficients.hpp)
  // Format 2.3's error map (/error_map): band edges and per (band, slot) the two comparisons.
  struct ErrorMap {
    bool present = false, exact = false, same_model = false;
    std::vector<double> band_start, band_end;                // [m]
    std::vector<ErrorStats> table_vs_model, model_vs_exact;  // [band * n_slots + slot]
  } error_map;
};

// The state's variables indexed by Var as the table's axes hold them: yaw folded to |yaw| on a
// table that stores half of a symmetric yaw axis (yaw_even).
inline void table_variables(const TableData& d, const State& s, double (&v)[kNumVars]) noexcept {
  v[kVarY] = s.y, v[kVarRoll] = s.roll, v[kVarLoad] = s.load, v[kVarXi] = s.xi, v[kVarEta] = s.eta, v[kVarPhi] = s.phi;
  v[kVarYaw] = d.yaw_even ? std::abs(s.yaw) : s.yaw;
}

// Reads /error_map when present (error_map.cpp); a table without one loads as before.
void read_error_map(const Hdf5File& f, TableData& d);

}  // namespace railtab::lookup::detail
