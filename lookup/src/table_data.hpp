// In-memory layout of a loaded table, built by table_load.cpp and read by the query path.
//
// Parts of one wheel that are tabulated over the same axes (creep and wear always; geometry and
// normal when load is not swept) share one BLOCK, so a query walks each set of corners once.
// A block stores its grid nodes in C order (first axis slowest, the file's order without the
// slot axis), one RECORD of doubles per node:
//
//   record = [ part a: slot 0: out_0 .. out_{n-1} | slot 1: .. | part b: slot 0: .. | ... |
//              zero padding to a multiple of 4 doubles |
//              statuses as uint32: part a slot 0, part a slot 1, .., part b slot 0, ..,
//              padded with 0 to a multiple of 4 uint32 ]
//
// so one multilinear query reads 2^D records, each with unit stride, values in chunks of 4
// (register accumulators), statuses in the same cache lines as the values.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "grid.hpp"
#include "railtab/lookup.hpp"

namespace railtab::lookup::detail {

inline constexpr int kMaxDims = kNumVars;  // a block tabulates at most y, roll, load, xi, eta, phi
inline constexpr int kMaxValues = kMaxSlots * kNumOutputs;  // values in one record, at most
inline constexpr int kMaxStatuses = kMaxSlots * kNumParts;  // statuses in one record, at most
inline constexpr int kValueChunk = 4;   // values are accumulated (and padded) in chunks of this
inline constexpr int kStatusChunk = 4;  // statuses are folded (and padded) in chunks of this
static_assert(kMaxStatuses % kStatusChunk == 0, "status arrays hold whole chunks");

struct Block {
  int n_dims = 0;                     // tabulated axes (slot excluded), 0..kMaxDims
  int var[kMaxDims] = {};             // state variable (Var) of each dimension, in file order
  std::size_t stride[kMaxDims] = {};  // doubles between neighbouring nodes along each dimension
  int n_parts = 0;                    // parts stored in this block
  int part[kNumParts] = {};           // which (Part), in file order
  int n_values = 0;                   // sum over its parts of n_slots * outputs
  int values_padded = 0;              // n_values rounded up to a multiple of kValueChunk
  int n_status = 0;                   // n_parts * n_slots (stored padded to kStatusChunk)
  int record = 0;                     // doubles per node
  std::vector<double> data;           // nodes x record, see the layout above
};

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
  bool has_part[kNumParts] = {};      // part present (for both wheels)
  int n_blocks = 0;                   // blocks per wheel
  Block block[2][kNumParts];          // [wheel][block], same block structure for both wheels
  std::vector<AxisInfo> axes_info;    // public copy of the axes, file order
  std::vector<std::pair<std::string, double>> fixed_list;  // public copy of fixed_axes
};

}  // namespace railtab::lookup::detail
