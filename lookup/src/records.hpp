// SPDX-License-Identifier: Apache-2.0
// Storage of the query records (layout in table_data.hpp): bytes, cache-line aligned, holding
// each value as a double, or as a float in the creep and wear block when every value of it is
// exactly a float (format 2.2 stores the creep and wear outputs as float32, docs/table-format.md
// "Storage precision"): half the bytes per record. The multilinear sums of float records run in
// float (weighted_sum.hpp); the others convert to double (exact).
// Values are read through memcpy (records are bytes, whatever type they hold).
#pragma once

#include <cstddef>
#include <cstring>
#include <new>
#include <vector>

namespace railtab::lookup::detail {

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

using RecordBytes = std::vector<unsigned char, CacheAligned<unsigned char>>;
using RecordPtr = const unsigned char*;

// Bytes of a query record: n_values values of value_bytes (8 or 4) each, then n_parts uint32
// statuses, padded to 16 bytes (SSE2 pairs; the default creep + wear record: 64 B as doubles,
// 32 B as floats, so records never straddle a cache line).
constexpr int record_bytes(int n_values, int value_bytes, int n_parts) noexcept {
  return (n_values * value_bytes + n_parts * 4 + 15) / 16 * 16;
}

// Value k of a record holding T (double or float), as a double (exact).
template <class T>
inline double record_value(RecordPtr r, int k) noexcept {
  T v;
  std::memcpy(&v, r + static_cast<std::size_t>(k) * sizeof(T), sizeof v);
  return v;
}

}  // namespace railtab::lookup::detail
