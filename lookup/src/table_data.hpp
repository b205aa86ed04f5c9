// In-memory layout of a loaded table, built by table_load.cpp and read by the query path.
//
// Parts of one wheel that are tabulated over the same axes (creep and wear always; geometry and
// normal when load is not swept) share one BLOCK, so a query walks each set of corners once.
// A block is SLOT-MAJOR: one grid per contact slot, one after the other, so a query for one
// slot (Table::query_slot) touches only that slot's outputs. Each slot grid stores its nodes in
// C order (first axis slowest, the file's order without the slot axis), one RECORD per node:
//
//   record = [ part a: out_0 .. out_{n-1} | part b: .. | zero padding to an even count |
//              statuses as uint32: part a, part b, .., padded with 0 to 4 uint32 (2 doubles) ]
//
// The default creep + wear block has 5 values + 1 pad + 2 status doubles = 64 bytes: one cache
// line per node, and the two corners along the fastest axis are two adjacent lines. A
// multilinear query reads 2^D records per slot, each with unit stride; statuses are folded with
// two 64-bit OR/AND per corner. The data start on a 64-byte boundary.
#pragma once

#include <cstddef>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "grid.hpp"
#include "railtab/lookup.hpp"

namespace railtab::lookup::detail {

inline constexpr int kMaxDims = kNumVars;  // a block tabulates at most y, roll, load, xi, eta, phi
inline constexpr int kMaxSlotValues = kNumOutputs;  // values in one slot record, at most
inline constexpr int kStatusDoubles = 2;  // 4 uint32 statuses (one per part, at most) per record
static_assert(kNumParts * sizeof(StatusBits) <= kStatusDoubles * sizeof(double),
              "every part's status fits in a record");

// std::allocator with 64-byte (cache line) alignment, so records never straddle more lines than
// their size requires.
template <class T>
struct CacheAligned {
  using value_type = T;
  static constexpr std::align_val_t kAlign{64};
  CacheAligned() = default;
  template <class U>
  CacheAligned(const CacheAligned<U>&) noexcept {}
  T* allocate(std::size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), kAlign)); }
  void deallocate(T* p, std::size_t n) noexcept { ::operator delete(p, n * sizeof(T), kAlign); }
  template <class U>
  bool operator==(const CacheAligned<U>&) const noexcept { return true; }
};

struct Block;
// Multilinear kernel for one block, chosen at load by the block's dimension count: writes the
// values and part statuses of slots [slot_begin, slot_end) into contact[slot - slot_begin]
// (interpolate.hpp).
using LinearKernel = void (*)(const Block& block, const AxisLoc* loc, int slot_begin,
                              int slot_end, Contact* contact) noexcept;

struct Block {
  int n_dims = 0;                     // tabulated axes (slot excluded), 0..kMaxDims
  int var[kMaxDims] = {};             // state variable (Var) of each dimension, in file order
  std::size_t stride[kMaxDims] = {};  // doubles between neighbouring nodes along each dimension
  int n_parts = 0;                    // parts stored in this block
  int part[kNumParts] = {};           // which (Part), in file order
  int n_values = 0;                   // values per slot record: sum over its parts of outputs
  int values_padded = 0;              // n_values rounded up to an even count
  int record = 0;                     // doubles per node: values_padded + kStatusDoubles
  int first_output = -1;              // Output of value 0 when the parts' outputs are one
                                      // contiguous run of Contact::value (always in format 1.0)
  std::size_t slot_size = 0;          // doubles per slot grid (nodes x record)
  LinearKernel linear = nullptr;      // multilinear kernel for n_dims
  std::vector<double, CacheAligned<double>> data;  // n_slots grids, see the layout above
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
  int n_tabulated = 0;                // tabulated variables, and which (Var), in table order:
  int tabulated_var[kNumVars] = {};   // the query locates only these
  int n_fixed = 0;                    // fixed variables, and which (Var)
  int fixed_var[kNumVars] = {};
  double fixed_tolerance[kNumVars] = {};  // |query - fixed_value| above this: kOutOfRange
  int n_absent = 0;                   // parts not in the table, and which (their outputs are 0)
  int absent_part[kNumParts] = {};
  bool has_part[kNumParts] = {};      // part present (for both wheels)
  int n_blocks = 0;                   // blocks per wheel
  Block block[2][kNumParts];          // [wheel][block], same block structure for both wheels
  std::vector<AxisInfo> axes_info;    // public copy of the axes, file order
  std::vector<std::pair<std::string, double>> fixed_list;  // public copy of fixed_axes
  bool checksums_verified = false;    // every dataset had Fletcher32, metadata checksummed
};

}  // namespace railtab::lookup::detail
